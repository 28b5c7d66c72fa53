// VisualSfM's .nvm and Bundler's bundle.out: small files written here from the formats'
// documentation (VisualSfM's "NVM file format", Bundler's README "Output format"), their
// numbers worked out by hand from the formulas those documents give.

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <string>

#include "../error_message.hpp"
#include "../temp_dir.hpp"
#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/observations.hpp"

using namespace libcam;
using libcam::test::file_error_of;

namespace {

constexpr ImageSize kSize{640, 480};  // OpenCV's centre (319.5, 239.5)

// Bundler: camera 0 at R = I, t = (0, 0, -5), f 800, k1 -0.1, k2 0.02; camera 1 not
// registered (zeros). The point (0.5, 0.25, 0): P = (0.5, 0.25, -5), p = -P / P.z =
// (0.1, 0.05), |p|^2 = 0.0125, r(p) = 1 - 0.1 * 0.0125 + 0.02 * 0.0125^2 = 0.998753125,
// p' = 800 r(p) p = (79.90025, 39.950125) from the centre, y up.
const std::string kBundle =
    "# Bundle file v0.3\n2 2\n"
    "800 -0.1 0.02\n1 0 0\n0 1 0\n0 0 1\n0 0 -5\n"
    "0 0 0\n0 0 0\n0 0 0\n0 0 0\n0 0 0\n"
    "0.5 0.25 0\n255 0 0\n1 0 7 79.90025 39.950125\n"
    "0 0 1\n0 255 0\n1 0 8 -12.5 3.25\n";

// NVM: camera a.jpg at the identity, centre (0, 0, -4); b.jpg turned 90 degrees about y
// (quaternion (cos 45, 0, sin 45, 0): R = [0 0 1; 0 1 0; -1 0 0]) at centre (4, 0, 0);
// f = 1000. The point (0.2, -0.1, 1): in a, (0.2, -0.1, 5), measured 1000 (0.04, -0.02) =
// (40, -20); in b, R ((0.2, -0.1, 1) - (4, 0, 0)) = (1, -0.1, 3.8), measured
// (1000 / 3.8, -100 / 3.8).
std::string nvm_file(const std::string& r_of_a) {
    return "NVM_V3\n\n2\n"
           "a.jpg 1000 1 0 0 0 0 0 -4 " + r_of_a + " 0\n"
           "b.jpg 1000 0.70710678118654752 0 0.70710678118654752 0 4 0 0 0 0\n"
           "1\n0.2 -0.1 1 255 255 255 2 0 3 40 -20 1 9 263.15789473684211 -26.315789473684211\n\n0\n";
}

}  // namespace

TEST_CASE("Bundler: cameras down -z with y up, f k1 k2 as OPENCV4, measurements from the centre with y up",
          "[bundler]") {
    test::TempDir dir;
    const auto file = write_file(dir, "bundle.out", kBundle);
    write_file(dir, "list.txt", "img0.jpg 0 800\nimg1.jpg\n");
    ReadOptions options;
    options.size = kSize;
    const CameraSet set = read_camera_set(file, std::nullopt, options);
    CHECK(set.format == CameraFormat::Bundler);
    REQUIRE(set.cameras.size() == 1);  // camera 1 is not registered
    CHECK(set.cameras[0].name == "img0.jpg");
    const Camera& camera = set.cameras[0].file.camera;
    CHECK(camera.size == kSize);
    CHECK(camera.intrinsics.fx == 800);
    CHECK(camera.intrinsics.fy == 800);
    CHECK(camera.intrinsics.cx == 319.5);
    CHECK(camera.intrinsics.cy == 239.5);
    CHECK(camera.lens == Lens{LensType::OpenCv4, {-0.1, 0.02, 0.0, 0.0}});
    CHECK(camera.pose.R == Mat3(Vec3(1, -1, -1).asDiagonal()));
    CHECK(camera.pose.t == Vec3(0, 0, 5));
    const Projection projected = PreparedCamera(camera).project(Vec3(0.5, 0.25, 0));
    CHECK((projected.pixel - Vec2(319.5 + 79.90025, 239.5 - 39.950125)).norm() < 1e-9);

    ObservationReadOptions observation_options;
    observation_options.size = kSize;
    const ObservationSet observed = read_observations(file, observation_options);
    CHECK(observed.tool == ObservationTool::Bundler);
    REQUIRE(observed.observations.size() == 2);
    CHECK((observed.observations[0].pixel - Vec2(399.40025, 199.549875)).norm() < 1e-12);
    CHECK((observed.observations[1].pixel - Vec2(319.5 - 12.5, 239.5 - 3.25)).norm() < 1e-12);
    const Reprojection reprojection = reproject(observed);
    CHECK(reprojection.residuals[0].error_px < 1e-9);

    // The size is not in the file: without it, one line says how to give it.
    CHECK(file_error_of([&] { read_camera_set(file); }) ==
          file.string() + ": a bundle file stores no image size: give it (--image-size WIDTHxHEIGHT; every image of "
                          "the file has it)");
    // A view list naming a camera that is not registered is refused.
    std::string orphan = kBundle;
    orphan.replace(orphan.find("1 0 8"), 5, "1 1 8");
    CHECK(file_error_of([&] { read_observations(write_file(dir, "orphan.out", orphan), observation_options); }) ==
          (dir.path() / "orphan.out").string() + ": line 18: point 1: camera 1 is not registered (its f is 0)");
    std::string letters = kBundle;
    letters.replace(letters.find("-0.1"), 4, "k1(x)");
    CHECK(file_error_of([&] { read_camera_set(write_file(dir, "bad.out", letters), std::nullopt, options); }) ==
          (dir.path() / "bad.out").string() + ": line 3: camera 0 k1: expected a number, got 'k1(x)'");
    CHECK_THROWS_AS(read_observations(write_file(dir, "huge.out", "1000000000 5\n1 2 3\n"), observation_options),
                    FileError);
}

