#pragma once
// OPENCV4, OPENCV5, OPENCV8, OPENCV12, OPENCV14: OpenCV's radial-tangential family,
// exactly as cv::projectPoints evaluates it (mrcal's LENSMODEL_OPENCV4/5/8/12 are the
// same). Coefficients in OpenCV's order, the missing ones zero:
//
//     k1 k2 p1 p2 [k3 [k4 k5 k6 [s1 s2 s3 s4 [tauX tauY]]]]
//
//   u = (x, y) = (X/Z, Y/Z),   r2 = x^2 + y^2,
//   R = (1 + k1 r2 + k2 r2^2 + k3 r2^3) / (1 + k4 r2 + k5 r2^2 + k6 r2^3)
//   d = ( x R + 2 p1 x y + p2 (r2 + 2 x^2) + s1 r2 + s2 r2^2,
//         y R + p1 (r2 + 2 y^2) + 2 p2 x y + s3 r2 + s4 r2^2 )
//   m = (v0 / v2, v1 / v2),  v = T(tauX, tauY) [d; 1]       (OPENCV14; else m = d)
//
// T is OpenCV's tilted-sensor matrix (computeTiltProjectionMatrix):
//   Rxy = Ry(tauY) Rx(tauX),  T = [Rxy22 0 -Rxy02; 0 Rxy22 -Rxy12; 0 0 1] Rxy.
//
// Valid domain: Z > 0 (cv::projectPoints takes Z = 0 as Z = 1 and mirrors Z < 0 into
// the image; libcam flags both); r below valid_radius(), where the radial part r R(r)
// folds over or its denominator reaches 0 (from k1..k6: the tangential, prism and tilt
// terms are taken to be small, as in the WACV 2022 analysis); and v2 > 0.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <span>

#include "libcam/lens/lane.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/pinhole.hpp"
#include "libcam/lens/undistort.hpp"
#include "libcam/lens/valid_radius.hpp"

namespace libcam {

namespace detail {

template <class Scalar>
using Mat33T = Eigen::Matrix<Scalar, 3, 3>;

// OpenCV's "projection onto z" of a rotation: [m22 0 -m02; 0 m22 -m12; 0 0 corner].
template <class Scalar>
Mat33T<Scalar> tilt_projection(const Mat33T<Scalar>& rotation, const Scalar& corner) {
    Mat33T<Scalar> out;
    out << rotation(2, 2), Scalar(0), -rotation(0, 2),  //
        Scalar(0), rotation(2, 2), -rotation(1, 2),     //
        Scalar(0), Scalar(0), corner;
    return out;
}

// The tilt matrix T(tauX, tauY), and when asked its derivatives by the product rule.
template <class Scalar>
struct TiltMatrix {
    Mat33T<Scalar> matrix, d_tau_x, d_tau_y;

    TiltMatrix(const Scalar& tau_x, const Scalar& tau_y, bool with_derivatives) {
        using std::cos;
        using std::sin;
        const Scalar cx = cos(tau_x), sx = sin(tau_x), cy = cos(tau_y), sy = sin(tau_y);
        const Scalar zero(0), one(1);
        Mat33T<Scalar> rot_x, rot_y;
        rot_x << one, zero, zero, zero, cx, sx, zero, -sx, cx;
        rot_y << cy, zero, -sy, zero, one, zero, sy, zero, cy;
        const Mat33T<Scalar> rot_xy = rot_y * rot_x;
        const Mat33T<Scalar> projection = tilt_projection(rot_xy, one);
        matrix = projection * rot_xy;
        if (!with_derivatives) return;
        Mat33T<Scalar> d_rot_x, d_rot_y;
        d_rot_x << zero, zero, zero, zero, -sx, cx, zero, -cx, -sx;
        d_rot_y << -sy, zero, -cy, zero, zero, zero, cy, zero, -sy;
        const Mat33T<Scalar> d_rot_xy_x = rot_y * d_rot_x;
        const Mat33T<Scalar> d_rot_xy_y = d_rot_y * rot_x;
        d_tau_x = tilt_projection(d_rot_xy_x, zero) * rot_xy + projection * d_rot_xy_x;
        d_tau_y = tilt_projection(d_rot_xy_y, zero) * rot_xy + projection * d_rot_xy_y;
    }
};

constexpr LensType opencv_lens_type(int n) {
    switch (n) {
        case 4: return LensType::OpenCv4;
        case 5: return LensType::OpenCv5;
        case 8: return LensType::OpenCv8;
        case 12: return LensType::OpenCv12;
        default: return LensType::OpenCv14;
    }
}

}  // namespace detail

template <class Scalar, int N>
struct OpenCvLens : OnPinholePoint<OpenCvLens<Scalar, N>, Scalar> {
    static_assert(N == 4 || N == 5 || N == 8 || N == 12 || N == 14, "OpenCV takes 4, 5, 8, 12 or 14 coefficients");
    static constexpr LensType type = detail::opencv_lens_type(N);
    static constexpr int num_coefficients = N;
    template <class Other>
    using InScalar = OpenCvLens<Other, N>;
    using Parameters = LensParameters<Scalar, N>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;
    using Jacobian23 = Eigen::Matrix<Scalar, 2, 3>;
    using CoefficientJacobian = Eigen::Matrix<Scalar, 2, N>;

