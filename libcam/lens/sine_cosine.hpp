#pragma once
// sine_cosine(x, s, c): sin(x) and cos(x) for an angle from the optical axis, x in
// [0, pi] (the models' theta and phi); what the fisheye and FOV models need to turn an
// angle back into a ray.
//
// Why not std::sin and std::cos: in the batch loops (Lane<T>, lane.hpp) a libm call per
// point stops the loop vectoriser, so a whole batch of rays from angles ran one point at
// a time. This is arithmetic only (+, -, *, a conversion to int and back, comparisons and
// selects), which the vectoriser turns into vector instructions, and it is the one
// implementation for float, double and Lane<T>: the one-point and batch paths give the
// same bits. Any other type (long double, the tests' 113-bit reference, ceres::Jet) takes
// its own sin and cos, so the reference the tests measure against stays independent of
// this code (as angle_from_axis in arctangent.hpp).
//
// Method: Cephes' sin and cos (S. L. Moshier; sin.c, and sinf.c for float). x is reduced
// by the nearest multiple j pi/4 with j even, z = x - j pi/4 in [-pi/4, pi/4], with pi/4
// in three parts so that z keeps its digits; then sin(z) = z + z^3 P(z^2) and
// cos(z) = 1 - z^2 / 2 + z^4 Q(z^2), and the quadrant j / 2 says which is which and the
// signs. Exact for x = 0 (sin 0, cos 1).
//
// Domain: 0 <= x < 8192 (Cephes' bound for float's reduction); the models pass at most
// pi, and the accuracy is measured on [0, pi]. NaN past the domain, and for NaN.
// Accuracy: the sine_cosine row of docs/numerical-limits.md (tests/lens/test_extremes_lens.cpp).

#include <cmath>
#include <limits>
#include <type_traits>

#include "libcam/lens/arctangent.hpp"
#include "libcam/lens/lane.hpp"

namespace libcam {

namespace detail {

// Always inlined: a call left in a model's loop (GCC's inliner gave up on FOV's) keeps the
// loop scalar.
template <class T>
[[gnu::always_inline]] inline void sine_cosine_arithmetic(T x, T& s, T& c) {
    constexpr bool kDouble = std::is_same_v<T, double>;
    // pi/4 in three parts (Cephes' DP1, DP2, DP3). The first two are short (23 and 21
    // significant bits in double, 8 and 11 in float), so that j times each is exact for
    // every j of the domain in double, and for j < 2^13 (x < 6400) in float.
    const T part1 = kDouble ? T(7.85398125648498535156e-1) : T(0.78515625);
    const T part2 = kDouble ? T(3.77489470793079817668e-8) : T(2.4187564849853515625e-4);
    const T part3 = kDouble ? T(2.69515142907905952645e-15) : T(3.77489497744594108e-8);
    const T four_over_pi = T(1.27323954473516268615);
    // The octant, rounded up to even: x - j pi/4 then lies in [-pi/4, pi/4]. (x >= 0, so
    // the conversion's truncation is floor; outside the domain, and for NaN, 0 is
    // converted instead and the result is NaN below.)
    const bool in_domain = x < T(8192);
    const int octant = static_cast<int>(in_domain ? x * four_over_pi : T(0));
    const int j = (octant + 1) & ~1;
    const T y = T(j);
    const T z = ((x - y * part1) - y * part2) - y * part3;
    const T zz = z * z;
    T sin_z, cos_z;
    if constexpr (kDouble) {
        const T p = ((((1.58962301576546568060e-10 * zz - 2.50507477628578072866e-8) * zz + 2.75573136213857245213e-6) * zz -
                      1.98412698295895385996e-4) * zz + 8.33333333332211858878e-3) * zz - 1.66666666666666307295e-1;
        const T q = ((((-1.13585365213876817300e-11 * zz + 2.08757008419747316778e-9) * zz - 2.75573141792967388112e-7) * zz +
                      2.48015872888517045348e-5) * zz - 1.38888888888730564116e-3) * zz + 4.16666666666665929218e-2;
        sin_z = z + z * (zz * p);
        cos_z = T(1) - T(0.5) * zz + zz * zz * q;
    } else {
        sin_z = ((T(-1.9515295891e-4) * zz + T(8.3321608736e-3)) * zz - T(1.6666654611e-1)) * zz * z + z;
        cos_z = ((T(2.443315711809948e-5) * zz - T(1.388731625493765e-3)) * zz + T(4.166664568298827e-2)) * zz * zz -
                T(0.5) * zz + T(1);
    }
    // x = z + quadrant pi/2: sin is sin_z, cos_z, -sin_z, -cos_z in quadrants 0 to 3, and
    // cos is the same one quadrant on.
    const int quadrant = (j >> 1) & 3;
    const bool swap = (quadrant & 1) != 0;
    const T sine = swap ? cos_z : sin_z, cosine = swap ? sin_z : cos_z;
    const bool negate_sine = quadrant >= 2, negate_cosine = quadrant == 1 || quadrant == 2;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    s = in_domain ? (negate_sine ? -sine : sine) : nan;
    c = in_domain ? (negate_cosine ? -cosine : cosine) : nan;
}

}  // namespace detail

template <class Scalar>
[[gnu::always_inline]] inline void sine_cosine(const Scalar& x, Scalar& s, Scalar& c) {
    if constexpr (!kArithmeticAngle<Scalar>) {
        using std::cos;
        using std::sin;
        s = sin(x);
        c = cos(x);
    } else if constexpr (is_lane_v<Scalar>) {
        decltype(lane_value(x)) sine, cosine;
        detail::sine_cosine_arithmetic(lane_value(x), sine, cosine);
        s = Scalar(sine);
        c = Scalar(cosine);
    } else {
        detail::sine_cosine_arithmetic(x, s, c);
    }
}

}  // namespace libcam
