// `libcam dataset` and NeRF's transforms.json, run as a user runs it: a transforms.json of
// OPENCV per-frame intrinsics (with nerfstudio's applied_transform and applied_scale) to
// NeRF's layout and to a COLMAP model, and a COLMAP model to NeRF's layout. The source's
// poses are converted here by hand (OpenGL's camera-to-world, the move undone); the
// images' blobs are drawn through the OPENCV formula written out here and found at the
// new pinhole's fx X / Z + cx.

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "cli_runner.hpp"
#include "real_cameras.hpp"
#include "libcam/io/camera_file.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using libcam::test::run_libcam;
using libcam::test::TempDir;
using Json = nlohmann::json;

Json run_json(const std::vector<std::string>& args) {
    const libcam::test::CliResult result = run_libcam(args);
    INFO(result.describe());
    REQUIRE(result.exit_code == 0);
    return Json::parse(result.out);
}

// An OPENCV camera in transforms.json's numbers (pixel corner at 0).
struct OpenCvFrame {
    double fl_x, fl_y, cx, cy, k1, k2, p1, p2;

    // OpenCV's pixel (centre at 0) of a camera-frame point.
    cv::Point2d project(double X, double Y, double Z) const {
        const double a = X / Z, b = Y / Z, r2 = a * a + b * b, radial = 1 + k1 * r2 + k2 * r2 * r2;
        const double xd = a * radial + 2 * p1 * a * b + p2 * (r2 + 2 * a * a);
        const double yd = b * radial + p1 * (r2 + 2 * b * b) + 2 * p2 * a * b;
        return {fl_x * xd + cx - 0.5, fl_y * yd + cy - 0.5};
    }
    Json keys() const {
        return {{"w", 96}, {"h", 72}, {"fl_x", fl_x}, {"fl_y", fl_y}, {"cx", cx}, {"cy", cy},
                {"k1", k1}, {"k2", k2}, {"p1", p1}, {"p2", p2}};
    }
};

// The camera-frame points each image shows as blobs, spread over the image.
const std::vector<cv::Point3d> kBlobs = {{0, 0, 1}, {-0.35, -0.25, 1}, {0.4, 0.28, 1}, {0.3, -0.3, 1}, {-0.4, 0.3, 1}};

cv::Mat blob_image(const OpenCvFrame& lens) {
    cv::Mat image(72, 96, CV_64F, cv::Scalar(0));
    for (const cv::Point3d& p : kBlobs) {
        const cv::Point2d at = lens.project(p.x, p.y, p.z);
        for (int y = 0; y < image.rows; ++y) {
            for (int x = 0; x < image.cols; ++x) {
                image.at<double>(y, x) += std::exp(-((x - at.x) * (x - at.x) + (y - at.y) * (y - at.y)) / (2 * 1.2 * 1.2));
            }
        }
    }
    cv::Mat out;
    image.convertTo(out, CV_16U, 65535.0);
    return out;
}

// The intensity centroid within 4 pixels of `near`.
cv::Point2d centroid(const cv::Mat& image, const cv::Point2d& near) {
    const int cx = static_cast<int>(std::lround(near.x)), cy = static_cast<int>(std::lround(near.y));
    double sum = 0, sx = 0, sy = 0;
    for (int y = cy - 4; y <= cy + 4; ++y) {
        for (int x = cx - 4; x <= cx + 4; ++x) {
            const double w = image.at<std::uint16_t>(y, x);
            sum += w;
            sx += w * x;
            sy += w * y;
        }
    }
    return {sx / sum, sy / sum};
}

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

// The source: nerfstudio's COLMAP axes swap turned 90 degrees more about z (A), moved by b,
// scaled by 2; three frames, the first two with one camera.
const Mat3 kA = (Mat3() << 0, -1, 0, 0, 0, 1, -1, 0, 0).finished();
const Vec3 kB(0.5, -1, 2);
constexpr double kScale = 2;

struct SourceFrame {
    std::string name;
    OpenCvFrame lens;
    Eigen::Matrix4d transform;  // camera-to-world, OpenGL's axes, the moved world
};

std::vector<SourceFrame> source_frames() {
    const OpenCvFrame one{70, 71, 48.3, 35.8, -0.2, 0.05, 0.001, -0.002};
    const OpenCvFrame two{60, 60.5, 47.9, 36.4, 0.1, -0.02, -0.0015, 0.0005};
    const auto transform = [](double angle, const Vec3& centre) {
        Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
        m.topLeftCorner<3, 3>() = Eigen::AngleAxisd(angle, Vec3(0.3, 0.9, -0.2).normalized()).toRotationMatrix();
        m.topRightCorner<3, 1>() = centre;
        return m;
    };
    return {{"a.png", one, transform(0.4, Vec3(1, 2, 3))},
            {"b.png", one, transform(-0.7, Vec3(-2, 0.5, 4))},
            {"sub/c.png", two, transform(1.9, Vec3(0.25, -3, 1))}};
}

