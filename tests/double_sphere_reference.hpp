#pragma once
// The Double Sphere camera as its paper writes it (Usenko, Demmel and Cremers, "The
// Double Sphere Camera Model", 3DV 2018, equations 40-47), transcribed here apart from
// libcam's lens/double_sphere.hpp and evaluated in long double (64-bit significand, 11
// bits more than double): the expected values of the tests, independent of the code
// under test.

#include <cmath>
#include <limits>
#include <optional>

#include "libcam/camera/camera.hpp"

namespace libcam::test {

using Long = long double;

// Equations 40-42: the pixel of a camera-frame point; nothing outside the domain, taken
// as the geometry the paper describes: the point carried onto the second sphere must be
// in front of the tangent cone of the pinhole alpha / (1 - alpha) behind that sphere's
// centre (z2 > -w1; equation 43's closed form for it is narrower, see
// lens/double_sphere.hpp).
inline std::optional<Vec2> double_sphere_paper_pixel(const Camera& camera, const Vec3& point) {
    const Long xi = camera.lens.coefficients.at(0), alpha = camera.lens.coefficients.at(1);
    const Long x = point.x(), y = point.y(), z = point.z();
    const Long d1 = std::sqrt(x * x + y * y + z * z);
    const Long d2 = std::sqrt(x * x + y * y + (xi * d1 + z) * (xi * d1 + z));
    const Long w1 = alpha <= Long(0.5) ? alpha / (1 - alpha) : (1 - alpha) / alpha;
    if (!((xi * d1 + z) / d2 > -w1)) return std::nullopt;
    const Long denominator = alpha * d2 + (1 - alpha) * (xi * d1 + z);
    const Intrinsics& k = camera.intrinsics;
    return Vec2(static_cast<double>(k.fx * x / denominator + k.cx), static_cast<double>(k.fy * y / denominator + k.cy));
}

// Equations 45-47: the unit ray of a pixel, or nothing where it has none.
inline std::optional<Vec3> double_sphere_paper_ray(const Camera& camera, const Vec2& pixel) {
    const Long xi = camera.lens.coefficients.at(0), alpha = camera.lens.coefficients.at(1);
    const Intrinsics& k = camera.intrinsics;
    const Long mx = (Long(pixel.x()) - k.cx) / k.fx, my = (Long(pixel.y()) - k.cy) / k.fy;
    const Long r2 = mx * mx + my * my;
    if (alpha > Long(0.5) && !(r2 <= 1 / (2 * alpha - 1))) return std::nullopt;
    const Long mz = (1 - alpha * alpha * r2) / (alpha * std::sqrt(1 - (2 * alpha - 1) * r2) + 1 - alpha);
    const Long scale = (mz * xi + std::sqrt(mz * mz + (1 - xi * xi) * r2)) / (mz * mz + r2);
    return Vec3(static_cast<double>(scale * mx), static_cast<double>(scale * my), static_cast<double>(scale * mz - xi));
}

}  // namespace libcam::test
