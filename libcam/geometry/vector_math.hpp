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

// v times a power of two (exact) that brings its largest component into [1, 2), so
// products of tiny (1e-320) or huge (1e300) vectors neither underflow nor overflow.
// The zero vector stays zero.
inline Vec3 scaled_to_unit_range(const Vec3& v) {
    const double largest = v.cwiseAbs().maxCoeff();
    if (largest == 0.0 || !std::isfinite(largest)) return v;
    const int exponent = std::ilogb(largest);
    return {std::ldexp(v.x(), -exponent), std::ldexp(v.y(), -exponent), std::ldexp(v.z(), -exponent)};
}

// Angle between two vectors in radians, accurate for tiny and near-pi angles
// (acos of the dot product loses half the digits near 0), at any magnitude.
inline double angle_between(const Vec3& a, const Vec3& b) {
    const Vec3 sa = scaled_to_unit_range(a);
    const Vec3 sb = scaled_to_unit_range(b);
    return std::atan2(accurate_cross(sa, sb).norm(), sa.dot(sb));
}

inline double degrees_from_radians(double angle) { return angle * (180.0 / std::numbers::pi); }
inline double radians_from_degrees(double angle) { return angle * (std::numbers::pi / 180.0); }

}  // namespace libcam
