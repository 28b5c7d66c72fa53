// `libcam reproject` and `libcam fit --observations` (and info and dataset given a
// workspace's sparse/ folder), run as a user runs them, on COLMAP text models this test writes: a pinhole camera whose pixels are worked out by
// x = f X / Z + cx (plus COLMAP's half pixel), with a known pattern of noise.

#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.hpp"
#include "temp_dir.hpp"

namespace {

using libcam::test::run_libcam;
using libcam::test::TempDir;
using Json = nlohmann::json;

constexpr double kF = 800.0, kCx = 319.5, kCy = 239.5;  // OpenCV's pixels; COLMAP's are +0.5

struct Point {
    double x, y, z;
};

// Six images of 150 points: image i is the camera moved by (0.1 i, 0, 0), looking down +Z.
// Each observation gets a fixed pseudo-random offset of up to 0.3 px per axis.
// `colmap_centres`: the pixels written as COLMAP writes them (+0.5), or as OpenCV's.
void write_model(const std::filesystem::path& folder, bool colmap_centres) {
    std::filesystem::create_directories(folder);
    std::vector<Point> points;
    for (int i = 0; i < 150; ++i) {
        points.push_back({-1.0 + 0.013 * i, -0.6 + 0.0081 * ((i * 37) % 150), 4.0 + 0.01 * ((i * 53) % 100)});
    }
    const double shift = colmap_centres ? 0.5 : 0.0;
    std::ostringstream images;
    images.precision(17);
    std::vector<std::string> tracks(points.size());
    for (int image = 0; image < 6; ++image) {
        const double tx = -0.1 * image;  // t = -R C with C = (0.1 i, 0, 0)
        images << image + 1 << " 1 0 0 0 " << tx << " 0 0 1 img" << image << ".png\n";
        for (std::size_t p = 0; p < points.size(); ++p) {
            const double noise_x = 0.3 * std::sin(1.7 * (p + 1) * (image + 3));
            const double noise_y = 0.3 * std::cos(2.3 * (p + 2) * (image + 1));
            const double x = kF * (points[p].x + tx) / points[p].z + kCx + shift + noise_x;
            const double y = kF * points[p].y / points[p].z + kCy + shift + noise_y;
            images << (p ? " " : "") << x << " " << y << " " << p + 1;
            tracks[p] += " " + std::to_string(image + 1) + " " + std::to_string(p);
        }
        images << "\n";
    }
    std::ostringstream points_text;
    points_text.precision(17);
    for (std::size_t p = 0; p < points.size(); ++p) {
        points_text << p + 1 << " " << points[p].x << " " << points[p].y << " " << points[p].z << " 0 0 0 0.3"
                    << tracks[p] << "\n";
    }
    libcam::test::write_whole_file(folder / "cameras.txt", "1 PINHOLE 640 480 800 800 320 240\n");
    libcam::test::write_whole_file(folder / "images.txt", images.str());
    libcam::test::write_whole_file(folder / "points3D.txt", points_text.str());
}

}  // namespace

TEST_CASE("libcam reproject --json: the statistics under their keys, and the pixel-centre check quiet on a right model") {
    TempDir dir;
    write_model(dir / "model", true);
    const auto result = run_libcam({"reproject", (dir / "model").string(), "--json", "--worst", "3"});
    REQUIRE(result.exit_code == 0);
    const Json j = Json::parse(result.out);
    CHECK(j["count"] == 900);
    CHECK(j["observations"] == 900);
    CHECK(j["tool"] == "COLMAP");
    // The noise is at most 0.3 px per axis: |d| < 0.43.
    CHECK(j["max_px"].get<double>() < 0.3 * std::sqrt(2.0) + 1e-9);
    CHECK(j["rms_px"].get<double>() > 0.1);
    for (const char* key : {"mean_px", "median_px", "p99_px"}) CHECK(j[key].get<double>() <= j["max_px"].get<double>());
    REQUIRE(j["per_view"].size() == 6);
    CHECK(j["per_view"][0]["name"] == "img0.png");
    CHECK(j["per_view"][0]["count"] == 150);
    CHECK(j["per_view"][0].contains("rms_px"));
    CHECK(j["per_view"][0].contains("mean_px"));
    CHECK(j["reported"]["mean_point_error_px"].get<double>() == Approx(0.3));
    CHECK(j["recomputed"].contains("mean_point_error_px"));
    CHECK(j["convention_check"]["suspect"] == false);
    CHECK(std::abs(j["convention_check"]["best_shift_px"][0].get<double>()) < 0.1);
    CHECK(j["worst"].size() == 3);
    CHECK_FALSE(j.contains("weighted_rms_px"));  // COLMAP weighs no observation
}

TEST_CASE("libcam reproject finds a COLMAP model whose pixels were written in OpenCV's convention") {
    TempDir dir;
    write_model(dir / "model", false);
    const auto result = run_libcam({"reproject", (dir / "model").string(), "--json"});
    REQUIRE(result.exit_code == 0);
    const Json j = Json::parse(result.out);
    CHECK(j["convention_check"]["suspect"] == true);
    CHECK(j["convention_check"]["best_shift_px"][0].get<double>() == Approx(-0.5).margin(0.05));
    CHECK(j["convention_check"]["best_shift_px"][1].get<double>() == Approx(-0.5).margin(0.05));
    const auto text = run_libcam({"reproject", (dir / "model").string()});
    CHECK(text.out.find("SUSPECT: the observations fit the other pixel-centre convention") != std::string::npos);
}

