// The camera files of Gaussian-splatting and NeRF training: 3D Gaussian Splatting's
// cameras.json and LLFF's poses_bounds.npy. Hand-made files with numbers worked out from
// each tool's own formulas (camera_to_JSON; LLFF's pose_utils.py), a real cameras.json,
// and each malformed field refused by name.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "error_message.hpp"
#include "gs_reference.hpp"
#include "real_cameras.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using libcam::test::file_error_of;

namespace {

// World-to-camera rotations of the hand-made cameras: 90 degrees about z, and none.
const Mat3 kQuarterTurn = (Mat3() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished();

void check_pose(const Camera& camera, const Mat3& R, const Vec3& t) {
    CHECK((camera.pose.R - R).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((camera.pose.t - t).cwiseAbs().maxCoeff() < 1e-14);
}

void check_intrinsics(const Camera& camera, long width, long height, double fx, double fy, double cx, double cy) {
    CHECK(camera.size.width == width);
    CHECK(camera.size.height == height);
    CHECK(camera.intrinsics.fx == fx);
    CHECK(camera.intrinsics.fy == fy);
    CHECK(camera.intrinsics.cx == cx);
    CHECK(camera.intrinsics.cy == cy);
    CHECK(camera.intrinsics.skew == 0.0);
    CHECK(camera.lens.type == LensType::Pinhole);
}

// ---- 3D Gaussian Splatting ------------------------------------------------------------

// camera_to_JSON for R = kQuarterTurn, T = (1, 2, 3): rotation = R^T row by row, position
// = -R^T T = (-2, 1, -3); and for R = I, T = (0, 0, -5): position (0, 0, 5).
constexpr const char* kGsCameras = R"([
  {"id": 0, "img_name": "left", "width": 640, "height": 480,
   "position": [-2.0, 1.0, -3.0], "rotation": [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
   "fy": 510.0, "fx": 500.0},
  {"id": 1, "img_name": "right", "width": 400, "height": 300,
   "position": [0.0, 0.0, 5.0], "rotation": [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
   "fy": 350.0, "fx": 350.0}
])";

std::string gs_with(const std::string& from, const std::string& to) {
    std::string text = kGsCameras;
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("gs-cameras: a hand-made cameras.json gives back the R, T camera_to_JSON was given") {
    libcam::test::TempDir dir;
    const auto file = dir / "cameras.json";
    write_file_atomically(file, kGsCameras);
    const CameraSet set = read_camera_set(file);
    REQUIRE(set.format == CameraFormat::GsCameras);
    REQUIRE(set.cameras.size() == 2);
    CHECK(set.cameras[0].name == "left");
    CHECK(set.cameras[1].name == "right");
    // The principal point at the image centre, (W - 1) / 2 in OpenCV's pixels.
    check_intrinsics(set.cameras[0].file.camera, 640, 480, 500.0, 510.0, 319.5, 239.5);
    check_intrinsics(set.cameras[1].file.camera, 400, 300, 350.0, 350.0, 199.5, 149.5);
    check_pose(set.cameras[0].file.camera, kQuarterTurn, Vec3(1, 2, 3));
    check_pose(set.cameras[1].file.camera, Mat3::Identity(), Vec3(0, 0, -5));
}

TEST_CASE("gs-cameras: OpenSfM's list of reconstructions is still OpenSfM's") {
    libcam::test::TempDir dir;
    const auto file = dir / "reconstruction.json";
    write_file_atomically(file, R"([{"cameras": {"c": {"projection_type": "perspective", "width": 4, "height": 3,
        "focal": 1.0, "k1": 0.0, "k2": 0.0}}, "shots": {}}])");
    CHECK(read_camera_set(file).format == CameraFormat::OpenSfm);
}

