// The command-line program with lens distortion: `libcam convert` between every format
// that can hold the model, `libcam rays --from FILE` through the lens, and pixels with
// no ray reported as {"valid": false, "direction": null}; `libcam models`, the lens
// table, against the models' own definitions and against docs/lens-models.md.

#include <algorithm>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "libcam/lens/lens_model.hpp"

using libcam::test::read_whole_file;
using libcam::test::run_libcam;
using libcam::test::TempDir;
using libcam::test::write_whole_file;
using nlohmann::json;

namespace {

// OPENCV4 with k1 = -0.5 only, fx = fy = 500, cx = 499.5, cy = 374.5, 1000x750, at the
// origin looking down +z with OpenCV axes (R = I, t = 0).
// Radially, r_d(r) = r (1 - 0.5 r^2): increasing up to r = sqrt(2/3), where it reaches
// (2/3) sqrt(2/3) = 0.5443. Pixels farther than that (x 500) from the centre have no ray.
const char* kBarrelJson = R"({
  "model": "OPENCV4",
  "image_size": [1000, 750],
  "K": [[500, 0, 499.5], [0, 500, 374.5], [0, 0, 1]],
  "dist": [-0.5, 0, 0, 0],
  "R": [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
  "t": [0, 0, 0]
})";

// r with r (1 - 0.5 r^2) = target on [0, sqrt(2/3)], by bisection (independent of libcam).
double undistorted_radius(double target) {
    double low = 0.0, high = std::sqrt(2.0 / 3.0);
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (low + high);
        (mid * (1 - 0.5 * mid * mid) < target ? low : high) = mid;
    }
    return 0.5 * (low + high);
}

json rays_json(const std::vector<std::string>& args) {
    const auto result = run_libcam(args);
    INFO(result.describe());
    REQUIRE(result.exit_code == 0);
    return json::parse(result.out);
}

}  // namespace

TEST_CASE("rays through a distorted lens: inside the fold a ray, past it valid false and direction null") {
    TempDir dir;
    write_whole_file(dir / "barrel.json", kBarrelJson);
    // Pixel 250 px right of the centre: distorted radius 0.5; pixel 300 px right: 0.6 > 0.5443.
    const json out = rays_json({"rays", "--from", (dir / "barrel.json").string(), "--json", "--pixels", "749.5,374.5",
                                "799.5,374.5", "499.5,374.5"});
    const json& rays = out.at("rays");
    REQUIRE(rays.size() == 3);

    const double r = undistorted_radius(0.5);  // the ray is (r, 0, 1), normalised
    const double norm = std::hypot(r, 1.0);
    REQUIRE(rays[0].at("valid") == true);
    REQUIRE(std::abs(rays[0].at("direction")[0].get<double>() - r / norm) < 1e-12);
    REQUIRE(std::abs(rays[0].at("direction")[1].get<double>()) < 1e-12);
    REQUIRE(std::abs(rays[0].at("direction")[2].get<double>() - 1 / norm) < 1e-12);
    // Not a look-at camera: no look-at direction.
    REQUIRE(rays[0].at("direction_look_at").is_null());

    REQUIRE(rays[1].at("valid") == false);
    REQUIRE(rays[1].at("direction").is_null());

    REQUIRE(rays[2].at("valid") == true);  // the principal point looks straight ahead
    REQUIRE(std::abs(rays[2].at("direction")[2].get<double>() - 1.0) < 1e-15);
}

