// NeRF's transforms.json as nerfstudio and instant-ngp write it: the world nerfstudio moved
// the frames to (applied_transform, applied_scale, dataparser_transforms.json), the camera
// models under nerfstudio's and instant-ngp's names, and real files. Every expected number
// is worked by hand from the fixture's text, from nerfstudio's or instant-ngp's formula
// transcribed here, or from the numbers another file (COLMAP's cameras.txt) holds.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/detail/nerf_transforms.hpp"
#include "error_message.hpp"
#include "real_cameras.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using libcam::test::file_error_of;
namespace fs = std::filesystem;

namespace {

std::string error_of(const std::string& json) {
    return file_error_of([&] { (void)parse_camera_set(json, CameraFormat::Nerf, "t.json"); });
}

Camera only_camera(const std::string& json) { return parse_camera(json, CameraFormat::Nerf, "t.json").camera; }

double max_difference(const nlohmann::json& a, const nlohmann::json& b) {
    double most = 0;
    for (std::size_t r = 0; r < a.size(); ++r) {
        for (std::size_t c = 0; c < a[r].size(); ++c) most = std::max(most, std::abs(a[r][c].get<double>() - b[r][c].get<double>()));
    }
    return most;
}

// nerfstudio's applied_transform for a COLMAP model (colmap_utils.py: rows 0, 2, 1 of the
// identity, the last negated): x' = x, y' = z, z' = -y. Here with b = (1, 1, 1) and s = 2.
const char* const kMovedWorld = R"({
  "applied_transform": [[1, 0, 0, 1], [0, 0, 1, 1], [0, -1, 0, 1]],
  "applied_scale": 2,
  "fl_x": 500, "w": 640, "h": 480,
  "frames": [{"file_path": "images/a.png",
              "transform_matrix": [[1, 0, 0, 4], [0, 1, 0, 6], [0, 0, 1, 8], [0, 0, 0, 1]]}]
})";

void check_moved_world_pose(const Camera& camera) {
    // Centre: x_source = A^T (x_frames / 2 - b) = A^T ((2, 3, 4) - (1, 1, 1)) = A^T (1, 2, 3)
    // with A^T = [[1, 0, 0], [0, 0, -1], [0, 1, 0]]: (1, -3, 2).
    CHECK((camera.pose.centre() - Vec3(1, -3, 2)).norm() < 1e-15);
    // Camera-to-world: A^T diag(1, -1, -1) (OpenGL's identity in OpenCV's axes) =
    // [[1, 0, 0], [0, 0, 1], [0, -1, 0]]; the pose's R is its transpose.
    const Mat3 expected = (Mat3() << 1, 0, 0, 0, 0, -1, 0, 1, 0).finished();
    CHECK((camera.pose.R - expected).cwiseAbs().maxCoeff() == 0);
}

}  // namespace

TEST_CASE("transforms.json: nerfstudio's applied_transform and applied_scale give poses in the source world") {
    const CameraSet set = parse_camera_set(kMovedWorld, CameraFormat::Nerf, "t.json");
    REQUIRE(set.cameras.size() == 1);
    check_moved_world_pose(set.cameras[0].file.camera);

    // Written back with the move: the same matrices and the same transform_matrix.
    const NerfScene scene = read_nerf_scene(kMovedWorld, {"t.json", {}, {}});
    CHECK(scene.world.source == NerfWorld::Source::AppliedTransform);
    const std::vector<CameraFileText> files = write_nerf_scene(scene.cameras, scene.world);
    REQUIRE(files.size() == 1);
    CHECK(files[0].name == "transforms.json");
    const nlohmann::json written = nlohmann::json::parse(files[0].text);
    const nlohmann::json source = nlohmann::json::parse(kMovedWorld);
    CHECK(written["applied_transform"] == source["applied_transform"]);
    CHECK(written["applied_scale"] == 2.0);
    CHECK(max_difference(written["frames"][0]["transform_matrix"], source["frames"][0]["transform_matrix"]) < 1e-12);
    CHECK(written["frames"][0]["file_path"] == "images/a.png");

    // applied_scale alone scales the centres: (4, 6, 8) / 2.
    const Camera scaled = only_camera(R"({"applied_scale": 2, "fl_x": 500, "w": 640, "h": 480,
        "frames": [{"transform_matrix": [[1, 0, 0, 4], [0, 1, 0, 6], [0, 0, 1, 8], [0, 0, 0, 1]]}]})");
    CHECK(scaled.pose.centre() == Vec3(2, 3, 4));

    CHECK(error_of(R"({"applied_transform": [[2, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]], "fl_x": 500, "w": 640, "h": 480})") ==
          "t.json: \"applied_transform\": its 3x3 part is not a rotation (libcam moves rigid poses only; scale goes in "
          "the scale)");
    CHECK(error_of(R"({"applied_transform": [[-1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]], "fl_x": 500, "w": 640, "h": 480})") ==
          "t.json: \"applied_transform\": its 3x3 part is not a rotation (libcam moves rigid poses only; scale goes in "
          "the scale)");
    CHECK(error_of(R"({"applied_scale": 0, "fl_x": 500, "w": 640, "h": 480})") ==
          "t.json: \"applied_scale\": must be positive, got 0");
    CHECK(error_of(R"({"applied_transform": [[1, 0, 0, 0], [0, 1, 0, 0]], "fl_x": 500, "w": 640, "h": 480})") ==
          "t.json: \"applied_transform\": expected 3 rows of 4 numbers");
}