TEST_CASE("gs-cameras: each malformed field is refused with the file, the field and the value") {
    const auto error = [](const std::string& text) {
        return file_error_of([&] { parse_camera_set(text, CameraFormat::GsCameras, "c.json"); });
    };
    CHECK(error(R"({"img_name": "a"})").find("c.json: expected a list of cameras") == 0);
    CHECK(error("[]") == "c.json: no camera");
    const std::string no_fx = error(gs_with(R"("fx": 500.0)", R"("fx_": 500.0)"));
    CHECK(no_fx.find("c.json") == 0);
    CHECK(no_fx.find("fx") != std::string::npos);
    CHECK(no_fx.find("missing") != std::string::npos);
    const std::string rows = error(gs_with("[[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]",
                                           "[[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]]"));
    CHECK(rows.find("rotation") != std::string::npos);
    CHECK(rows.find("expected 3 rows") != std::string::npos);
    const std::string scaled = error(gs_with("[[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]",
                                             "[[0.0, 2.0, 0.0], [-2.0, 0.0, 0.0], [0.0, 0.0, 2.0]]"));
    CHECK(scaled.find("rotation") != std::string::npos);
    CHECK(scaled.find("not a camera's rotation") != std::string::npos);
    const std::string width = error(gs_with(R"("width": 640)", R"("width": 640.5)"));
    CHECK(width.find("width") != std::string::npos);
    CHECK(width.find("640.5") != std::string::npos);
    const std::string position = error(gs_with("[-2.0, 1.0, -3.0]", "[-2.0, 1.0]"));
    CHECK(position.find("position") != std::string::npos);
    CHECK(position.find("expected 3 numbers") != std::string::npos);
}

TEST_CASE("gs-cameras: the real cameras.json of a 3DGS run on Mip-NeRF 360's bicycle") {
    const auto path = libcam::test::real_data_path("3dgs-augustine-GSSample/cameras.json");
    if (!libcam::test::real_data_present(path)) {
        WARN("skipped: " << path << " is not there");
        return;
    }
    const CameraSet set = read_camera_set(path);
    REQUIRE(set.format == CameraFormat::GsCameras);
    const nlohmann::json file = nlohmann::json::parse(read_text_file(path));
    REQUIRE(set.cameras.size() == 193);
    REQUIRE(file.size() == 193);
    CHECK(set.cameras.front().name == "_DSC8679");
    for (std::size_t i = 0; i < set.cameras.size(); ++i) {
        const Camera& camera = set.cameras[i].file.camera;
        const nlohmann::json& item = file[i];
        INFO("camera " << i << " (" << item["img_name"].get<std::string>() << ")");
        CHECK(set.cameras[i].name == item["img_name"].get<std::string>());
        // SOURCES.md: every camera is 616x409 with these focal lengths.
        check_intrinsics(camera, 616, 409, 581.5412784147853, 578.5591777564451, 307.5, 204.0);
        // The pose gives back the file's centre and camera-to-world rotation.
        const Vec3 centre = -camera.pose.R.transpose() * camera.pose.t;
        for (int r = 0; r < 3; ++r) {
            CHECK(std::abs(centre(r) - item["position"][r].get<double>()) < 1e-12);
            for (int c = 0; c < 3; ++c) {
                CHECK(std::abs(camera.pose.R(c, r) - item["rotation"][r][c].get<double>()) < 1e-12);
            }
        }
        // A point in front of the camera lands where 3DGS's rasterizer draws it.
        const Vec3 world = centre + camera.pose.R.transpose() * Vec3(0.4, -0.3, 2.0);
        const Vec2 expected = test::gs_rasterizer_pixel(item, world);
        const Vec2 projected = camera.intrinsics.K().topLeftCorner<2, 3>() * (camera.pose.R * world + camera.pose.t) /
                               (camera.pose.R * world + camera.pose.t).z();
        CHECK((projected - expected).norm() < 1e-9);
    }
}

// ---- LLFF ------------------------------------------------------------------------------