TEST_CASE("convert carries distortion through json, opencv-yaml, opencv-xml and cameramodel") {
    TempDir dir;
    write_whole_file(dir / "barrel.json", kBarrelJson);
    std::string previous = (dir / "barrel.json").string();
    for (const std::string format : {"opencv-yaml", "opencv-xml", "cameramodel", "json"}) {
        const std::string extension = format == "opencv-yaml" ? ".yaml"
                                      : format == "opencv-xml" ? ".xml"
                                      : format == "cameramodel" ? ".cameramodel"
                                                                : ".json";
        const std::string next = (dir / ("chain" + extension)).string();
        const auto result = run_libcam({"convert", "--from", previous, "--to", format, "-o", next});
        INFO(format << "\n" << result.describe());
        REQUIRE(result.exit_code == 0);
        previous = next;
    }
    // The end of the chain, as JSON, holds the same model and numbers as the start.
    const auto result = run_libcam({"convert", "--from", previous});
    REQUIRE(result.exit_code == 0);
    const json end = json::parse(result.out);
    REQUIRE(end.at("model") == "OPENCV4");
    REQUIRE(end.at("dist") == json::parse("[-0.5, 0, 0, 0]"));
    REQUIRE(end.at("K") == json::parse("[[500, 0, 499.5], [0, 500, 374.5], [0, 0, 1]]"));
    REQUIRE(end.at("fov_axes").empty());  // a lens with distortion is no look-at camera
}

TEST_CASE("a format that cannot hold the model is an error, and writes nothing") {
    TempDir dir;
    const std::string fisheye = R"({"model": "FISHEYE", "image_size": [800, 800],
      "K": [[300, 0, 399.5], [0, 300, 399.5], [0, 0, 1]], "dist": [0.1, 0.01, 0, 0],
      "R": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "t": [0, 0, 0]})";
    write_whole_file(dir / "fisheye.json", fisheye);
    for (const std::string format : {"cameramodel", "gl"}) {
        const std::string target = (dir / ("out." + format)).string();
        const auto result = run_libcam({"convert", "--from", (dir / "fisheye.json").string(), "--to", format, "-o", target});
        INFO(format << "\n" << result.describe());
        REQUIRE(result.exit_code == 1);
        REQUIRE(result.out.empty());
        REQUIRE_THAT(result.err, Catch::Matchers::Contains("FISHEYE"));
        REQUIRE_FALSE(std::filesystem::exists(target));
    }
}

TEST_CASE("a behind-the-camera fisheye ray comes back through rays") {
    // FISHEYE with zero coefficients is the equidistant lens: theta_d = theta, so a pixel
    // at distance f * theta from the centre looks theta from the optical axis. With
    // f = 100 and the pixel 200 px right of the centre, theta = 2 rad (past 90 degrees):
    // the ray is (sin 2, 0, cos 2), cos 2 < 0.
    TempDir dir;
    write_whole_file(dir / "equidistant.json", R"({"model": "FISHEYE", "image_size": [800, 800],
      "K": [[100, 0, 399.5], [0, 100, 399.5], [0, 0, 1]], "dist": [0, 0, 0, 0],
      "R": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "t": [0, 0, 0]})");
    const json out = rays_json({"rays", "--from", (dir / "equidistant.json").string(), "--json", "--pixels", "599.5,399.5"});
    const json& ray = out.at("rays")[0];
    REQUIRE(ray.at("valid") == true);
    REQUIRE(std::abs(ray.at("direction")[0].get<double>() - std::sin(2.0)) < 1e-12);
    REQUIRE(std::abs(ray.at("direction")[1].get<double>()) < 1e-12);
    REQUIRE(std::abs(ray.at("direction")[2].get<double>() - std::cos(2.0)) < 1e-12);
}

namespace {

json models_json() {
    const auto result = run_libcam({"models", "--json"});
    INFO(result.describe());
    REQUIRE(result.exit_code == 0);
    return json::parse(result.out);
}

const json& model_named(const json& models, const std::string& name) {
    for (const json& model : models) {
        if (model.at("name") == name) return model;
    }
    FAIL("libcam models --json has no model " << name);
    throw std::logic_error("unreachable");
}

// The cells of a markdown table's row, trimmed.
std::vector<std::string> cells(const std::string& row) {
    std::vector<std::string> out;
    std::istringstream in(row.substr(1));
    for (std::string cell; std::getline(in, cell, '|');) {
        const std::size_t first = cell.find_first_not_of(' '), last = cell.find_last_not_of(' ');
        out.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
    }
    return out;
}

}  // namespace

