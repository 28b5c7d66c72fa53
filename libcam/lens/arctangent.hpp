#pragma once
// angle_from_axis(y, x): atan2(y, x) for y >= 0, the angle (0 to pi) between the point
// (x, y) and the positive x axis; what the fisheye models call theta = atan2(rho, z).
//
// Why not std::atan2: in the batch loops (Lane<T>, lane.hpp) a libm call per point stops
// the loop vectoriser, so a whole batch of FISHEYE points ran one at a time. This is
// arithmetic only (+, -, *, /, comparisons and selects), which the vectoriser turns into
// vector instructions, and it is the one implementation for float, double and Lane<T>:
// the one-point and batch paths give the same bits. Any other type (long double, the
// tests' 113-bit reference, ceres::Jet) takes its own atan2, so the reference the tests
// measure against stays independent of this code.
//
// Method: Cephes' atan (S. L. Moshier). With t = min(y, |x|) / max(y, |x|) in [0, 1],
//   atan(t) = a + a z P(z) / Q(z),  z = a^2,  a = t                    for t <= 0.66,
//   atan(t) = pi/4 + atan(a),       a = (t - 1) / (t + 1) in (-0.21, 0]  above;
// the angle is then k pi/4 + s atan(a) for k in 0..4 and s = +-1 (which octant), with
// k pi/4 as a short high part (k times it exact) plus a low part, so that pi/2 and pi
// carry their full precision.
//
// Accuracy (against atan2 in 113 bits, 6e6 points spread over 2^+-30 and every octant):
// at most 1.5 ulp in double and in float, 0.27 ulp on average (libm's atan2: 0.52 ulp
// in double). NaN for a NaN input and for (0, 0).

#include <cmath>
#include <type_traits>

#include "libcam/lens/lane.hpp"

namespace libcam {

// Whether angle_from_axis evaluates its arithmetic form in Scalar.
template <class Scalar>
inline constexpr bool kArithmeticAngle =
    std::is_same_v<Scalar, float> || std::is_same_v<Scalar, double> || is_lane_v<Scalar>;

// Always inlined: the batch kernels call it per point, and a call would run the copy
// compiled for the portable baseline, a point at a time (when more models came to call
// it, GCC stopped inlining it: FISHEYE's batch projection became 3.3 times as slow).
template <class Scalar>
[[gnu::always_inline]] inline Scalar angle_from_axis(const Scalar& y, const Scalar& x) {
    if constexpr (!kArithmeticAngle<Scalar>) {
        using std::atan2;
        return atan2(y, x);
    } else {
        using std::abs;
        // Cephes' atan.c: atan(a) = a + a z P(z) / Q(z) for |a| <= 0.66 (Q's leading 1 implied).
        const Scalar p0(-8.750608600031904122785e-1), p1(-1.615753718733365076637e1), p2(-7.500855792314704667340e1),
            p3(-1.228866684490136173410e2), p4(-6.485021904942025371773e1);
        const Scalar q0(2.485846490142306297962e1), q1(1.650270098316988542046e2), q2(4.328810604912902668951e2),
            q3(4.853903996359136964868e2), q4(1.945506571482613964425e2);
        // pi/4 = high + low: high has 8 significant bits, so k high is exact for k <= 4.
        const Scalar quarter_pi_high(0.78515625), quarter_pi_low(2.4191339744830961566e-4);

        const Scalar ax = abs(x);
        const bool steep = y > ax;  // nearer the y axis: the angle is pi/2 -+ atan(|x| / y)
        const Scalar low = steep ? ax : y, high = steep ? y : ax;
        const bool upper = low > Scalar(0.66) * high;  // t > 0.66: pi/4 + atan((t - 1) / (t + 1))
        // For t > 0.66, low - high is exact (Sterbenz: low >= high / 2).
        const Scalar a = (upper ? low - high : low) / (upper ? low + high : high);
        const Scalar z = a * a;
        const Scalar p = (((p0 * z + p1) * z + p2) * z + p3) * z + p4;
        const Scalar q = ((((z + q0) * z + q1) * z + q2) * z + q3) * z + q4;
        const Scalar tail = a * z * p / q;  // atan(a) - a
        // angle = k pi/4 + s atan(a):  0 + t,  pi - t,  pi/2 - t,  pi/2 + t  (t = atan(low / high)).
        const bool behind = x < Scalar(0);
        const Scalar c = upper ? Scalar(1) : Scalar(0);
        const Scalar k = steep ? (behind ? Scalar(2) + c : Scalar(2) - c) : (behind ? Scalar(4) - c : c);
        const Scalar s = steep != behind ? Scalar(-1) : Scalar(1);
        // For k = 0 this is a + tail, Cephes' own sum.
        return k * quarter_pi_high + (s * a + (k * quarter_pi_low + s * tail));
    }
}

}  // namespace libcam