Json matrix_json(const Eigen::MatrixXd& m) {
    Json rows = Json::array();
    for (long r = 0; r < m.rows(); ++r) {
        Json row = Json::array();
        for (long c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
        rows.push_back(row);
    }
    return rows;
}

void write_source(const fs::path& folder) {
    Json frames = Json::array();
    for (const SourceFrame& frame : source_frames()) {
        Json keys = frame.lens.keys();
        keys["file_path"] = "./images/" + frame.name;
        keys["transform_matrix"] = matrix_json(frame.transform);
        frames.push_back(keys);
        fs::create_directories((folder / "images" / frame.name).parent_path());
        REQUIRE(cv::imwrite((folder / "images" / frame.name).string(), blob_image(frame.lens)));
    }
    Eigen::Matrix<double, 3, 4> applied;
    applied << kA, kB;
    const Json transforms = {{"camera_model", "OPENCV"}, {"applied_transform", matrix_json(applied)},
                             {"applied_scale", kScale}, {"frames", frames}};
    libcam::test::write_whole_file(folder / "transforms.json", transforms.dump(2));
}

double max_difference(const Json& a, const Eigen::Matrix4d& b) {
    double most = 0;
    for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) most = std::max(most, std::abs(a[r][c].get<double>() - b(r, c)));
    }
    return most;
}

}  // namespace

TEST_CASE("dataset: a transforms.json of per-frame OPENCV cameras into NeRF's layout, poses, move and masks kept", "[dataset]") {
    TempDir dir;
    write_source(dir / "src");
    const fs::path out = dir / "out";
    const Json summary = run_json({"dataset", (dir / "src" / "transforms.json").string(), "-o", out.string(), "--to",
                                   "nerf", "--json", "--camera", "all", "--masks"});
    CHECK(summary["observations_in"] == 0);
    CHECK(summary["images_out"] == 3);
    CHECK(summary["cameras"].size() == 2);

    const Json written = Json::parse(libcam::test::read_whole_file(out / "transforms.json"));
    const Json source = Json::parse(libcam::test::read_whole_file(dir / "src" / "transforms.json"));
    CHECK(written["applied_transform"] == source["applied_transform"]);
    CHECK(written["applied_scale"] == kScale);
    CHECK(written["camera_model"] == "OPENCV");
    const std::vector<SourceFrame> frames = source_frames();
    REQUIRE(written["frames"].size() == frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const Json& frame = written["frames"][i];
        INFO(frames[i].name);
        CHECK(frame["file_path"] == "images/" + frames[i].name);
        // nerfstudio's mask_path (0: ignore the pixel), the mask --masks wrote: `all`
        // leaves corners without a source, black in the image and 0 in the mask.
        REQUIRE(frame["mask_path"] == "masks/" + frames[i].name + ".png");
        const cv::Mat mask = cv::imread((out / frame["mask_path"].get<std::string>()).string(), cv::IMREAD_UNCHANGED);
        REQUIRE(mask.type() == CV_8U);
        CHECK(mask.at<unsigned char>(0, 0) == 0);
        CHECK(mask.at<unsigned char>(mask.rows / 2, mask.cols / 2) == 255);
        CHECK(max_difference(frame["transform_matrix"], frames[i].transform) < 1e-12);
        // A pinhole: no coefficients, square pixels.
        for (const char* k : {"k1", "k2", "p1", "p2", "k3", "k4", "distortion_params"}) CHECK(!frame.contains(k));
        CHECK(frame["fl_x"] == frame["fl_y"]);
        // Each blob where the new pinhole images its point (same axes as the source camera).
        const cv::Mat image = cv::imread((out / frame["file_path"].get<std::string>()).string(), cv::IMREAD_UNCHANGED);
        REQUIRE(image.type() == CV_16U);
        const double f = frame["fl_x"], cx = frame["cx"].get<double>() - 0.5, cy = frame["cy"].get<double>() - 0.5;
        double worst = 0;
        for (const cv::Point3d& p : kBlobs) {
            const cv::Point2d expected(f * p.x / p.z + cx, f * p.y / p.z + cy);
            const cv::Point2d found = centroid(image, expected);
            worst = std::max(worst, std::hypot(found.x - expected.x, found.y - expected.y));
        }
        CHECK(worst < 0.1);
        WARN(frames[i].name << ": largest blob centroid distance " << worst << " px");
    }
    // libcam's reader takes it back: pinholes.
    const libcam::CameraSet back = libcam::read_camera_set(out / "transforms.json");
    REQUIRE(back.cameras.size() == 3);
    for (const libcam::NamedCamera& named : back.cameras) CHECK(named.file.camera.lens.type == libcam::LensType::Pinhole);
}