TEST_CASE("transforms.json: a dataparser_transforms.json beside it says the frames are in nerfstudio's training world") {
    const libcam::test::TempDir dir;
    // The same move as kMovedWorld, recorded the way nerfstudio's trainer does.
    write_file_atomically(dir.path() / "transforms.json", R"({"fl_x": 500, "w": 640, "h": 480,
        "frames": [{"file_path": "images/a.png",
                    "transform_matrix": [[1, 0, 0, 4], [0, 1, 0, 6], [0, 0, 1, 8], [0, 0, 0, 1]]}]})");
    write_file_atomically(dir.path() / "dataparser_transforms.json",
                          R"({"transform": [[1, 0, 0, 1], [0, 0, 1, 1], [0, -1, 0, 1]], "scale": 2})");
    const CameraSet set = read_camera_set(dir.path() / "transforms.json");
    REQUIRE(set.cameras.size() == 1);
    check_moved_world_pose(set.cameras[0].file.camera);

    // Written back: the frames in the training world, and the record beside them.
    const NerfScene scene = read_nerf_scene(read_text_file(dir.path() / "transforms.json"),
                                            {"transforms.json", dir.path(), {}});
    const std::vector<CameraFileText> files = write_nerf_scene(scene.cameras, scene.world);
    REQUIRE(files.size() == 2);
    CHECK(files[1].name == "dataparser_transforms.json");
    const nlohmann::json record = nlohmann::json::parse(files[1].text);
    CHECK(record["scale"] == 2.0);
    CHECK(record["transform"] == nlohmann::json::parse("[[1, 0, 0, 1], [0, 0, 1, 1], [0, -1, 0, 1]]"));
    const nlohmann::json written = nlohmann::json::parse(files[0].text);
    CHECK(!written.contains("applied_transform"));
    CHECK(max_difference(written["frames"][0]["transform_matrix"],
                         nlohmann::json::parse("[[1, 0, 0, 4], [0, 1, 0, 6], [0, 0, 1, 8], [0, 0, 0, 1]]")) < 1e-12);

    // Both moves: which came first is not known.
    write_file_atomically(dir.path() / "transforms.json",
                          R"({"applied_transform": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]], "fl_x": 500, "w": 640, "h": 480})");
    CHECK(file_error_of([&] { (void)read_camera_set(dir.path() / "transforms.json"); }) ==
          (dir.path() / "transforms.json").string() +
              ": \"applied_transform\": given, and dataparser_transforms.json is beside the file: which move the "
              "frames are in is not clear; move one of them away (read as NeRF transforms.json, by its extension .json "
              "and its keys)");
}

