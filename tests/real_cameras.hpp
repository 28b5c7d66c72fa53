#pragma once
// The calibration files other projects wrote for real cameras: a folder outside the
// source tree, which tests/CMakeLists.txt names (LIBCAM_REAL_CAMERAS_DIR). A test that
// reads them skips, saying so, when the folder is absent.

#include <catch2/catch.hpp>
#include <filesystem>

namespace libcam::test {

// The folder, or one inside it ("mrcal").
inline std::filesystem::path real_cameras_folder(const std::filesystem::path& inside = {}) {
    return std::filesystem::path(LIBCAM_REAL_CAMERAS) / inside;
}

// Whether `folder` is there; when not, warns that the test is skipped.
inline bool real_cameras_present(const std::filesystem::path& folder = real_cameras_folder()) {
    if (std::filesystem::is_directory(folder)) return true;
    WARN("skipped: no folder of real calibration files at " << folder.string());
    return false;
}

// The folder of real reconstructions and calibrations with their observations, or a
// file or folder inside it ("opencv-calib-outputs2/hpfily/out_camera_data.xml").
inline std::filesystem::path real_data_path(const std::filesystem::path& inside = {}) {
    return std::filesystem::path(LIBCAM_REAL_DATA) / inside;
}

// Whether `path` (in the real-data folder) is there; when not, warns that the test is skipped.
inline bool real_data_present(const std::filesystem::path& path) {
    std::error_code error;
    if (std::filesystem::exists(path, error)) return true;
    WARN("skipped: no real data at " << path.string());
    return false;
}

}  // namespace libcam::test