TEST_CASE("dataset: a transforms.json into a COLMAP model: cameras deduplicated, poses in the source world", "[dataset]") {
    TempDir dir;
    write_source(dir / "src");
    const fs::path out = dir / "out";
    const Json summary = run_json({"dataset", (dir / "src" / "transforms.json").string(), "-o", out.string(), "--json",
                                   "--text", "--no-images"});
    CHECK(summary["observations_in"] == 0);
    CHECK(summary["points_in"] == 0);
    REQUIRE(summary["cameras"].size() == 2);
    CHECK(summary["cameras"][0]["images"] == 2);
    CHECK(summary["cameras"][1]["images"] == 1);
    // An empty points3D: comment lines only.
    std::istringstream points(libcam::test::read_whole_file(out / "sparse" / "0" / "points3D.txt"));
    for (std::string line; std::getline(points, line);) CHECK((line.empty() || line[0] == '#'));

    const libcam::CameraSet model = libcam::read_camera_set(out / "sparse" / "0");
    const std::vector<SourceFrame> frames = source_frames();
    REQUIRE(model.cameras.size() == frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const libcam::Camera& camera = model.cameras[i].file.camera;
        INFO(frames[i].name);
        CHECK(model.cameras[i].name == frames[i].name);
        CHECK(camera.lens.type == libcam::LensType::Pinhole);
        // By hand: the moved world's camera-to-world with OpenCV's axes is M diag(1, -1, -1);
        // in the source world A^T of it, the centre A^T (c / s - b); the pose is its inverse.
        const Mat3 camera_to_world = kA.transpose() * frames[i].transform.topLeftCorner<3, 3>() *
                                     Eigen::Vector3d(1, -1, -1).asDiagonal();
        const Vec3 centre = kA.transpose() * (frames[i].transform.topRightCorner<3, 1>() / kScale - kB);
        CHECK((camera.pose.R - camera_to_world.transpose()).cwiseAbs().maxCoeff() < 1e-12);
        CHECK((camera.pose.t + camera_to_world.transpose() * centre).cwiseAbs().maxCoeff() < 1e-12);
    }
}

TEST_CASE("dataset: a COLMAP model into NeRF's layout reads back as the COLMAP output's cameras and poses", "[dataset]") {
    TempDir dir;
    const fs::path model = dir / "model";
    fs::create_directories(model);
    libcam::test::write_whole_file(model / "cameras.txt",
                                   "1 OPENCV 320 240 300 290 165.3 114.7 -0.25 0.06 0.001 -0.0015\n"
                                   "2 SIMPLE_RADIAL 200 150 180 100.5 75.5 0.03\n");
    libcam::test::write_whole_file(model / "images.txt",
                                   "1 0.7 0.1 -0.1 0.7 0.5 -1 2 1 a.png\n160.5 120.5 1 10 10 -1\n"
                                   "2 0.5 0.5 0.5 0.5 -2 0.3 1 2 b.jpg\n100.5 75.5 2\n");
    libcam::test::write_whole_file(model / "points3D.txt", "1 0.1 0.2 5 10 20 30 0.5 1 0\n2 -1 0.5 6 40 50 60 0.5 2 0\n");
    const Json colmap_summary = run_json({"dataset", model.string(), "-o", (dir / "colmap").string(), "--no-images",
                                          "--json", "--text"});
    const Json nerf_summary =
        run_json({"dataset", model.string(), "-o", (dir / "nerf").string(), "--no-images", "--json", "--to", "nerf"});
    CHECK(nerf_summary["cameras"] == colmap_summary["cameras"]);
    CHECK(nerf_summary["points_kept"] == 2);

    const libcam::CameraSet colmap = libcam::read_camera_set(dir / "colmap" / "sparse" / "0");
    const libcam::CameraSet nerf = libcam::read_camera_set(dir / "nerf" / "transforms.json");
    REQUIRE(nerf.cameras.size() == 2);
    REQUIRE(colmap.cameras.size() == 2);
    for (std::size_t i = 0; i < 2; ++i) {
        const libcam::Camera& a = colmap.cameras[i].file.camera;
        const libcam::Camera& b = nerf.cameras[i].file.camera;
        CHECK(nerf.cameras[i].name == "images/" + colmap.cameras[i].name);
        CHECK(b.lens.type == libcam::LensType::Pinhole);
        CHECK(a.size == b.size);
        CHECK(std::abs(a.intrinsics.fx - b.intrinsics.fx) < 1e-12);
        CHECK(std::abs(a.intrinsics.fy - b.intrinsics.fy) < 1e-12);
        CHECK(std::abs(a.intrinsics.cx - b.intrinsics.cx) < 1e-12);
        CHECK(std::abs(a.intrinsics.cy - b.intrinsics.cy) < 1e-12);
        CHECK((a.pose.R - b.pose.R).cwiseAbs().maxCoeff() < 1e-12);
        CHECK((a.pose.centre() - b.pose.centre()).cwiseAbs().maxCoeff() < 1e-12);
    }
    // The model's points beside it, as nerfstudio's ply_file_path.
    const Json written = Json::parse(libcam::test::read_whole_file(dir / "nerf" / "transforms.json"));
    CHECK(written["ply_file_path"] == "sparse_pc.ply");
    CHECK(!written.contains("applied_transform"));
    const std::string ply = libcam::test::read_whole_file(dir / "nerf" / "sparse_pc.ply");
    CHECK(ply.find("element vertex 2\n") != std::string::npos);
    CHECK(ply.find("\n0.10000000000000001 0.20000000000000001 5 10 20 30\n") != std::string::npos);
}

