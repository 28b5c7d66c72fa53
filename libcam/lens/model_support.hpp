#pragma once
// What every lens model header shares: the per-camera parameters a model is evaluated
// with, and the "Jacobian requested?" plumbing that makes an unrequested Jacobian
// cost nothing (the pointer is std::nullptr_t and the code computing it is discarded
// by `if constexpr`).

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <span>
#include <type_traits>

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

// The coefficients of a model with N of them, cast to Scalar; the caller has checked
// the count (Lens::validate).
template <class Scalar, int N>
Eigen::Matrix<Scalar, N, 1> coefficients_as(std::span<const double> values) {
    Eigen::Matrix<Scalar, N, 1> out;
    for (int i = 0; i < N; ++i) out(i) = Scalar(values[static_cast<std::size_t>(i)]);
    return out;
}

}  // namespace libcam