TEST_CASE("libcam reproject --observations-out and --heatmap write their files") {
    TempDir dir;
    write_model(dir / "model", true);
    const auto csv = dir / "residuals.csv";
    const auto png = dir / "heatmap.png";
    const auto result =
        run_libcam({"reproject", (dir / "model").string(), "--observations-out", csv.string(), "--heatmap", png.string()});
    REQUIRE(result.exit_code == 0);
    std::istringstream rows(libcam::test::read_whole_file(csv));
    std::string line;
    std::getline(rows, line);
    CHECK(line == "view,point,observed_x,observed_y,projected_x,projected_y,error_px,inlier");
    std::getline(rows, line);
    // The first observation: point 1 at (-1, -0.6, 4) in img0, projected at COLMAP's
    // (800 * -1 / 4 + 320, 800 * -0.6 / 4 + 240) = (120, 120).
    std::vector<std::string> fields;
    std::stringstream fields_in(line);
    for (std::string field; std::getline(fields_in, field, ',');) fields.push_back(field);
    REQUIRE(fields.size() == 8);
    CHECK(fields[0] == "img0.png");
    CHECK(fields[1] == "1");
    CHECK(std::stod(fields[4]) == Approx(120.0).margin(1e-9));
    CHECK(std::stod(fields[5]) == Approx(120.0).margin(1e-9));
    CHECK(fields[7] == "1");
    std::size_t count = 2;
    while (std::getline(rows, line)) ++count;
    CHECK(count == 1 + 900);
    const std::string picture = libcam::test::read_whole_file(png);
    CHECK(picture.substr(1, 3) == "PNG");
}

TEST_CASE("info, reproject and dataset given a workspace's sparse/ take its one model, and ask to name one of several") {
    TempDir dir;
    const std::string sparse = (dir / "sparse").string();
    write_model(dir / "sparse" / "0", true);
    const auto info = run_libcam({"info", sparse, "--json"});
    REQUIRE(info.exit_code == 0);
    CHECK(Json::parse(info.out).at("cameras").size() == 6);  // the six images of write_model
    const auto reproject = run_libcam({"reproject", sparse, "--json"});
    REQUIRE(reproject.exit_code == 0);
    CHECK(Json::parse(reproject.out)["count"] == 900);
    const auto dataset = run_libcam({"dataset", sparse, "-o", (dir / "out").string(), "--no-images", "--text"});
    REQUIRE(dataset.exit_code == 0);
    CHECK(libcam::test::read_whole_file(dir / "out" / "sparse" / "0" / "cameras.txt")
              .find("1 PINHOLE 640 480 800 800 320 240") != std::string::npos);
    // The images beside the model are the workspace's images/ (sparse/0's grandparent's).
    const auto no_images = run_libcam({"dataset", sparse, "-o", (dir / "out2").string()});
    CHECK(no_images.exit_code != 0);
    CHECK(no_images.err.find((dir / "images").string() + ": no such images folder") != std::string::npos);

    // COLMAP's mapper numbers its models 0, 1, 2, ...: 10 comes after 2.
    write_model(dir / "sparse" / "10", true);
    write_model(dir / "sparse" / "2", true);
    std::filesystem::create_directories(dir / "sparse" / "notes");  // a folder without a model is not one
    const std::string several = sparse + " holds 3 COLMAP models (0, 2, 10): name one, e.g. " + sparse + "/0";
    for (const char* command : {"info", "reproject"}) {
        const auto refused = run_libcam({command, sparse});
        INFO(command);
        CHECK(refused.exit_code == 1);
        CHECK(refused.err.find(several) != std::string::npos);
        CHECK(std::count(refused.err.begin(), refused.err.end(), '\n') == 1);
    }
    const auto refused = run_libcam({"dataset", sparse, "-o", (dir / "out3").string(), "--no-images"});
    CHECK(refused.exit_code == 1);
    CHECK(refused.err.find(several) != std::string::npos);
    CHECK(run_libcam({"info", sparse + "/2"}).exit_code == 0);
}

TEST_CASE("libcam reproject refuses what it cannot read, in one line") {
    TempDir dir;
    write_model(dir / "model", true);
    const auto no_camera = run_libcam({"reproject", (dir / "model").string(), "--camera", "7"});
    CHECK(no_camera.exit_code == 2);
    CHECK(no_camera.err.find("--camera: no camera '7'") != std::string::npos);
    libcam::test::write_whole_file(dir / "cam.json",
                                   R"({"image_size": [640, 480], "K": [[500, 0, 320], [0, 500, 240], [0, 0, 1]]})");
    const auto camera_only = run_libcam({"reproject", (dir / "cam.json").string()});
    CHECK(camera_only.exit_code == 1);
    CHECK(camera_only.err.find("cam.json: libcam JSON holds no observations") != std::string::npos);
    CHECK(std::count(camera_only.err.begin(), camera_only.err.end(), '\n') == 1);
}

TEST_CASE("libcam fit --observations chooses the pinhole that made the model, judged on held-out views") {
    TempDir dir;
    write_model(dir / "model", true);
    const auto out = dir / "chosen.json";
    const auto result = run_libcam({"fit", "--observations", (dir / "model").string(), "--model", "PINHOLE,OPENCV4",
                                    "--folds", "3", "--json", "-o", out.string()});
    REQUIRE(result.exit_code == 0);
    const Json j = Json::parse(result.out);
    REQUIRE(j["candidates"].size() == 2);
    for (const Json& c : j["candidates"]) {
        for (const char* key : {"model", "params", "rms_px", "heldout_rms_px"}) CHECK(c.contains(key));
    }
    CHECK(j["chosen"]["model"] == "PINHOLE");
    CHECK(j["chosen"]["K"][0][0].get<double>() == Approx(kF).margin(1.0));
    CHECK(j["chosen"]["K"][0][2].get<double>() == Approx(kCx).margin(1.0));
    CHECK(j["folds"] == 3);
    CHECK(std::filesystem::exists(out));
}