TEST_CASE("transforms.json: nerfstudio's camera_model names, distortion_params and per-frame models") {
    const std::string size = R"("fl_x": 500, "fl_y": 501, "cx": 320, "cy": 240, "w": 640, "h": 480)";
    // COLMAP's names nerfstudio takes for its perspective camera: the same OpenCV keys.
    const Camera simple_radial = only_camera("{\"camera_model\": \"SIMPLE_RADIAL\", \"k1\": 0.1, " + size + "}");
    CHECK(simple_radial.lens.type == LensType::OpenCv4);
    CHECK(simple_radial.lens.coefficients == std::vector<double>{0.1, 0, 0, 0});
    const Camera radial = only_camera("{\"camera_model\": \"RADIAL\", \"k1\": 0.1, \"k2\": -0.02, " + size + "}");
    CHECK(radial.lens.coefficients == std::vector<double>{0.1, -0.02, 0, 0});
    CHECK(only_camera("{\"camera_model\": \"SIMPLE_PINHOLE\", " + size + "}").lens.type == LensType::Pinhole);

    // distortion_params in nerfstudio's order k1 k2 k3 k4 p1 p2: OpenCV's k1 k2 p1 p2 k3.
    const Camera listed = only_camera("{\"distortion_params\": [0.1, 0.2, 0.3, 0, 0.01, 0.02], " + size + "}");
    CHECK(listed.lens.type == LensType::OpenCv5);
    CHECK(listed.lens.coefficients == std::vector<double>{0.1, 0.2, 0.01, 0.02, 0.3});
    // nerfstudio's k4 multiplies r^8 (camera_utils.py: d = 1 + r (k1 + r (k2 + r (k3 + r k4)))
    // with r = x^2 + y^2): BROWN_K4, in OpenCV's order with k4 last.
    const Camera with_k4 = only_camera("{\"distortion_params\": [0.1, 0.2, 0.3, 0.4, 0.01, 0.02], " + size + "}");
    CHECK(with_k4.lens.type == LensType::BrownK4);
    CHECK(with_k4.lens.coefficients == std::vector<double>{0.1, 0.2, 0.01, 0.02, 0.3, 0.4});
    CHECK(error_of("{\"distortion_params\": [0.1, 0.2], " + size + "}") ==
          "t.json: \"distortion_params\": expected 6 numbers (k1, k2, k3, k4, p1, p2), got 2");

    // Per-frame models: a fisheye frame beside a perspective one.
    const CameraSet set = parse_camera_set("{" + size + R"(, "k1": 0.05, "frames": [
        {"file_path": "f.png", "camera_model": "OPENCV_FISHEYE", "k2": 0.01, "k3": 0.002, "k4": 0.0003},
        {"file_path": "p.png"}]})",
                                           CameraFormat::Nerf, "t.json");
    REQUIRE(set.cameras.size() == 2);
    CHECK(set.cameras[0].file.camera.lens.type == LensType::Fisheye);
    CHECK(set.cameras[0].file.camera.lens.coefficients == std::vector<double>{0.05, 0.01, 0.002, 0.0003});
    CHECK(set.cameras[1].file.camera.lens.type == LensType::OpenCv4);
    CHECK(set.cameras[1].file.camera.lens.coefficients == std::vector<double>{0.05, 0, 0, 0});
}

