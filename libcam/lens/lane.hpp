#pragma once
// Lane<T>: a float or double that Eigen does not vectorise by itself, for the batch
// loops over many points (camera/projector.cpp, camera/unprojector.cpp).
//
// Why: Eigen packs the two coordinates of one Vector2d into one SSE register. Inside a
// loop over points those packed statements stop GCC's loop vectoriser, which would
// otherwise put one point in each SIMD lane (2 doubles or 4 floats with SSE2, more
// with AVX). Eigen has no packet type for a user scalar, so with Lane<double> it emits
// plain scalar code, and after inlining the compiler vectorises across points.
//
// Every operation is the same IEEE operation on the wrapped value, so a model
// evaluated in Lane<double> gives bit for bit what it gives in double: this is the same
// model code in another scalar type (as for ceres::Jet), not a second implementation.

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <type_traits>

namespace libcam {

template <class T>
struct Lane {
    static_assert(std::is_floating_point_v<T>);
    T value;

    Lane() = default;
    constexpr Lane(T v) : value(v) {}  // NOLINT: implicit, as a T converts to a T
    template <class U>
        requires(std::is_arithmetic_v<U> && !std::is_same_v<U, T>)
    constexpr explicit Lane(U v) : value(static_cast<T>(v)) {}
    constexpr explicit operator T() const { return value; }

    constexpr Lane& operator+=(Lane other) { return value += other.value, *this; }
    constexpr Lane& operator-=(Lane other) { return value -= other.value, *this; }
    constexpr Lane& operator*=(Lane other) { return value *= other.value, *this; }
    constexpr Lane& operator/=(Lane other) { return value /= other.value, *this; }

    friend constexpr Lane operator+(Lane a, Lane b) { return a.value + b.value; }
    friend constexpr Lane operator-(Lane a, Lane b) { return a.value - b.value; }
    friend constexpr Lane operator*(Lane a, Lane b) { return a.value * b.value; }
    friend constexpr Lane operator/(Lane a, Lane b) { return a.value / b.value; }
    friend constexpr Lane operator-(Lane a) { return -a.value; }
    friend constexpr Lane operator+(Lane a) { return a; }

    friend constexpr bool operator<(Lane a, Lane b) { return a.value < b.value; }
    friend constexpr bool operator>(Lane a, Lane b) { return a.value > b.value; }
    friend constexpr bool operator<=(Lane a, Lane b) { return a.value <= b.value; }
    friend constexpr bool operator>=(Lane a, Lane b) { return a.value >= b.value; }
    friend constexpr bool operator==(Lane a, Lane b) { return a.value == b.value; }
    friend constexpr bool operator!=(Lane a, Lane b) { return a.value != b.value; }

    // Found by argument-dependent lookup after `using std::sqrt;` in the models.
    friend Lane sqrt(Lane a) { return std::sqrt(a.value); }
    friend Lane abs(Lane a) { return std::abs(a.value); }
    friend Lane sin(Lane a) { return std::sin(a.value); }
    friend Lane cos(Lane a) { return std::cos(a.value); }
    friend Lane tan(Lane a) { return std::tan(a.value); }
    friend Lane atan(Lane a) { return std::atan(a.value); }
    friend Lane atan2(Lane y, Lane x) { return std::atan2(y.value, x.value); }
    friend bool isfinite(Lane a) { return std::isfinite(a.value); }
};

// Whether a scalar type is a Lane: the few places where a model must not branch per
// point (opencv.hpp's overflow-safe rational factor) ask.
template <class T>
inline constexpr bool is_lane_v = false;
template <class T>
inline constexpr bool is_lane_v<Lane<T>> = true;

// A copy of v made from its value. `const Scalar xi = lens.coefficients(0)` copies a Lane
// as a whole structure, which stops GCC's loop vectoriser (the batch loops of UCM, EUCM,
// the Double Sphere, MEI and the thin-prism fisheyes ran a point at a time); a Lane built
// from the number it holds does not. The same bits; for a T, v itself.
template <class T>
constexpr T by_value(const T& v) {
    return v;
}
template <class T>
constexpr Lane<T> by_value(const Lane<T>& v) {
    return Lane<T>(v.value);
}

// The plain value of a T or a Lane<T>.
template <class T>
constexpr T lane_value(T v) {
    return v;
}
template <class T>
constexpr T lane_value(Lane<T> v) {
    return v.value;
}

}  // namespace libcam

namespace Eigen {
template <class T>
struct NumTraits<libcam::Lane<T>> : NumTraits<T> {
    using Real = libcam::Lane<T>;
    using NonInteger = libcam::Lane<T>;
    using Literal = libcam::Lane<T>;
    using Nested = libcam::Lane<T>;
    enum { IsComplex = 0, IsInteger = 0, IsSigned = 1, RequireInitialization = 0, ReadCost = 1, AddCost = 1, MulCost = 1 };
    static libcam::Lane<T> epsilon() { return NumTraits<T>::epsilon(); }
    static libcam::Lane<T> dummy_precision() { return NumTraits<T>::dummy_precision(); }
    static libcam::Lane<T> highest() { return NumTraits<T>::highest(); }
    static libcam::Lane<T> lowest() { return NumTraits<T>::lowest(); }
};
}  // namespace Eigen

template <class T>
class std::numeric_limits<libcam::Lane<T>> : public std::numeric_limits<T> {
public:
    static constexpr libcam::Lane<T> epsilon() noexcept { return std::numeric_limits<T>::epsilon(); }
    static constexpr libcam::Lane<T> infinity() noexcept { return std::numeric_limits<T>::infinity(); }
    static constexpr libcam::Lane<T> quiet_NaN() noexcept { return std::numeric_limits<T>::quiet_NaN(); }
    static constexpr libcam::Lane<T> max() noexcept { return std::numeric_limits<T>::max(); }
    static constexpr libcam::Lane<T> min() noexcept { return std::numeric_limits<T>::min(); }
    static constexpr libcam::Lane<T> lowest() noexcept { return std::numeric_limits<T>::lowest(); }
};
