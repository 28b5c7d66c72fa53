#pragma once
// Small vector formulas that must stay accurate when their inputs are nearly
// parallel or their results nearly zero. Each exists once and is used everywhere.

#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace libcam {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// a*b - c*d with one rounding error (Kahan's algorithm with fused multiply-add):
// the plain formula cancels catastrophically when a*b ~ c*d.
inline double difference_of_products(double a, double b, double c, double d) {
    const double cd = c * d;
    const double error = std::fma(-c, d, cd);  // exactly cd - c*d
    return std::fma(a, b, -cd) + error;
}

// Cross product with every component accurate to a few ulps even when a and b are
// nearly parallel (where a.cross(b) loses all relative accuracy).
inline Vec3 accurate_cross(const Vec3& a, const Vec3& b) {
    return {difference_of_products(a.y(), b.z(), a.z(), b.y()),
            difference_of_products(a.z(), b.x(), a.x(), b.z()),
            difference_of_products(a.x(), b.y(), a.y(), b.x())};
}

// Angle between two vectors in radians, accurate for tiny and near-pi angles
// (acos of the dot product loses half the digits near 0).
inline double angle_between(const Vec3& a, const Vec3& b) {
    return std::atan2(accurate_cross(a, b).norm(), a.dot(b));
}

inline double degrees_from_radians(double angle) { return angle * (180.0 / std::numbers::pi); }
inline double radians_from_degrees(double angle) { return angle * (std::numbers::pi / 180.0); }

}  // namespace libcam
