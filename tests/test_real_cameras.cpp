// The calibration files other tools wrote for real cameras (a folder of them beside the
// source tree; see LIBCAM_REAL_CAMERAS_DIR in tests/CMakeLists.txt): the ones libcam
// reads give the numbers written in them, copied here by hand from each file's text; every
// other one is refused with a libcam error naming the file, never a crash and never a
// camera read wrongly.

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"

using namespace libcam;
namespace fs = std::filesystem;

namespace {

const fs::path kFolder = LIBCAM_REAL_CAMERAS;

// What a file holds, from its text.
struct Expected {
    const char* path;  // inside the folder
    LensType type;
    ImageSize size;
    double fx, fy, cx, cy;
    double first_coefficient;  // 0 for PINHOLE
};

const std::vector<Expected> kReadable{
    {"colmap-fiord-fisheye/camera_intrinsics.yaml", LensType::Fisheye, {3264, 3264}, 991.0, 991.0, 1612.0, 1617.0,
     0.024943212941115993},
    {"opencv-calib-sample-outputs/fisheye_cali/out_camera_data.xml", LensType::Opencv5, {640, 480}, 243.40126575350806,
     243.40126575350806, 319.5, 239.5, -0.25283129827330714},
    {"mrcal/cam0.opencv8.cameramodel", LensType::Opencv8, {4000, 2200}, 1761.181055, 1761.250444, 1965.706996,
     1087.518797, -0.01266096516},
    {"mrcal/opencv8-0.cameramodel", LensType::Opencv8, {6016, 4016}, 2073.872915, 2077.452267, 3004.686823, 1997.377253,
     0.4791613797},
    {"mrcal/opencv8-1.cameramodel", LensType::Opencv8, {6016, 4016}, 2073.872915, 2077.452267, 3004.686823, 1997.377253,
     0.4791613797},
    // mrcal's splined models: the first coefficient is the spline's order.
    {"mrcal/cam0.splined.cameramodel", LensType::SplinedStereographic, {4000, 2200}, 1761.181055, 1761.250444,
     1965.706996, 1087.518797, 3.0},
    {"mrcal/splined-0.cameramodel", LensType::SplinedStereographic, {6016, 4016}, 2018.95821, 2058.977247, 3017.639608,
     1957.291928, 3.0},
    {"mrcal/splined-1.cameramodel", LensType::SplinedStereographic, {6016, 4016}, 2018.95821, 2058.977247, 3017.639608,
     1957.291928, 3.0},
    {"mrcal/pinhole-narrow-yawed-left.cameramodel", LensType::Pinhole, {3008, 2008}, 2405.678127, 2453.362582,
     1508.569804, 978.395964, 0.0},
    {"mrcal/pinhole-narrow-yawed-right.cameramodel", LensType::Pinhole, {3008, 2008}, 2405.678127, 2453.362582,
     1508.569804, 978.395964, 0.0},
};

bool folder_present() {
    if (fs::is_directory(kFolder)) return true;
    WARN("skipped: no folder of real calibration files at " << kFolder.string());
    return false;
}

}  // namespace

TEST_CASE("Real calibration files libcam reads give the numbers written in them", "[files][real]") {
    if (!folder_present()) return;
    for (const Expected& e : kReadable) {
        CAPTURE(e.path);
        const Camera camera = read_camera_file(kFolder / e.path).camera;
        CHECK(camera.lens.type == e.type);
        CHECK(camera.size == e.size);
        CHECK(camera.intrinsics.fx == e.fx);
        CHECK(camera.intrinsics.fy == e.fy);
        CHECK(camera.intrinsics.cx == e.cx);
        CHECK(camera.intrinsics.cy == e.cy);
        CHECK((camera.lens.coefficients.empty() ? 0.0 : camera.lens.coefficients.front()) == e.first_coefficient);
    }
}

TEST_CASE("Every other real calibration file is refused with one line naming it, never read wrongly", "[files][real]") {
    if (!folder_present()) return;
    int refused = 0;
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(kFolder)) {
        if (!entry.is_regular_file() || entry.path().filename() == "SOURCES.md") continue;
        const std::string relative = fs::relative(entry.path(), kFolder).generic_string();
        const bool readable = std::any_of(kReadable.begin(), kReadable.end(), [&](const Expected& e) { return relative == e.path; });
        if (readable) continue;
        CAPTURE(relative);
        try {
            (void)read_camera_file(entry.path());
            FAIL("read as a camera, but this test does not know what it holds");
        } catch (const Error& error) {  // FileError, or InvalidArgument for a value libcam cannot take
            const std::string message = error.what();
            CHECK(message.starts_with(entry.path().string() + ": "));
            CHECK(message.find('\n') == std::string::npos);
            ++refused;
        }
    }
    CHECK(refused > 0);
}
