#pragma once
// What every lens model header shares: the per-camera parameters a model is evaluated
// with, and the "Jacobian requested?" plumbing that makes an unrequested Jacobian
// cost nothing (the pointer is std::nullptr_t and the code computing it is discarded
// by `if constexpr`).

#include <Eigen/Core>
#include <array>
#include <string>
#include <cstddef>
#include <limits>
#include <span>
#include <type_traits>

#include "libcam/error.hpp"
#include "libcam/lens/lane.hpp"

namespace libcam {

// A lens model's coefficients and its valid domain, worked out once per camera by
// Model::parameters(). valid_radius bounds the model's undistorted radius (the
// normalised radius r = |(x/z, y/z)| for OpenCV's models, the angle theta from the
// optical axis for FISHEYE); infinity where the model needs no bound.
template <class Scalar, int N>
struct LensParameters {
    Eigen::Matrix<Scalar, N, 1> coefficients;
    Scalar valid_radius = Scalar(std::numeric_limits<double>::infinity());
};

// The parameters from the coefficients and a valid radius worked out before: what
// Model::parameters() returns, and what a batch path keeps per camera (the radius costs
// a polynomial root search, the rest is a copy).
template <class Scalar, int N>
LensParameters<Scalar, N> lens_parameters(std::span<const double> coefficients, double valid_radius) {
    // Once per camera: a wrong count would read past the caller's coefficients.
    if (coefficients.size() != static_cast<std::size_t>(N)) {
        throw InvalidArgument("dist: the lens model takes " + std::to_string(N) + " coefficients, got " +
                              std::to_string(coefficients.size()));
    }
    LensParameters<Scalar, N> parameters;
    for (int i = 0; i < N; ++i) parameters.coefficients(i) = Scalar(coefficients[static_cast<std::size_t>(i)]);
    parameters.valid_radius = Scalar(valid_radius);
    return parameters;
}

// Whether every coordinate of v is finite, without a branch: x - x is 0 for a finite x
// and NaN for an infinite or NaN one, and NaN != NaN. (Eigen's allFinite() stops at
// the first bad coordinate, and that branch per point stops the batch loops' vectoriser.)
template <class Vector>
bool all_finite(const Vector& v) {
    auto zero = v(0) - v(0);
    for (int i = 1; i < v.size(); ++i) zero += v(i) - v(i);
    return zero == zero;
}

// The Jacobians of m = (x, y) / D, for a model written as a ratio (the unified
// family), from D's gradient: d m / d point = ([I 0] - m (d D / d point)^T) / D, and
// d m / d c = -m (d D / d c) / D for each coefficient c. `inverse` is 1 / D.
template <class Scalar, class JacobianPtr>
void ratio_point_jacobian(const Eigen::Matrix<Scalar, 2, 1>& m, const Scalar& inverse,
                          const Eigen::Matrix<Scalar, 3, 1>& d_denominator, JacobianPtr d_m_d_point) {
    d_m_d_point->row(0) = -(m.x() * inverse) * d_denominator.transpose();
    d_m_d_point->row(1) = -(m.y() * inverse) * d_denominator.transpose();
    (*d_m_d_point)(0, 0) += inverse;
    (*d_m_d_point)(1, 1) += inverse;
}

template <class Scalar, int N, class JacobianPtr>
void ratio_coefficient_jacobian(const Eigen::Matrix<Scalar, 2, 1>& m, const Scalar& inverse,
                                const Eigen::Matrix<Scalar, N, 1>& d_denominator, JacobianPtr d_m_d_coefficients) {
    for (int k = 0; k < N; ++k) d_m_d_coefficients->col(k) = -(d_denominator(k) * inverse) * m;
}

// The smallest normal number of float, double, long double or Lane<T> (T's); 0 for
// another type (the tests' 113-bit reference, ceres::Jet), where a check against it then
// only excludes 0.
template <class Scalar>
Scalar smallest_normal() {
    if constexpr (std::is_floating_point_v<Scalar>) {
        return std::numeric_limits<Scalar>::min();
    } else if constexpr (is_lane_v<Scalar>) {
        return Scalar(std::numeric_limits<decltype(lane_value(Scalar()))>::min());
    } else {
        return Scalar(0);
    }
}

// The value of a scalar of any type libcam evaluates models in, as a double: for the
// few decisions a model takes on a value rather than computing with it (which spline
// patch a point falls in). A ceres::Jet gives its value part.
template <class Scalar>
double value_as_double(const Scalar& x) {
    if constexpr (std::is_arithmetic_v<Scalar>) {
        return static_cast<double>(x);
    } else if constexpr (is_lane_v<Scalar>) {
        return static_cast<double>(lane_value(x));
    } else if constexpr (requires { x.a; }) {
        return value_as_double(x.a);
    } else {
        return static_cast<double>(x);
    }
}

// |p| + Z of a point with X^2 + Y^2 = rho2 and |p| = norm, without cancellation: for
// Z < 0 as rho2 / (|p| - Z) (STEREOGRAPHIC, EQUISOLID).
template <class Scalar>
Scalar norm_plus_z(const Scalar& rho2, const Scalar& norm, const Scalar& z) {
    return z >= Scalar(0) ? norm + z : rho2 / (norm - z);
}

// 1 + c[0] s + c[1] s^2 + ... + c[N-1] s^N and its derivative in s, by Horner: the
// radial stretch of the models polynomial in theta^2 (thin_prism_fisheye.hpp, ...).
template <class Scalar, std::size_t N>
Scalar stretch_polynomial(const std::array<Scalar, N>& c, const Scalar& s, Scalar& slope) {
    Scalar value = c[N - 1], derivative = Scalar(static_cast<double>(N)) * c[N - 1];
    for (std::size_t i = N - 1; i-- > 0;) {
        value = c[i] + s * value;
        derivative = Scalar(static_cast<double>(i + 1)) * c[i] + s * derivative;
    }
    slope = derivative;
    return Scalar(1) + s * value;
}

// True when a Jacobian output pointer of type Ptr was passed (not the nullptr default).
template <class Ptr>
inline constexpr bool is_requested = !std::is_same_v<Ptr, std::nullptr_t>;

// `target` if the caller requested the Jacobian Ptr, else nullptr: hands a request on to
// an inner function without evaluating anything the caller did not ask for.
template <class Ptr, class T>
constexpr auto pass_request(T* target) {
    if constexpr (is_requested<Ptr>) {
        return target;
    } else {
        return nullptr;
    }
}

}  // namespace libcam