TEST_CASE("transforms.json: FISHEYE624 is RAD_TAN_THIN_PRISM_FISHEYE, as nerfstudio's fisheye624_project computes it") {
    const std::vector<double> k = {0.02, -0.003, 0.0004, -0.00005, 0.000006, -0.0000007,
                                   0.0011, -0.0009, 0.0007, -0.0003, -0.0005, 0.0002};
    std::string params;
    for (double v : k) params += (params.empty() ? "" : ", ") + nlohmann::json(v).dump();
    const std::string text = R"({"camera_model": "FISHEYE624", "fl_x": 400, "fl_y": 401, "cx": 640, "cy": 480,
        "w": 1280, "h": 960, "distortion_params": [)" + params + "]}";
    const Camera camera = only_camera(text);
    REQUIRE(camera.lens.type == LensType::RadTanThinPrismFisheye);
    CHECK(camera.lens.coefficients == k);

    // nerfstudio's fisheye624_project (cameras/camera_utils.py), transcribed: th = atan(r),
    // th_k = th + k0 th^3 + ... + k5 th^13, (xr, yr) = th_k (a, b) / r; then
    // u += (2 xr^2 + rd^2) p0 + 2 xr yr p1, v += (2 yr^2 + rd^2) p1 + 2 xr yr p0;
    // u += s0 rd^2 + s1 rd^4, v += s2 rd^2 + s3 rd^4; pixel = f (u, v) + c.
    const auto nerfstudio_pixel = [&](const Vec3& p) {
        const double a = p.x() / p.z(), b = p.y() / p.z(), r = std::hypot(a, b), th = std::atan(r);
        double th_k = th;
        for (int i = 0; i < 6; ++i) th_k += k[i] * std::pow(th, 3 + 2 * i);
        const double xr = th_k * a / r, yr = th_k * b / r, rd2 = xr * xr + yr * yr;
        double u = xr + (2 * xr * xr + rd2) * k[6] + 2 * xr * yr * k[7];
        double v = yr + (2 * yr * yr + rd2) * k[7] + 2 * xr * yr * k[6];
        u += k[8] * rd2 + k[9] * rd2 * rd2;
        v += k[10] * rd2 + k[11] * rd2 * rd2;
        return Vec2(400 * u + 640, 401 * v + 480);
    };
    const PreparedCamera prepared(camera);
    for (const Vec3& point : {Vec3(0.3, -0.2, 1.0), Vec3(-1.5, 0.7, 1.0), Vec3(2.0, 2.5, 0.8), Vec3(0.01, 0.02, 1.0)}) {
        const Projection projected = prepared.project(point);
        REQUIRE(projected.valid);
        // libcam's pixel centres are nerfstudio's minus 0.5.
        CHECK((projected.pixel + Vec2(0.5, 0.5) - nerfstudio_pixel(point)).norm() < 1e-9);
    }

    // Written as FISHEYE624 and read back the same.
    const nlohmann::json written = nlohmann::json::parse(format_camera(camera, CameraFormat::Nerf));
    CHECK(written["camera_model"] == "FISHEYE624");
    CHECK(written["distortion_params"].get<std::vector<double>>() == k);
    const Camera back = only_camera(written.dump());
    CHECK(back.lens.coefficients == k);
    CHECK(back.intrinsics.cx == camera.intrinsics.cx);

    CHECK(error_of(R"({"camera_model": "FISHEYE624", "fl_x": 400, "w": 1280, "h": 960})") ==
          "t.json: \"distortion_params\": missing: FISHEYE624 needs its 12 coefficients k0..k5 p0 p1 s0..s3");
    CHECK(error_of(R"({"camera_model": "FISHEYE624", "fl_x": 400, "w": 1280, "h": 960, "distortion_params": [1, 2]})") ==
          "t.json: \"distortion_params\": FISHEYE624 needs 12 numbers (k0..k5 p0 p1 s0..s3), got 2");
}