TEST_CASE("NVM: quaternion WXYZ world to camera, the camera centre, measurements from the centre", "[nvm]") {
    test::TempDir dir;
    const auto file = write_file(dir, "scene.nvm", nvm_file("0"));
    ReadOptions options;
    options.size = kSize;
    const CameraSet set = read_camera_set(file, std::nullopt, options);
    CHECK(set.format == CameraFormat::Nvm);
    REQUIRE(set.cameras.size() == 2);
    CHECK(set.cameras[1].name == "b.jpg");
    const Camera& b = set.cameras[1].file.camera;
    CHECK(b.lens.type == LensType::Pinhole);
    CHECK(b.intrinsics.fx == 1000);
    CHECK(b.intrinsics.cx == 319.5);
    const Mat3 R_b = (Mat3() << 0, 0, 1, 0, 1, 0, -1, 0, 0).finished();
    CHECK((b.pose.R - R_b).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((b.pose.centre() - Vec3(4, 0, 0)).norm() < 1e-14);

    ObservationReadOptions observation_options;
    observation_options.size = kSize;
    const ObservationSet observed = read_observations(file, observation_options);
    CHECK(observed.tool == ObservationTool::VisualSfm);
    REQUIRE(observed.observations.size() == 2);
    CHECK(observed.observations[0].pixel == Vec2(359.5, 219.5));
    const Reprojection reprojection = reproject(observed);
    CHECK(reprojection.summary.all.stats.max_px < 1e-9);
}

TEST_CASE("NVM: the radial distortion undistorts the measurement, which no lens does: cameras refused, "
          "observations undistorted", "[nvm]") {
    test::TempDir dir;
    // r = 0.5 on a's measurement (40, -20): |m / f|^2 = 0.002, ideal = 1.001 (40, -20).
    const auto file = write_file(dir, "scene.nvm", nvm_file("0.5"));
    ReadOptions options;
    options.size = kSize;
    CHECK_THROWS_WITH(read_camera_set(file, std::nullopt, options),
                      file.string() + ": camera 0 ('a.jpg'): VisualSfM's measurement distortion r = 0.5 undistorts "
                                      "the measured pixel, which no libcam lens does (its observations read)");
    ObservationReadOptions observation_options;
    observation_options.size = kSize;
    const ObservationSet observed = read_observations(file, observation_options);
    CHECK((observed.observations[0].pixel - Vec2(319.5 + 40.04, 239.5 - 20.02)).norm() < 1e-12);
    CHECK(observed.observations[1].pixel == Vec2(319.5 + 263.15789473684211, 239.5 - 26.315789473684211));

    CHECK(file_error_of([&] { read_observations(file); }) ==
          file.string() + ": an NVM file stores no image size: give it (--image-size WIDTHxHEIGHT; every image of the "
                          "file has it)");
    CHECK(file_error_of([&] {
              read_observations(write_file(dir, "fixed.nvm", "NVM_V3 FixedK 1000 320 1000 240\n0\n"), observation_options);
          }) == (dir.path() / "fixed.nvm").string() +
                    ": line 1: NVM_V3 FixedK (a calibration shared by every camera) is not read");
    std::string zero_quaternion = nvm_file("0");
    zero_quaternion.replace(zero_quaternion.find("1000 1 0 0 0"), 12, "1000 0 0 0 0");
    CHECK(file_error_of([&] { read_camera_set(write_file(dir, "q.nvm", zero_quaternion), std::nullopt, options); }) ==
          (dir.path() / "q.nvm").string() + ": line 4: camera 0 quaternion: expected a unit quaternion, got norm 0");
}