TEST_CASE("models --json: every model, with the names and coefficients their own definitions give") {
    const json models = models_json();
    // Every row of the lens table, in its order (a new model is listed without editing this test;
    // the names of the models below are checked against their own definitions).
    std::vector<std::string> expected;
    for (const libcam::LensInfo& info : libcam::lens_models()) expected.emplace_back(info.name);
    REQUIRE(models.size() == expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) CHECK(models[i].at("name") == expected[i]);

    // OpenCV's calib3d documentation: distCoeffs (k1, k2, p1, p2[, k3[, k4, k5, k6[, s1, s2,
    // s3, s4[, tauX, tauY]]]]); cv::fisheye's D: (k1, k2, k3, k4).
    const json& opencv8 = model_named(models, "OPENCV8");
    CHECK(opencv8.at("coefficients") == json({"k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6"}));
    CHECK(opencv8.at("coefficient_count") == 8);
    CHECK(opencv8.at("opencv") == "cv::projectPoints");
    CHECK(model_named(models, "OPENCV14").at("coefficients") ==
          json({"k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6", "s1", "s2", "s3", "s4", "tauX", "tauY"}));
    const json& fisheye = model_named(models, "FISHEYE");
    CHECK(fisheye.at("coefficients") == json({"k1", "k2", "k3", "k4"}));
    CHECK(fisheye.at("opencv") == "cv::fisheye::projectPoints");
    CHECK(model_named(models, "UCM").at("opencv") == "cv::omnidir::projectPoints");

    // COLMAP's models.h: OPENCV (k1 k2 p1 p2), FULL_OPENCV (k1 k2 p1 p2 k3 k4 k5 k6),
    // OPENCV_FISHEYE (k1 k2 k3 k4), FOV (omega).
    CHECK(model_named(models, "OPENCV4").at("colmap") == "OPENCV");
    CHECK(opencv8.at("colmap") == "FULL_OPENCV");
    CHECK(fisheye.at("colmap") == "OPENCV_FISHEYE");
    CHECK(model_named(models, "FOV").at("colmap") == "FOV");
    CHECK(model_named(models, "OPENCV5").at("colmap") == "");  // COLMAP has no 5-coefficient OpenCV model

    // Kalibr's camera-distortion pairs and basalt's camera types.
    CHECK(model_named(models, "OPENCV4").at("kalibr") == "pinhole-radtan");
    CHECK(fisheye.at("kalibr") == "pinhole-equi");
    CHECK(model_named(models, "MEI").at("kalibr") == "omni-radtan");
    CHECK(fisheye.at("basalt") == "kb4");
    CHECK(model_named(models, "DOUBLE_SPHERE").at("basalt") == "ds");

    // mrcal.h: LENSMODEL_CAHVORE keeps its linearity in its name, the splined model its
    // order, Nx, Ny and fov_x_deg; mrcal has no fisheye of OpenCV's.
    const json& cahvore = model_named(models, "CAHVORE");
    CHECK(cahvore.at("mrcal") == "LENSMODEL_CAHVORE");
    CHECK(cahvore.at("mrcal_in_name") == json({"linearity"}));
    const json& splined = model_named(models, "SPLINED_STEREOGRAPHIC");
    CHECK(splined.at("mrcal_in_name") == json({"order", "Nx", "Ny", "fov_x_deg"}));
    CHECK(splined.at("coefficient_count").is_null());  // set by Nx and Ny
    CHECK(fisheye.at("mrcal") == "");
    CHECK(model_named(models, "OPENCV12").at("mrcal_in_name") == json::array());

    // A perspective projection divides by Z: nothing behind the camera. An equidistant
    // fisheye and a stereographic projection reach past 90 degrees (mrcal's
    // can_project_behind_camera for LENSMODEL_STEREOGRAPHIC).
    CHECK(model_named(models, "PINHOLE").at("sees_behind_camera") == false);
    CHECK(opencv8.at("sees_behind_camera") == false);
    CHECK(fisheye.at("sees_behind_camera") == true);
    CHECK(model_named(models, "STEREOGRAPHIC").at("sees_behind_camera") == true);
    // The pinhole inverts by a formula; OpenCV's distortion has no closed-form inverse
    // (cv::undistortPoints iterates).
    CHECK(model_named(models, "PINHOLE").at("inverse") == "closed-form");
    CHECK(opencv8.at("inverse") == "solved");

    // OpenCV's longer coefficient vectors extend the shorter: one family, the pinhole's,
    // ranked by length. MEI is the unified model (UCM) with OpenCV's distortion after it.
    int rank = -1;
    for (const char* name : {"PINHOLE", "OPENCV4", "OPENCV5", "OPENCV8", "OPENCV12", "OPENCV14"}) {
        const json& model = model_named(models, name);
        CHECK(model.at("family") == "PINHOLE");
        CHECK(model.at("family_rank").get<int>() > rank);
        rank = model.at("family_rank").get<int>();
    }
    CHECK(model_named(models, "MEI").at("family") == "UCM");
    CHECK(model_named(models, "MEI").at("family_rank") == 1);
}