TEST_CASE("transforms.json: instant-ngp's is_fisheye, latlong and f-theta, as its ray code computes them") {
    const std::string size = R"("fl_x": 300, "cx": 320, "cy": 240, "w": 640, "h": 480)";
    // is_fisheye: k1..k4 are OpenCV's fisheye coefficients.
    const Camera fisheye = only_camera("{\"is_fisheye\": true, \"k1\": 0.1, \"k2\": 0.01, \"k3\": 0.001, \"k4\": 0.0001, " +
                                       size + "}");
    CHECK(fisheye.lens.type == LensType::Fisheye);
    CHECK(fisheye.lens.coefficients == std::vector<double>{0.1, 0.01, 0.001, 0.0001});
    CHECK(error_of("{\"is_fisheye\": true, \"p1\": 0.1, " + size + "}") ==
          "t.json: \"p1\": OPENCV_FISHEYE has no tangential coefficients");
    CHECK(error_of("{\"is_fisheye\": true, \"camera_model\": \"EQUIRECTANGULAR\", " + size + "}") ==
          "t.json: \"is_fisheye\": true, but camera_model is 'EQUIRECTANGULAR'");

    // latlong: instant-ngp's latlong_to_dir with uv = (pixel + 0.5) / size (its pixel
    // corner at 0): phi = 2 pi (u - 0.5), theta = pi (v - 0.5), the ray
    // (sin phi cos theta, sin theta, cos phi cos theta). The focal lengths are not used.
    const Camera pano = only_camera(R"({"latlong": true, "fl_x": 123, "w": 2000, "h": 1000})");
    CHECK(pano.lens.type == LensType::Lonlat);
    CHECK(pano.intrinsics.fx == 2000 / (2 * std::numbers::pi));
    CHECK(pano.intrinsics.fy == 1000 / std::numbers::pi);
    CHECK(pano.intrinsics.cx == 999.5);
    CHECK(pano.intrinsics.cy == 499.5);
    const PreparedCamera prepared(pano);
    for (const Vec2& pixel : {Vec2(1499.5, 249.5), Vec2(100.25, 800.75), Vec2(999.5, 499.5)}) {
        const double phi = 2 * std::numbers::pi * ((pixel.x() + 0.5) / 2000 - 0.5);
        const double theta = std::numbers::pi * ((pixel.y() + 0.5) / 1000 - 0.5);
        const Vec3 expected(std::sin(phi) * std::cos(theta), std::sin(theta), std::cos(phi) * std::cos(theta));
        const Ray ray = prepared.ray(pixel);
        REQUIRE(ray.valid);
        CHECK((ray.direction - expected).norm() < 1e-12);
    }

    // f-theta: instant-ngp's f_theta_undistortion, transcribed: d = the pixel's offset from
    // (cx, cy) with its centre at + 0.5, alpha = p0 + p1 |d| + ... + p4 |d|^4, the ray
    // (sin(alpha) d / |d|, cos(alpha)). fl_x is not used.
    const double p[] = {0, 2.5e-3, 1.5e-7, -2e-9, 1e-12};
    const Camera ftheta = only_camera(R"({"ftheta_p0": 0, "ftheta_p1": 2.5e-3, "ftheta_p2": 1.5e-7, "ftheta_p3": -2e-9,
        "ftheta_p4": 1e-12, "fl_x": 900, "cx": 330, "cy": 236, "w": 640, "h": 480})");
    CHECK(ftheta.lens.type == LensType::LensPolynomial);
    CHECK(ftheta.lens.coefficients == std::vector<double>{0, -2.5e-3, -1.5e-7, 2e-9, -1e-12});
    const PreparedCamera ftheta_prepared(ftheta);
    for (const Vec2& pixel : {Vec2(10, 20), Vec2(600.25, 400.5), Vec2(329.5, 100), Vec2(320, 240)}) {
        const Vec2 d = pixel + Vec2(0.5, 0.5) - Vec2(330, 236);
        const double r = d.norm();
        const double alpha = p[0] + r * (p[1] + r * (p[2] + r * (p[3] + r * p[4])));
        const Vec3 expected(std::sin(alpha) * d.x() / r, std::sin(alpha) * d.y() / r, std::cos(alpha));
        const Ray ray = ftheta_prepared.ray(pixel);
        REQUIRE(ray.valid);
        CHECK((ray.direction - expected).norm() < 1e-12);
        const Projection back = ftheta_prepared.project(expected);
        REQUIRE(back.valid);
        CHECK((back.pixel - pixel).norm() < 1e-9);
    }
    CHECK(error_of("{\"ftheta_p0\": 0, \"ftheta_p1\": 0.002, " + size + "}") ==
          "t.json: \"ftheta_p2\": missing: instant-ngp's f-theta lens needs ftheta_p0..ftheta_p4");
    CHECK(error_of("{\"equirectangular\": true, " + size + "}") ==
          "t.json: \"equirectangular\": instant-ngp's equirectangular lens (the height linear in sin(latitude)) is not "
          "a lens model libcam has");
}