    // The normalised radius r past which the radial part folds over (or its denominator
    // reaches 0); +infinity if it never does.
    static double valid_radius(std::span<const double> k) {
        const auto at = [&](std::size_t i) { return i < k.size() ? k[i] : 0.0; };
        const double numerator[] = {1.0, at(0), at(1), at(4)};
        const double denominator[] = {1.0, at(5), at(6), at(7)};
        return radial_valid_radius(numerator, denominator);
    }

    static Parameters parameters(std::span<const double> k) {
        return lens_parameters<Scalar, N>(k, valid_radius(k));
    }

    // project, unproject and ray_from_undistorted: OnPinholePoint's (pinhole.hpp).

    // m = distort(u) for the pinhole-normalised point u = (X/Z, Y/Z); false outside the
    // valid domain (m then meaningless; evaluated without branches, see pinhole.hpp).
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& u, Vec2T& m, UJacobianPtr d_m_d_u = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        const Scalar x = u.x(), y = u.y();
        const Scalar r2 = x * x + y * y;
        const Radial radial = radial_factor(lens, r2);
        const bool inside = r2 < lens.valid_radius * lens.valid_radius;
        const bool positive = radial.denominator > Scalar(0);
        const bool in_domain = inside & positive;  // &, not &&: no branch
        const Scalar p1 = c<2>(lens), p2 = c<3>(lens);
        const Scalar two(2), r4 = r2 * r2, xy2 = two * x * y;
        Vec2T d(x * radial.value + p1 * xy2 + p2 * (r2 + two * x * x),
                y * radial.value + p1 * (r2 + two * y * y) + p2 * xy2);
        if constexpr (kThinPrism) d += Vec2T(c<8>(lens) * r2 + c<9>(lens) * r4, c<10>(lens) * r2 + c<11>(lens) * r4);

        Jacobian22 d_d_d_u;
        if constexpr (is_requested<UJacobianPtr>) {
            const Scalar mixed = xy2 * radial.d_r2 + two * (p1 * x + p2 * y);
            d_d_d_u << radial.value + two * x * x * radial.d_r2 + two * p1 * y + Scalar(6) * p2 * x, mixed,  //
                mixed, radial.value + two * y * y * radial.d_r2 + Scalar(6) * p1 * y + two * p2 * x;
            if constexpr (kThinPrism) {
                const Scalar prism_x = two * (c<8>(lens) + two * c<9>(lens) * r2);
                const Scalar prism_y = two * (c<10>(lens) + two * c<11>(lens) * r2);
                d_d_d_u += (Jacobian22() << x * prism_x, y * prism_x, x * prism_y, y * prism_y).finished();
            }
        }
        Eigen::Matrix<Scalar, 2, 12> d_d_d_k;
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            const Scalar zero(0);
            const Vec3T powers_over_q = powers_over_denominator(r2, radial);  // s^i / Q
            const int numerator_columns[3] = {0, 1, 4};  // k1 k2 k3
            for (int i = 0; i < 3; ++i) {
                d_d_d_k.col(numerator_columns[i]) = u * powers_over_q(i);
                d_d_d_k.col(5 + i) = u * (-radial.value * powers_over_q(i));  // k4 k5 k6
            }
            d_d_d_k.col(2) << xy2, r2 + two * y * y;  // p1
            d_d_d_k.col(3) << r2 + two * x * x, xy2;  // p2
            d_d_d_k.col(8) << r2, zero;
            d_d_d_k.col(9) << r4, zero;
            d_d_d_k.col(10) << zero, r2;
            d_d_d_k.col(11) << zero, r4;
        }

