#pragma once
// The calibration files other projects wrote for real cameras: a folder outside the
// source tree, which tests/CMakeLists.txt names (LIBCAM_REAL_CAMERAS_DIR). A test that
// reads them skips, saying so, when the folder is absent.

#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <vector>

#include "libcam/io/camera_types.hpp"

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

// The cameras of a set that differ in size, K or lens, in the file's order: the views of
// one camera (COLMAP's images, NeRF's frames) once.
inline std::vector<const NamedCamera*> distinct_cameras(const CameraSet& set) {
    std::vector<const NamedCamera*> distinct;
    for (const NamedCamera& named : set.cameras) {
        const Camera& camera = named.file.camera;
        const bool seen = std::any_of(distinct.begin(), distinct.end(), [&](const NamedCamera* other) {
            const Camera& o = other->file.camera;
            return o.size == camera.size && o.intrinsics.K() == camera.intrinsics.K() && o.lens == camera.lens;
        });
        if (!seen) distinct.push_back(&named);
    }
    return distinct;
}

}  // namespace libcam::test
