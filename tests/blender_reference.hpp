#pragma once
// Blender's Cycles cameras as Cycles maps a pixel to a ray (intern/cycles/kernel/camera/
// projection.h: fisheye_to_direction, fisheye_equisolid_to_direction,
// fisheye_lens_polynomial_to_direction, equirectangular_range_to_direction; the viewplane and sensor of scene/camera.cpp and
// blender/camera.cpp), written out again step by step in long double: the tests'
// independent reference for libcam's Blender conversion.

#include <cmath>
#include <numbers>
#include <optional>

#include <Eigen/Core>

#include "libcam/convert/blender_camera.hpp"

namespace libcam::test {

namespace blender_detail {

using Real = long double;
using Vec3R = Eigen::Matrix<Real, 3, 1>;

// The tail the fisheyes share: angle theta from the axis, azimuth of (x, y) on the
// sensor (y up), as a direction in Cycles' panorama frame (x forward, y left, z up).
inline Vec3R fisheye_direction(Real theta, Real x, Real y) {
    const Real r = std::sqrt(x * x + y * y);
    Real phi = std::acos(r != 0 ? x / r : Real(0));
    if (y < 0) phi = -phi;
    return {std::cos(theta), -std::cos(phi) * std::sin(theta), std::sin(phi) * std::sin(theta)};
}

// Cycles' panorama frame to libcam's camera frame (x right, y down, z forward).
inline Eigen::Vector3d from_panorama_frame(const Vec3R& d) {
    return Eigen::Vector3d(static_cast<double>(-d.y()), static_cast<double>(-d.z()), static_cast<double>(d.x()));
}

}  // namespace blender_detail

// The ray Cycles traces through the centre of libcam's pixel (u, v) (centres at integers,
// rows from the top); nullopt where Cycles renders black (outside a fisheye's circle).
inline std::optional<Eigen::Vector3d> blender_ray(const BlenderCamera& camera, double u, double v) {
    using namespace blender_detail;
    const Real W = static_cast<Real>(camera.size.width), H = static_cast<Real>(camera.size.height);
    // Cycles' raster: the bottom-left corner is (0, 0), y up, pixel centres at +0.5.
    const Real xr = Real(u) + Real(0.5), yr = H - Real(0.5) - Real(v);
    // blender_camera_viewplane: the sides in pixels times their aspect.
    const Real xratio = W * Real(camera.pixel_aspect_x), yratio = H * Real(camera.pixel_aspect_y);
    const bool horizontal =
        camera.sensor_fit == SensorFit::Auto ? xratio > yratio : camera.sensor_fit == SensorFit::Horizontal;
    const Real S = camera.sensor_fit == SensorFit::Vertical ? camera.sensor_height_mm : camera.sensor_width_mm;
    if (camera.type == BlenderCameraType::Perspective) {
        const Real aspect = horizontal ? xratio / yratio : yratio / xratio;
        const Real ax = horizontal ? aspect : 1, ay = horizontal ? 1 : aspect;
        const Real tan_half_fov = Real(0.5) * S / Real(camera.lens_mm) / aspect;
        const Real left = -ax + 2 * aspect * Real(camera.shift_x), right = ax + 2 * aspect * Real(camera.shift_x);
        const Real bottom = -ay + 2 * aspect * Real(camera.shift_y), top = ay + 2 * aspect * Real(camera.shift_y);
        const Real x = (left + xr / W * (right - left)) * tan_half_fov;
        const Real y = (bottom + yr / H * (top - bottom)) * tan_half_fov;
        return Eigen::Vector3d(static_cast<double>(x), static_cast<double>(-y), 1.0);
    }
    // The panoramic viewplane: (U, V) in [0, 1] over the image, moved by the shift. The
    // equisolid and polynomial fisheyes' sensor (blender_camera_sync): S along the fitted
    // side, the other side's in proportion to the pixels times their aspect.
    const Real U = xr / W + Real(camera.shift_x), V = yr / H + Real(camera.shift_y);
    switch (camera.type) {
        case BlenderCameraType::FisheyeEquidistant: {
            const Real x = (U - Real(0.5)) * 2, y = (V - Real(0.5)) * 2, r = std::sqrt(x * x + y * y);
            if (r > 1) return std::nullopt;
            return from_panorama_frame(fisheye_direction(r * Real(camera.fisheye_fov) / 2, x, y));
        }
        case BlenderCameraType::FisheyeEquisolid: {
            const Real sw = horizontal ? S : S * xratio / yratio, sh = horizontal ? S * yratio / xratio : S;
            const Real x = (U - Real(0.5)) * sw, y = (V - Real(0.5)) * sh, r = std::sqrt(x * x + y * y);
            const Real lens = camera.fisheye_lens_mm;
            if (r > 2 * lens * std::sin(Real(camera.fisheye_fov) / 4)) return std::nullopt;
            return from_panorama_frame(fisheye_direction(2 * std::asin(r / (2 * lens)), x, y));
        }
        case BlenderCameraType::FisheyeLensPolynomial: {
            const Real sw = horizontal ? S : S * xratio / yratio, sh = horizontal ? S * yratio / xratio : S;
            const Real x = (U - Real(0.5)) * sw, y = (V - Real(0.5)) * sh, r = std::sqrt(x * x + y * y);
            const auto& k = camera.fisheye_polynomial;
            const Real r2 = r * r;
            const Real theta = -(Real(k[0]) + Real(k[1]) * r + Real(k[2]) * r2 + Real(k[3]) * r2 * r + Real(k[4]) * r2 * r2);
            if (std::abs(theta) > Real(camera.fisheye_fov) / 2) return std::nullopt;
            return from_panorama_frame(fisheye_direction(theta, x, y));
        }
        case BlenderCameraType::Equirectangular: {
            const Real lon_min = camera.longitude_min, lon_max = camera.longitude_max;
            const Real lat_min = camera.latitude_min, lat_max = camera.latitude_max;
            const Real phi = (lon_min - lon_max) * U - lon_min;
            const Real theta = (lat_min - lat_max) * V - lat_min + std::numbers::pi_v<Real> / 2;
            return from_panorama_frame(
                Vec3R(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
        }
        case BlenderCameraType::Perspective: break;
    }
    return std::nullopt;
}

}  // namespace libcam::test
