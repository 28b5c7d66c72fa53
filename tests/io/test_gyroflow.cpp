// Gyroflow's lens profiles: small profiles written the way Gyroflow's calibrator writes
// them (src/core/lens_profile.rs: calib_dimension, fisheye_params, distortion_model), read
// into libcam's models with Gyroflow's own rules (the principal point at (w / 2, h / 2)
// unless the profile is asymmetrical; opencv_fisheye when no model is named).

#include <catch2/catch.hpp>
#include <fstream>
#include <string>

#include "libcam/camera/camera.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "temp_dir.hpp"

using namespace libcam;

namespace {

std::string profile(const std::string& model_line, const std::string& coefficients, bool asymmetrical = false) {
    return R"({
    "name": "GoPro_HERO8 Black_Wide_4by3",
    "camera_brand": "GoPro",
    "camera_model": "HERO8 Black",
    "lens_model": "Wide",
    "camera_setting": "",
    "calib_dimension": { "w": 4000, "h": 3000 },
    "orig_dimension": { "w": 4000, "h": 3000 },
    "input_horizontal_stretch": 1.0,
    "num_images": 30,
    "use_opencv_fisheye": true,
    "fisheye_params": {
        "RMS_error": 0.8,
        "camera_matrix": [[1860.5, 0.0, 2010.25], [0.0, 1858.75, 1490.5], [0.0, 0.0, 1.0]],
        "distortion_coeffs": )" + coefficients + R"(
    },
    )" + model_line + R"("asymmetrical": )" + (asymmetrical ? "true" : "false") + R"(,
    "calibrator_version": "1.5.4"
})";
}

}  // namespace

TEST_CASE("Gyroflow: an opencv_fisheye profile is FISHEYE with Gyroflow's centre", "[io][gyroflow]") {
    const test::TempDir dir;
    const auto path = write_file(dir, "lens.json", profile("", "[0.05, 0.01, -0.002, 0.0005]"));
    const CameraSet set = read_camera_set(path);
    REQUIRE(set.format == CameraFormat::Gyroflow);
    const Camera& camera = set.cameras.at(0).file.camera;
    CHECK(set.cameras[0].name == "GoPro HERO8 Black Wide");
    CHECK(camera.size == ImageSize{4000, 3000});
    CHECK(camera.intrinsics.fx == 1860.5);
    CHECK(camera.intrinsics.fy == 1858.75);
    CHECK(camera.intrinsics.cx == 2000.0);  // w / 2: Gyroflow ignores the matrix's cx
    CHECK(camera.intrinsics.cy == 1500.0);
    CHECK(camera.lens == Lens{LensType::Fisheye, {0.05, 0.01, -0.002, 0.0005}});

    const auto asymmetric = write_file(dir, "asym.json", profile("", "[0.05, 0.01, -0.002, 0.0005]", true));
    const Camera own = read_camera_file(asymmetric).camera;
    CHECK(own.intrinsics.cx == 2010.25);
    CHECK(own.intrinsics.cy == 1490.5);
}

TEST_CASE("Gyroflow: opencv_standard, poly3, poly5 and ptlens profiles", "[io][gyroflow]") {
    const test::TempDir dir;
    const auto standard = write_file(dir, "standard.json",
                                     profile("\"distortion_model\": \"opencv_standard\",\n    ",
                                             "[0.1, -0.05, 0.001, 0.002, 0.02, 0, 0, 0, 0, 0, 0, 0]"));
    CHECK(read_camera_file(standard).camera.lens == Lens{LensType::OpenCv5, {0.1, -0.05, 0.001, 0.002, 0.02}});
    const auto poly5 = write_file(dir, "poly5.json", profile("\"distortion_model\": \"poly5\",\n    ", "[-0.1, 0.02]"));
    CHECK(read_camera_file(poly5).camera.lens == Lens{LensType::OpenCv4, {-0.1, 0.02, 0.0, 0.0}});
    const auto ptlens = write_file(dir, "ptlens.json", profile("\"distortion_model\": \"ptlens\",\n    ", "[0.01, -0.02, 0.003]"));
    CHECK(read_camera_file(ptlens).camera.lens == Lens{LensType::Ptlens, {0.01, -0.02, 0.003}});
    const auto gopro = write_file(dir, "gopro.json", profile("\"distortion_model\": \"gopro_superview\",\n    ", "[0, 0, 0, 0]"));
    CHECK_THROWS_AS(read_camera_file(gopro), NotRepresentable);
    const auto extra = write_file(dir, "extra.json", profile("\"distortion_model\": \"poly3\",\n    ", "[-0.1, 0.5]"));
    CHECK_THROWS_AS(read_camera_file(extra), FileError);
}