namespace {

// An .npy of float64 rows laid out by hand: numpy's version 1.0 header, padded with spaces
// and a newline to a multiple of 64 bytes, then the numbers little-endian in C order.
std::string npy_bytes(const std::vector<std::vector<double>>& rows, const std::string& descr = "<f8") {
    std::string header = "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (" + std::to_string(rows.size()) +
                         ", " + std::to_string(rows.empty() ? 17 : rows[0].size()) + "), }";
    while ((10 + header.size() + 1) % 64 != 0) header += ' ';
    header += '\n';
    std::string bytes("\x93NUMPY\x01\x00", 8);
    bytes += static_cast<char>(header.size() & 0xFF);
    bytes += static_cast<char>(header.size() >> 8);
    bytes += header;
    for (const auto& row : rows) {
        for (const double value : row) {
            std::uint64_t bits = 0;
            std::memcpy(&bits, &value, sizeof value);
            for (int b = 0; b < 8; ++b) bytes += static_cast<char>((bits >> (8 * b)) & 0xFF);
        }
    }
    return bytes;
}

// LLFF's rows for COLMAP's R = kQuarterTurn, t = (1, 2, 3) and R = I, t = (0, 0, -5):
// camera-to-world R^T with its columns reordered [y, x, -z] (pose_utils.py), the centre
// -R^T t, then H, W, focal; near and far.
//   R^T = [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]: columns x = (0, -1, 0), y = (1, 0, 0),
//   z = (0, 0, 1), so LLFF's columns are (1, 0, 0), (0, -1, 0), (0, 0, -1); centre (-2, 1, -3).
//   R^T = I: LLFF's columns (0, 1, 0), (1, 0, 0), (0, 0, -1); centre (0, 0, 5).
const std::vector<std::vector<double>> kLlffRows = {
    {1, 0, 0, -2, 480, 0, -1, 0, 1, 640, 0, 0, -1, -3, 500, 0.5, 10.0},
    {0, 1, 0, 0, 300, 1, 0, 0, 0, 400, 0, 0, -1, 5, 350, 1.0, 20.0},
};

std::string llff_error(const std::vector<std::vector<double>>& rows) {
    return file_error_of([&] { parse_camera_set(npy_bytes(rows), CameraFormat::Llff, "poses_bounds.npy"); });
}

}  // namespace

TEST_CASE("llff: a hand-made poses_bounds.npy gives back COLMAP's R, t that LLFF was given") {
    libcam::test::TempDir dir;
    const auto file = dir / "poses_bounds.npy";
    {
        std::ofstream out(file, std::ios::binary);
        out << npy_bytes(kLlffRows);
    }
    const CameraSet set = read_camera_set(file);
    REQUIRE(set.format == CameraFormat::Llff);
    REQUIRE(set.cameras.size() == 2);
    CHECK(set.cameras[0].name == "0");
    CHECK(set.cameras[1].name == "1");
    // COLMAP's image centre, where imgs2poses' COLMAP put the principal point.
    check_intrinsics(set.cameras[0].file.camera, 640, 480, 500.0, 500.0, 319.5, 239.5);
    check_intrinsics(set.cameras[1].file.camera, 400, 300, 350.0, 350.0, 199.5, 149.5);
    check_pose(set.cameras[0].file.camera, kQuarterTurn, Vec3(1, 2, 3));
    check_pose(set.cameras[1].file.camera, Mat3::Identity(), Vec3(0, 0, -5));

    // NeRF's ray code: pixel index i looks along (i - W / 2) / focal.
    ReadOptions options;
    options.nerf_principal_point = NerfPrincipalPoint::HalfSize;
    const CameraSet nerf = read_camera_set(file, std::nullopt, options);
    check_intrinsics(nerf.cameras[0].file.camera, 640, 480, 500.0, 500.0, 320.0, 240.0);
}

TEST_CASE("llff: each malformed field is refused with the file, the field and the value") {
    CHECK(file_error_of([] { parse_camera_set("not an npy", CameraFormat::Llff, "poses_bounds.npy"); })
              .find("poses_bounds.npy: not an .npy array") == 0);
    CHECK(file_error_of([] {
              parse_camera_set(npy_bytes(kLlffRows, "<U1").substr(0, 128), CameraFormat::Llff, "poses_bounds.npy");
          }).find("poses_bounds.npy: ") == 0);
    CHECK(llff_error({{1, 2, 3}}) ==
          "poses_bounds.npy: shape (1, 3): expected (N, 17) with N >= 1: per image a 3x5 [R | centre | H W focal] "
          "and near, far");
    auto rows = kLlffRows;
    rows[1][4] = 300.5;
    CHECK(llff_error(rows).find("poses_bounds.npy: row 1: column 4: H must be a whole number of pixels") == 0);
    CHECK(llff_error(rows).find("300.5") != std::string::npos);
    rows = kLlffRows;
    rows[0][8] = std::nan("");
    CHECK(llff_error(rows) == "poses_bounds.npy: row 0: column 8: must be finite, got nan");
    rows = kLlffRows;
    rows[0][0] = 2.0;
    CHECK(llff_error(rows).find("poses_bounds.npy: row 0: columns 0-2, 5-7, 10-12 (the camera-to-world rotation)") ==
          0);
    rows = kLlffRows;
    rows[0][14] = -500.0;
    const std::string focal = llff_error(rows);
    CHECK(focal.find("poses_bounds.npy: row 0: column 14 (focal)") == 0);
}