TEST_CASE("dataset: a real per-frame transforms.json, colmap-nerf-multicam-sangminkim, into a COLMAP model", "[dataset][real]") {
    const fs::path json = libcam::test::real_data_path("colmap-nerf-multicam-sangminkim/transforms.json");
    if (!libcam::test::real_data_present(json)) return;
    TempDir dir;
    const Json summary = run_json({"dataset", json.string(), "-o", (dir / "out").string(), "--no-images", "--json"});
    // SOURCES.md: 42 frames, 39 with cameras.txt's camera 2 and 3 with its camera 1 (the
    // first frame's is camera 2).
    CHECK(summary["images_in"] == 42);
    REQUIRE(summary["cameras"].size() == 2);
    CHECK(summary["cameras"][0]["images"] == 39);
    CHECK(summary["cameras"][1]["images"] == 3);
    const libcam::CameraSet model = libcam::read_camera_set(dir / "out" / "sparse" / "0");
    REQUIRE(model.cameras.size() == 42);
    // file_path ./images/robot/... : named under the images folder.
    CHECK(model.cameras[0].name == "robot/000000-color.png");
}

TEST_CASE("dataset: a transforms.json without poses or with an image outside its folder is refused naming the frame", "[dataset]") {
    TempDir dir;
    const auto error_of = [&](const std::string& json) {
        libcam::test::write_whole_file(dir / "t.json", json);
        const libcam::test::CliResult result =
            run_libcam({"dataset", (dir / "t.json").string(), "-o", (dir / "out").string(), "--no-images"});
        CHECK(result.exit_code == 1);
        return result.err;
    };
    const std::string camera = R"("fl_x": 50, "w": 64, "h": 48)";
    const std::string pose = R"("transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])";
    CHECK(error_of("{" + camera + ", \"frames\": [{\"file_path\": \"images/a.png\"}]}") ==
          "libcam: error: " + (dir / "t.json").string() +
              ": frames[0]: \"transform_matrix\": missing: a dataset needs each frame's pose\n");
    CHECK(error_of("{" + camera + ", \"frames\": [{\"file_path\": \"../a.png\", " + pose + "}]}") ==
          "libcam: error: " + (dir / "t.json").string() +
              ": frames[0]: \"file_path\": '../a.png' leads out of the json's folder through '..'; libcam dataset "
              "reads and writes each image under its name, relative to the json's folder\n");
    CHECK(error_of("{" + camera + ", \"frames\": [{\"file_path\": \"a.png\", " + pose +
                   "}, {\"file_path\": \"./a.png\", " + pose + "}]}") ==
          "libcam: error: " + (dir / "t.json").string() + ": frames[1]: \"file_path\": 'a.png' is also the name of " +
              (dir / "t.json").string() + ": frames[0]; the output keeps one image per name\n");
    CHECK(error_of("{" + camera + "}") == "libcam: error: " + (dir / "t.json").string() +
                                             ": \"frames\": missing: a dataset needs frames, each with its image and pose\n");
}