        if constexpr (N < 14) {
            m = d;
            if constexpr (is_requested<UJacobianPtr>) *d_m_d_u = d_d_d_u;
            if constexpr (is_requested<CoefficientJacobianPtr>) *d_m_d_coefficients = d_d_d_k.template leftCols<N>();
            return in_domain;
        } else {
            const bool tilt_in_front = apply_tilt(lens, d, m, d_d_d_u, d_d_d_k, d_m_d_u, d_m_d_coefficients);
            return in_domain && tilt_in_front;
        }
    }

    // The radial part alone, d(r) = r R(r^2), and its slope: the 1-D start of unproject.
    static Scalar radial_distortion(const Parameters& lens, const Scalar& r, Scalar& slope) {
        const Scalar r2 = r * r;
        const Radial radial = radial_factor(lens, r2);
        slope = radial.value + Scalar(2) * r2 * radial.d_r2;
        return r * radial.value;
    }

private:
    // The terms a model has: the shorter models are the longer with zeros, but the zeros
    // are not multiplied in (the compiler may not drop 0 * r2, which is not 0 for every
    // r2, and the batch paths would pay for them on every point).
    static constexpr bool kHasK3 = N >= 5;
    static constexpr bool kRational = N >= 8;    // k4 k5 k6: the denominator
    static constexpr bool kThinPrism = N >= 12;  // s1 s2 s3 s4

    // Coefficient i, or 0 for a model with fewer: the shorter models are the longer with zeros.
    template <int i>
    static Scalar c(const Parameters& lens) {
        if constexpr (i < N) {
            return lens.coefficients(i);
        } else {
            return Scalar(0);
        }
    }

    struct Radial {
        Scalar value;        // R = P / Q
        Scalar d_r2;         // dR / d(r^2)
        Scalar denominator;  // Q, or Q / s^3 when inverted: the same sign
        bool inverted;       // evaluated in t = 1 / s
    };

    // R = P(s) / Q(s), s = r^2, by Horner in s; where P or Q overflows (s^3 past the
    // largest number: r ~ 1e51 in double, 2.6e6 in float) by Horner in t = 1 / s, with P
    // and Q divided by s^3 first: P(s)/s^3 = t^3 + k1 t^2 + k2 t + k3. In s alone R would
    // be inf/inf = NaN there, though R itself is finite.
    //
    // Not in Lane<T>, the batch loops' type: that branch per point would stop the
    // vectoriser (it cost the batch paths 40 to 50 %). There such a point comes out NaN,
    // hence invalid, and the batch paths evaluate it again in T (camera/projector.cpp;
    // the Unprojector's full solver, for a pixel whose u is that far out).
    static Radial radial_factor(const Parameters& lens, const Scalar& r2) {
        const Scalar k1 = c<0>(lens), k2 = c<1>(lens);
        const Scalar one(1), two(2), three(3);
        Scalar from_k2 = k2, d_from_k2 = two * k2;  // k2 + k3 r2 and its derivative's part, when there is a k3
        if constexpr (kHasK3) {
            const Scalar k3 = c<4>(lens);
            from_k2 = k2 + r2 * k3;
            d_from_k2 = two * k2 + three * k3 * r2;
        }
        const Scalar p = one + r2 * (k1 + r2 * from_k2);
        const Scalar dp = k1 + r2 * d_from_k2;
        if constexpr (!kRational) {
            // A polynomial that overflows has an image that overflows: m comes out
            // non-finite and project() flags it.
            return {p, dp, one, false};
        } else {
            using std::isfinite;
            const Scalar k4 = c<5>(lens), k5 = c<6>(lens), k6 = c<7>(lens);
            const Scalar q = one + r2 * (k4 + r2 * (k5 + r2 * k6));
            if constexpr (!is_lane_v<Scalar>) {
                if (!(isfinite(p) && isfinite(q))) return inverted_radial_factor(lens, r2);
            }
            const Scalar dq = k4 + r2 * (two * k5 + three * k6 * r2);
            // p / q, not p * (1 / q): the reciprocal's extra rounding cost up to 20 ulps in
            // float near the camera plane (test_extremes "points at z -> 0+").
            const Scalar value = p / q;
            return {value, (dp - value * dq) / q, q, false};
        }
    }

    // R(t) = P~(t) / Q~(t) with t = 1 / s; dR/ds = -t^2 dR/dt = -t^2 (P~' - R Q~') / Q~.
    static Radial inverted_radial_factor(const Parameters& lens, const Scalar& r2) {
        const Scalar k1 = c<0>(lens), k2 = c<1>(lens), k3 = c<4>(lens);
        const Scalar k4 = c<5>(lens), k5 = c<6>(lens), k6 = c<7>(lens);
        const Scalar one(1), two(2), three(3);
        const Scalar t = one / r2;
        const Scalar p_t = k3 + t * (k2 + t * (k1 + t));
        const Scalar q_t = k6 + t * (k5 + t * (k4 + t));
        const Scalar dp_t = k2 + t * (two * k1 + three * t);
        const Scalar dq_t = k5 + t * (two * k4 + three * t);
        const Scalar value = p_t / q_t;
        return {value, -t * t * (dp_t - value * dq_t) / q_t, q_t, true};
    }

    // (s, s^2, s^3) / Q for the coefficient Jacobian, in t = 1 / s where R was.
    static Vec3T powers_over_denominator(const Scalar& r2, const Radial& radial) {
        const Scalar inv_q = Scalar(1) / radial.denominator;
        if (!radial.inverted) return Vec3T(r2, r2 * r2, r2 * r2 * r2) * inv_q;
        const Scalar t = Scalar(1) / r2;
        return Vec3T(t * t, t, Scalar(1)) * inv_q;
    }

    // OPENCV14's tilted sensor: m = (v0, v1) / v2 with v = T [d; 1], chained onto the
    // Jacobians of d.
    template <class UJacobianPtr, class CoefficientJacobianPtr>
    static bool apply_tilt(const Parameters& lens, const Vec2T& d, Vec2T& m, const Jacobian22& d_d_d_u,
                           const Eigen::Matrix<Scalar, 2, 12>& d_d_d_k, UJacobianPtr d_m_d_u,
                           CoefficientJacobianPtr d_m_d_coefficients) {
        const detail::TiltMatrix<Scalar> tilt(c<12>(lens), c<13>(lens), is_requested<CoefficientJacobianPtr>);
        const Vec3T d1(d.x(), d.y(), Scalar(1));
        const Vec3T v = tilt.matrix * d1;
        const bool in_front = v.z() > Scalar(0);
        const Scalar inv_z = Scalar(1) / v.z();
        m = Vec2T(v.x() * inv_z, v.y() * inv_z);
        if constexpr (is_requested<UJacobianPtr> || is_requested<CoefficientJacobianPtr>) {
            Jacobian23 d_m_d_v;
            d_m_d_v << inv_z, Scalar(0), -m.x() * inv_z,  //
                Scalar(0), inv_z, -m.y() * inv_z;
            const Jacobian22 d_m_d_d = d_m_d_v * tilt.matrix.template leftCols<2>();
            if constexpr (is_requested<UJacobianPtr>) *d_m_d_u = d_m_d_d * d_d_d_u;
            if constexpr (is_requested<CoefficientJacobianPtr>) {
                d_m_d_coefficients->template leftCols<12>() = d_m_d_d * d_d_d_k;
                d_m_d_coefficients->col(12) = d_m_d_v * (tilt.d_tau_x * d1);
                d_m_d_coefficients->col(13) = d_m_d_v * (tilt.d_tau_y * d1);
            }
        }
        return in_front;
    }
};

template <class Scalar>
using OpenCv4Lens = OpenCvLens<Scalar, 4>;
template <class Scalar>
using OpenCv5Lens = OpenCvLens<Scalar, 5>;
template <class Scalar>
using OpenCv8Lens = OpenCvLens<Scalar, 8>;
template <class Scalar>
using OpenCv12Lens = OpenCvLens<Scalar, 12>;
template <class Scalar>
using OpenCv14Lens = OpenCvLens<Scalar, 14>;

}  // namespace libcam
