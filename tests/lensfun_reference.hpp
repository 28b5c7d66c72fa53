#pragma once
// lensfun's own regression vectors (its tests/test_modifier_regression.cpp, the expected
// pixels stored in real-data/vectors/lensfun-test-modifier-regression.json) through
// libcam's reader of lensfun's XML and its lens models. Shared by the lensfun tests and
// the table of real files.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/io/camera_file.hpp"
#include "real_cameras.hpp"

namespace libcam::test {

// The vectors, or null (with a warning) where the real-data folder is absent.
inline nlohmann::json lensfun_vectors() {
    const std::filesystem::path path = real_data_path("vectors/lensfun-test-modifier-regression.json");
    if (!real_data_present(path)) return {};
    return nlohmann::json::parse(std::ifstream(path));
}

// The case whose name starts with `name`, or null.
inline const nlohmann::json* lensfun_vector_case(const nlohmann::json& vectors, const std::string& name) {
    if (vectors.is_null()) return nullptr;
    for (const nlohmann::json& c : vectors["cases"]) {
        if (c["name"].get<std::string>().starts_with(name)) return &c;
    }
    return nullptr;
}

// The database file of a case, in the real-data folder.
inline std::filesystem::path lensfun_case_database(const nlohmann::json& c) {
    return real_data_path("lensfun/data/db") / c["db_file"].get<std::string>();
}

// What reading the case's lens asks: the lens, focal length, crop factor and image size.
inline ReadOptions lensfun_case_options(const nlohmann::json& c) {
    ReadOptions options;
    options.lens = c["lens_model"].get<std::string>();
    options.focal_mm = c["focal_mm"].get<double>();
    options.crop_factor = c["camera_crop"].get<double>();
    options.size = ImageSize{c["width"].get<long>(), c["height"].get<long>()};
    options.lens_projection_only = c["operation"].get<std::string>().starts_with("EnableProjectionTransform");
    return options;
}

// lensfun's ApplyGeometryDistortion gives, for a pixel (x, y) of the corrected
// (rectilinear) image, the pixel of the source image it comes from: the camera's
// projection of the ray through (x, y) of a pinhole camera of the same K. NaN where the
// ray does not project.
inline Vec2 lensfun_source_pixel(const PreparedCamera& camera, double x, double y) {
    const Intrinsics& k = camera.camera().intrinsics;
    const Vec3 point((x - k.cx) / k.fx, (y - k.cy) / k.fy, 1.0);
    const Projection projected = camera.project_camera_point(point);
    return projected.valid ? projected.pixel : Vec2::Constant(std::numeric_limits<double>::quiet_NaN());
}

// The largest difference, on either axis, between libcam's source pixel and lensfun's
// expected one over the case's points (infinity where one does not project).
struct LensfunCaseMiss {
    double worst_px = 0.0;
    std::size_t points = 0;
};

inline LensfunCaseMiss lensfun_case_miss(const nlohmann::json& c) {
    const PreparedCamera camera(read_camera_file(lensfun_case_database(c), {}, std::nullopt, lensfun_case_options(c)).camera);
    LensfunCaseMiss miss;
    for (std::size_t i = 0; i < c["x"].size(); ++i) {
        const Vec2 pixel = lensfun_source_pixel(camera, c["x"][i].get<double>(), c["y"][i].get<double>());
        const double off = std::max(std::abs(pixel.x() - c["expected_x"][i].get<double>()),
                                    std::abs(pixel.y() - c["expected_y"][i].get<double>()));
        miss.worst_px = std::max(miss.worst_px, std::isnan(off) ? std::numeric_limits<double>::infinity() : off);
        ++miss.points;
    }
    return miss;
}

}  // namespace libcam::test