TEST_CASE("models: a table with a row per model, --markdown a table of twelve columns, bad flags refused") {
    const auto text = run_libcam({"models"});
    REQUIRE(text.exit_code == 0);
    CHECK(text.out.find("SPLINED_STEREOGRAPHIC  ") != std::string::npos);
    CHECK(text.out.find("LENSMODEL_SPLINED_STEREOGRAPHIC_order=..._Nx=..._Ny=..._fov_x_deg=...") != std::string::npos);

    const auto markdown = run_libcam({"models", "--markdown"});
    REQUIRE(markdown.exit_code == 0);
    std::istringstream lines(markdown.out);
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(lines, line);) {
        INFO(line);
        rows.push_back(cells(line));
        CHECK(rows.back().size() == 12);  // a '|' inside a cell would split it
    }
    REQUIRE(rows.size() == 2 + libcam::lens_models().size());  // titles, rule, a row per model
    CHECK(rows[0][0] == "model");
    // CAHVORE, the 20th model: mrcal's name with "..." for its linearity (mrcal.h's
    // mrcal_lensmodel_name_unconfigured), its column after OpenCV's.
    const std::vector<std::string>& cahvore = rows[2 + 19];
    CHECK(cahvore[0] == "CAHVORE");
    CHECK(cahvore[1] == "alpha beta r0 r1 r2 e0 e1 e2 linearity");
    CHECK(cahvore[7] == "`LENSMODEL_CAHVORE_linearity=...`");

    const auto both = run_libcam({"models", "--json", "--markdown"});
    CHECK(both.exit_code == 2);
    CHECK(std::count(both.err.begin(), both.err.end(), '\n') == 1);
}

// The first line where two texts differ, both ways, for a failure message.
std::string first_difference(const std::string& docs, const std::string& program) {
    std::istringstream a(docs), b(program);
    std::string line_a, line_b;
    for (int line = 1;; ++line) {
        const bool more_a = static_cast<bool>(std::getline(a, line_a));
        const bool more_b = static_cast<bool>(std::getline(b, line_b));
        if (!more_a && !more_b) return "none";
        if (!more_a || !more_b || line_a != line_b) {
            return "line " + std::to_string(line) + " of the table:\n  docs:    " + (more_a ? line_a : "(the end)") +
                   "\n  program: " + (more_b ? line_b : "(the end)");
        }
    }
}

TEST_CASE("docs/lens-models.md's table of models is what `libcam models --markdown` prints") {
    const auto result = run_libcam({"models", "--markdown"});
    {
        INFO(result.describe());
        REQUIRE(result.exit_code == 0);
    }
    const std::string docs = read_whole_file(LIBCAM_DOCS_DIR "/lens-models.md");
    const std::string begin = "<!-- generated by: libcam models --markdown -->\n";
    const std::string end = "<!-- end of generated table -->";
    const std::size_t from = docs.find(begin), to = docs.find(end);
    REQUIRE(from != std::string::npos);
    REQUIRE(to != std::string::npos);
    REQUIRE(from < to);
    INFO("docs/lens-models.md's table is stale. Regenerate it: replace the lines between its \"" +
         begin.substr(0, begin.size() - 1) + "\" and \"" + end +
         "\" comments with what `build/tools/libcam models --markdown` prints.");
    const std::string table = docs.substr(from + begin.size(), to - from - begin.size());
    CHECK(first_difference(table, result.out) == "none");
}