TEST_CASE("transforms.json: a real per-frame file, colmap-nerf-multicam-sangminkim, holds cameras.txt's two cameras") {
    const fs::path folder = libcam::test::real_data_path("colmap-nerf-multicam-sangminkim");
    if (!libcam::test::real_data_present(folder / "transforms.json")) return;
    // cameras.txt's numbers, read here as text: CAMERA_ID OPENCV W H fx fy cx cy k1 k2 p1 p2.
    std::map<int, std::vector<double>> colmap;
    std::ifstream cameras_txt(folder / "colmap_text/cameras.txt");
    for (std::string line; std::getline(cameras_txt, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        int id = 0;
        std::string model;
        fields >> id >> model;
        std::vector<double> numbers;
        for (double v = 0; fields >> v;) numbers.push_back(v);
        colmap[id] = numbers;
    }
    REQUIRE(colmap.size() == 2);

    const CameraSet set = read_camera_set(folder / "transforms.json");
    CHECK(set.format == CameraFormat::Nerf);
    REQUIRE(set.cameras.size() == 42);
    std::map<int, int> frames_of;
    for (const NamedCamera& named : set.cameras) {
        const Camera& c = named.file.camera;
        const int id = c.intrinsics.fx == colmap[1][2] ? 1 : c.intrinsics.fx == colmap[2][2] ? 2 : 0;
        REQUIRE(id != 0);
        ++frames_of[id];
        const std::vector<double>& n = colmap[id];
        CHECK(c.size == ImageSize{static_cast<long>(n[0]), static_cast<long>(n[1])});
        CHECK(c.intrinsics.fy == n[3]);
        CHECK(c.intrinsics.cx == n[4] - 0.5);
        CHECK(c.intrinsics.cy == n[5] - 0.5);
        CHECK(c.lens.type == LensType::OpenCv4);
        CHECK(c.lens.coefficients == std::vector<double>{n[6], n[7], n[8], n[9]});
    }
    CHECK(frames_of[1] == 3);
    CHECK(frames_of[2] == 39);
    CHECK(set.cameras[0].name == "./images/robot/000000-color.png");
    // The first frame's camera-to-world: its centre is the last column (to 1e-9: the pose
    // holds t = -R C with R the nearest rotation to the file's rounded one).
    CHECK((set.cameras[0].file.camera.pose.centre() - Vec3(0.4889635490753941, -0.07059537105399934, 3.8457233156842014))
              .norm() < 1e-9);
}

TEST_CASE("transforms.json: instant-ngp's fox scene still reads with its numbers") {
    const fs::path file = libcam::test::real_cameras_folder("instant-ngp/transforms.json");
    if (!libcam::test::real_data_present(file)) return;
    const CameraSet fox = read_camera_set(file);
    REQUIRE(fox.cameras.size() == 67);
    const Camera& c = fox.cameras[0].file.camera;
    CHECK(c.size == ImageSize{1080, 1920});
    CHECK(c.intrinsics.fx == 1375.52);
    CHECK(c.intrinsics.fy == 1374.49);
    CHECK(c.intrinsics.cx == 554.558 - 0.5);
    CHECK(c.intrinsics.cy == 965.268 - 0.5);
    CHECK(c.lens.coefficients == std::vector<double>{0.0578421, -0.0805099, -0.000980296, 0.00015575});
    CHECK(std::abs(c.pose.centre().x() - 3.168359405609479) < 1e-9);
    CHECK(std::abs(c.pose.centre().y() - -5.4794898611466945) < 1e-9);
}

TEST_CASE("transforms.json: a frame without its transform_matrix is listed unposed") {
    const CameraSet set = parse_camera_set(R"({"fl_x": 500, "w": 640, "h": 480, "frames": [
        {"file_path": "images/a.png", "transform_matrix": [[1, 0, 0, 4], [0, 1, 0, 6], [0, 0, 1, 8], [0, 0, 0, 1]]},
        {"file_path": "images/b.png"}]})",
                                           CameraFormat::Nerf, "t.json");
    REQUIRE(set.cameras.size() == 2);
    CHECK_FALSE(set.cameras[0].unposed);
    CHECK(set.cameras[1].unposed);
    CHECK(set.cameras[1].file.camera.intrinsics.fx == 500.0);
    // Its image's file name alone finds it.
    CHECK(&select_camera(set, "b.png", "t.json") == &set.cameras[1]);
    // A file without frames is one camera of intrinsics, not a view: not said to be unposed.
    CHECK_FALSE(parse_camera_set(R"({"fl_x": 500, "w": 640, "h": 480})", CameraFormat::Nerf, "t.json").cameras[0].unposed);
}
