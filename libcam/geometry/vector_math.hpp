#pragma once
// Small vector formulas that must stay accurate when their inputs are nearly
// parallel or their results nearly zero. Each exists once, as a template on the scalar
// type (so the same formula runs in float, double, long double and the 113-bit
// reference of the tests); the double overloads are the API everyone else calls. The
// templates take their scalar explicitly (std::type_identity_t: never deduced), so a
// call without one, even with ints or floats, always means the double overload.

#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <type_traits>

namespace libcam {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

template <class Scalar>
using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
template <class Scalar>
using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
template <class Scalar>
using Mat3T = Eigen::Matrix<Scalar, 3, 3>;

// pi rounded to Scalar: std::numbers for the built-in types, 4 atan(1) for a class type
// (boost::multiprecision), which has no std::numbers specialisation.
template <class Scalar>
Scalar pi_in() {
    if constexpr (std::is_floating_point_v<Scalar>) {
        return std::numbers::pi_v<Scalar>;
    } else {
        using std::atan;
        return Scalar(4) * atan(Scalar(1));
    }
}

// a*b - c*d with one rounding error (Kahan's algorithm with fused multiply-add):
// the plain formula cancels catastrophically when a*b ~ c*d.
template <class Scalar>
Scalar difference_of_products(const std::type_identity_t<Scalar>& a, const std::type_identity_t<Scalar>& b,
                              const std::type_identity_t<Scalar>& c, const std::type_identity_t<Scalar>& d) {
    using std::fma;
    const Scalar cd = c * d;
    const Scalar error = fma(-c, d, cd);  // exactly cd - c*d
    return fma(a, b, -cd) + error;
}
inline double difference_of_products(double a, double b, double c, double d) {
    return difference_of_products<double>(a, b, c, d);
}

// Cross product with every component accurate to a few ulps even when a and b are
// nearly parallel (where a.cross(b) loses all relative accuracy).
template <class Scalar>
Vec3T<Scalar> accurate_cross(const std::type_identity_t<Vec3T<Scalar>>& a, const std::type_identity_t<Vec3T<Scalar>>& b) {
    return {difference_of_products<Scalar>(a.y(), b.z(), a.z(), b.y()),
            difference_of_products<Scalar>(a.z(), b.x(), a.x(), b.z()),
            difference_of_products<Scalar>(a.x(), b.y(), a.y(), b.x())};
}
inline Vec3 accurate_cross(const Vec3& a, const Vec3& b) { return accurate_cross<double>(a, b); }

// v times a power of two (exact) that brings its largest component into [1, 2), so
// products of tiny (1e-320) or huge (1e300) vectors neither underflow nor overflow.
// The zero vector stays zero.
template <class Scalar>
Vec3T<Scalar> scaled_to_unit_range(const std::type_identity_t<Vec3T<Scalar>>& v) {
    using std::isfinite;
    using std::ilogb;
    using std::ldexp;
    const Scalar largest = v.cwiseAbs().maxCoeff();
    if (largest == Scalar(0) || !isfinite(largest)) return v;
    const int exponent = static_cast<int>(ilogb(largest));
    return {ldexp(v.x(), -exponent), ldexp(v.y(), -exponent), ldexp(v.z(), -exponent)};
}
inline Vec3 scaled_to_unit_range(const Vec3& v) { return scaled_to_unit_range<double>(v); }

// Angle between two vectors in radians, accurate for tiny and near-pi angles
// (acos of the dot product loses half the digits near 0), at any magnitude.
template <class Scalar>
Scalar angle_between(const std::type_identity_t<Vec3T<Scalar>>& a, const std::type_identity_t<Vec3T<Scalar>>& b) {
    using std::atan2;
    const Vec3T<Scalar> sa = scaled_to_unit_range<Scalar>(a);
    const Vec3T<Scalar> sb = scaled_to_unit_range<Scalar>(b);
    return atan2(accurate_cross<Scalar>(sa, sb).norm(), sa.dot(sb));
}
inline double angle_between(const Vec3& a, const Vec3& b) { return angle_between<double>(a, b); }

inline double degrees_from_radians(double angle) { return angle * (180.0 / std::numbers::pi); }
inline double radians_from_degrees(double angle) { return angle * (std::numbers::pi / 180.0); }

}  // namespace libcam
