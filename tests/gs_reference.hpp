#pragma once
// 3D Gaussian Splatting's own projection of a world point for one camera of its
// cameras.json, worked out from its code. Shared by the cameras.json tests and the table of
// real files.

#include <cmath>
#include <nlohmann/json.hpp>

#include "libcam/geometry/pose.hpp"

namespace libcam::test {

// 3DGS's own projection of a world point: the view matrix [R | T] (R = rotation^T, T =
// -R position), the symmetric frustum of getProjectionMatrix (ndc = x / (z tan(fov / 2)),
// fov = focal2fov(fx, W) = 2 atan(W / (2 fx))), then ndc2Pix(v, S) = ((v + 1) S - 1) / 2.
inline Vec2 gs_rasterizer_pixel(const nlohmann::json& item, const Vec3& world) {
    Mat3 rotation;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) rotation(r, c) = item["rotation"][r][c].get<double>();
    }
    const Vec3 position(item["position"][0].get<double>(), item["position"][1].get<double>(),
                        item["position"][2].get<double>());
    const Vec3 view = rotation.transpose() * (world - position);
    const double width = item["width"].get<double>();
    const double height = item["height"].get<double>();
    const double fov_x = 2.0 * std::atan(width / (2.0 * item["fx"].get<double>()));
    const double fov_y = 2.0 * std::atan(height / (2.0 * item["fy"].get<double>()));
    const double ndc_x = view.x() / (view.z() * std::tan(fov_x / 2.0));
    const double ndc_y = view.y() / (view.z() * std::tan(fov_y / 2.0));
    return {((ndc_x + 1.0) * width - 1.0) * 0.5, ((ndc_y + 1.0) * height - 1.0) * 0.5};
}

}  // namespace libcam::test
