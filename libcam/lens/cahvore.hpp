#pragma once
// CAHVORE: CAHVOR with a moving entrance pupil (E) and a choice of projection
// (linearity L), JPL's model for fisheye lenses, as libmrcal 2.2's
// LENSMODEL_CAHVORE_linearity=L defines it. Coefficients alpha beta r0 r1 r2 e0 e1 e2
// linearity; mrcal's intrinsics are fx fy cx cy and the first eight, and L is part of
// its model's name.
//
//   o = (sin(alpha) cos(beta), sin(beta), cos(alpha) cos(beta))   the optical axis
//   v = p / |p|,  omega = v . o,  l = |v - omega o|,  phi = atan2(l, omega)
//   theta solves  sin(theta - phi) = (theta - sin(theta)) (e0 + e1 theta^2 + e2 theta^4)
//   chi = tan(L theta) / L  (L > 0),  sin(L theta) / L  (L < 0),  theta  (L = 0)
//   mu  = r0 + r1 chi^2 + r2 chi^4
//   w   = o + ((1 + mu) chi / l) (v - omega o)     tan of w's angle from o: (1 + mu) chi
//   m   = (w_x / w_z, w_y / w_z)                  a pinhole about the camera's z axis
//
// L = 1 with E = 0 is CAHVOR (chi = tan(phi)); L = 0 is an equidistant fisheye (chi =
// theta). mrcal 2.2 normalises p first, so the model is central: a direction has one
// pixel. (JPL's CAHVORE, and mrcal from 2.3 on, move the entrance pupil along o with the
// point's distance: for E != 0 a point and a point twice as far along the same ray land on
// different pixels, which no central model can express; with E = 0 all agree.) theta is
// found as mrcal finds it, by Newton's method from theta = phi: here at most eight steps,
// which reach rounding level for every lens with |E| below 1.
//
// Valid domain: the pinhole points |u| < valid_radius() (u = (X/Z, Y/Z)), a disc about z
// whose directions all lie within phi_max of o. phi_max is where, scanning phi from the
// axis in steps of 1/4096 of a right angle, the map first stops being one-to-one or
// defined: theta stops increasing with phi (the Newton equation's slope reaches 0), L
// theta reaches a right angle, (1 + mu) chi stops increasing with chi, or w reaches the
// camera plane; or 90 degrees. mrcal refuses a whole projection call with a point past
// |L| theta = 90 degrees; here such points are flagged.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <type_traits>

#include "libcam/lens/cahvor.hpp"
#include "libcam/lens/lane.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/pinhole.hpp"

namespace libcam {

template <class Scalar>
struct CahvoreLens : OnPinholePoint<CahvoreLens<Scalar>, Scalar> {
    static constexpr LensType type = LensType::Cahvore;
    static constexpr int num_coefficients = 9;
    template <class Other>
    using InScalar = CahvoreLens<Other>;
    using Parameters = LensParameters<Scalar, 9>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;
    using Jacobian23 = Eigen::Matrix<Scalar, 2, 3>;
    using CoefficientJacobian = Eigen::Matrix<Scalar, 2, 9>;

    // mrcal's bound for a linearity of zero (|L| below it: chi = theta).
    static constexpr double kLinearZero = 1e-15;

    // The radius of the disc of pinhole points that bounds the valid domain (above);
    // +infinity for an untilted lens that stays one-to-one to 90 degrees.
    static double valid_radius(std::span<const double> k) {
        constexpr int kSteps = 4096;
        const double right_angle = std::numbers::pi / 2;
        const double gamma = detail::cahvor_tilt(k[0], k[1]);
        const double cot_gamma = gamma > 0.0 ? 1.0 / std::tan(gamma) : std::numeric_limits<double>::infinity();
        double theta = 0.0, previous_theta = 0.0, previous_stretch = 0.0;
        for (int i = 1; i < kSteps; ++i) {
            const double phi = right_angle * i / kSteps;
            const Angles<double> a = angles(k, phi, std::cos(phi), std::sin(phi));
            theta = a.theta;
            const Chi<double> chi = chi_of(k[8], theta);
            const double stretch = (1.0 + mu_of(k, chi.value)) * chi.value;
            const bool ok = std::isfinite(theta) && a.slope > 0.0 && theta > previous_theta &&
                            std::abs(k[8] * theta) < right_angle && chi.d_theta > 0.0 && stretch > previous_stretch &&
                            stretch < cot_gamma && std::isfinite(stretch);
            if (!ok) return detail::disc_within_angle(right_angle * (i - 1) / kSteps, gamma);
            previous_theta = theta;
            previous_stretch = stretch;
        }
        return gamma == 0.0 ? std::numeric_limits<double>::infinity()
                            : detail::disc_within_angle(right_angle * (kSteps - 1) / kSteps, gamma);
    }

    static Parameters parameters(std::span<const double> k) { return lens_parameters<Scalar, 9>(k, valid_radius(k)); }

    // project, unproject and ray_from_undistorted: OnPinholePoint's (pinhole.hpp).

    // m of the pinhole point u = (X/Z, Y/Z); false outside the valid domain.
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& u, Vec2T& m, UJacobianPtr d_m_d_u = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        using std::sqrt;
        const auto& k = lens.coefficients;
        const Scalar one(1), zero(0);
        const Vec3T o = detail::cahvor_axis(k(0), k(1));
        const Scalar norm = sqrt(one + u.squaredNorm());
        const Vec3T v = Vec3T(u.x(), u.y(), one) / norm;
        const Scalar omega = detail::dot3(v, o);
        const Vec3T c = detail::cross3(v, o);
        const Vec3T across = detail::cross3(o, c);  // v - omega o, to a few roundings of its size
        const Scalar l = sqrt(detail::dot3(c, c));
        const Scalar phi = atan2_of(l, omega);
        const Angles<Scalar> a = angles(k, phi, omega, l);
        const Chi<Scalar> chi = chi_of(k(8), a.theta);
        const Scalar mu = mu_of(k, chi.value);
        const Scalar stretch = (one + mu) * chi.value;  // tan of w's angle from o
        // w = o + (stretch / l) (v - omega o) = (1 + kappa) v / omega - kappa o, with
        // 1 + kappa = stretch cot(phi) = (1 + mu) chi cot(phi). Both
        // coefficients are worked out to a few roundings of their own size: 1 + kappa as a
        // product, kappa from q = chi cot(phi) - 1 without cancellation (chi_minus_tan).
        // Near the axis of a tilted lens, o and the second term of w nearly cancel (at
        // f = 5.7e12 px, 1e-5 px); near 90 degrees, 1 + kappa is small.
        const bool off_axis = l > zero;
        const Scalar cot_phi = omega / l;
        const Scalar q = off_axis ? chi_minus_tan(k(8), phi, omega, l, a) * cot_phi : zero;
        const Scalar kappa = q + mu * (one + q);
        const Scalar one_plus_kappa = off_axis ? stretch * cot_phi : one + k(2);
        const Vec3T w_prime = one_plus_kappa * v - (kappa * omega) * o;  // omega w
        const Scalar inverse_z_prime = one / w_prime.z();
        m = Vec2T(w_prime.x() * inverse_z_prime, w_prime.y() * inverse_z_prime);
        const bool in_domain = (u.squaredNorm() < lens.valid_radius * lens.valid_radius) & (omega > zero) &
                               (w_prime.z() > zero) & all_finite(m);

        if constexpr (is_requested<UJacobianPtr> || is_requested<CoefficientJacobianPtr>) {
            // Derivatives of w = w' / omega = o + scale (v - omega o) (scale = stretch / l,
            // 1 + r0 on the axis, where v - omega o is 0 too).
            const Scalar scale = off_axis ? stretch / l : one + k(2);
            const Scalar inverse_z = omega * inverse_z_prime;
            Jacobian23 d_m_d_w;
            d_m_d_w << inverse_z, zero, -m.x() * inverse_z,  //
                zero, inverse_z, -m.y() * inverse_z;
            // d stretch / d theta, and how scale moves with stretch and l (none on the axis).
            const Scalar d_mu_d_chi = Scalar(2) * chi.value * (k(3) + Scalar(2) * k(4) * chi.value * chi.value);
            const Scalar d_stretch_d_chi = one + mu + chi.value * d_mu_d_chi;
            const Scalar inverse_l = off_axis ? one / l : zero;
            // w moves by d_scale (v - omega o) + scale d_across + d_o, with d_scale from
            // d_stretch and d_l: d_scale = (d_stretch - scale d_l) / l.
            const auto d_w = [&](const Scalar& d_theta_other, const Scalar& d_omega, const Vec3T& d_across,
                                 const Vec3T& d_o) -> Vec3T {
                const Scalar d_l = detail::dot3(across, d_across) * inverse_l;
                const Scalar d_theta = a.d_omega * d_omega + a.d_l * d_l + d_theta_other;
                const Scalar d_scale = (d_stretch_d_chi * chi.d_theta * d_theta - scale * d_l) * inverse_l;
                return d_scale * across + scale * d_across + d_o;
            };
            if constexpr (is_requested<UJacobianPtr>) {
                Eigen::Matrix<Scalar, 3, 2> d_w_d_u;
                for (int j = 0; j < 2; ++j) {
                    Vec3T d_v = -v * (v(j) / norm);  // d(p / |p|) / d u_j
                    d_v(j) += one / norm;
                    const Scalar d_omega = detail::dot3(d_v, o);
                    d_w_d_u.col(j) = d_w(zero, d_omega, d_v - d_omega * o, Vec3T::Zero());
                }
                *d_m_d_u = d_m_d_w * d_w_d_u;
            }
            if constexpr (is_requested<CoefficientJacobianPtr>) {
                using std::cos;
                using std::sin;
                const Scalar sa = sin(k(0)), ca = cos(k(0)), sb = sin(k(1)), cb = cos(k(1));
                const Vec3T d_o[2] = {Vec3T(ca * cb, zero, -sa * cb), Vec3T(-sa * sb, cb, -ca * sb)};
                for (int j = 0; j < 2; ++j) {
                    const Scalar d_omega = detail::dot3(v, d_o[j]);
                    d_m_d_coefficients->col(j) = d_m_d_w * d_w(zero, d_omega, -(d_omega * o + omega * d_o[j]), d_o[j]);
                }
                // r0 r1 r2 move the stretch alone, e0 e1 e2 theta, L chi.
                const Vec3T along = across * inverse_l;
                const Scalar chi2 = chi.value * chi.value;
                const Scalar powers[3] = {chi.value, chi.value * chi2, chi.value * chi2 * chi2};
                for (int j = 0; j < 3; ++j) d_m_d_coefficients->col(2 + j) = d_m_d_w * (powers[j] * along);
                const Scalar theta2 = a.theta * a.theta;
                const Scalar theta_powers[3] = {one, theta2, theta2 * theta2};
                for (int j = 0; j < 3; ++j) {
                    d_m_d_coefficients->col(5 + j) = d_m_d_w * d_w(a.d_e0 * theta_powers[j], zero, Vec3T::Zero(), Vec3T::Zero());
                }
                d_m_d_coefficients->col(8) = d_m_d_w * ((d_stretch_d_chi * chi.d_linearity) * along);
            }
        }
        return in_domain;
    }

    // The distortion as if the axis were z: tan(phi') = (1 + mu) chi against tan(phi) =
    // r, and its slope: the 1-D start of unproject.
    static Scalar radial_distortion(const Parameters& lens, const Scalar& r, Scalar& slope) {
        using std::sqrt;
        const auto& k = lens.coefficients;
        const Scalar one(1);
        const Scalar norm = sqrt(one + r * r);
        const Scalar omega = one / norm, l = r / norm;
        const Angles<Scalar> a = angles(k, atan2_of(l, omega), omega, l);
        const Chi<Scalar> chi = chi_of(k(8), a.theta);
        const Scalar mu = mu_of(k, chi.value);
        const Scalar d_mu_d_chi = Scalar(2) * chi.value * (k(3) + Scalar(2) * k(4) * chi.value * chi.value);
        // d theta / d phi = -(F_omega d omega / d phi + F_l d l / d phi) / F_theta, with
        // d omega / d phi = -l, d l / d phi = omega; d phi / d r = omega^2.
        const Scalar d_theta_d_phi = a.d_l * omega - a.d_omega * l;
        slope = (one + mu + chi.value * d_mu_d_chi) * chi.d_theta * d_theta_d_phi * omega * omega;
        return (one + mu) * chi.value;
    }

private:
    // Newton steps on delta = theta - phi from 0: enough for rounding level where E is
    // below 1.
    static constexpr int kNewtonSteps = 8;

    // theta and delta = theta - phi, and theta's derivatives in omega and l (along the
    // unit circle omega^2 + l^2 = 1) and in e0 (e1, e2: times theta^2, theta^4).
    template <class T>
    struct Angles {
        T theta, delta, slope, d_omega, d_l, d_e0;
    };

    // Solves G(delta) = sin(delta) - (theta - sin(theta)) E(theta) = 0, theta = phi + delta
    // (for a unit v, omega sin(theta) - l cos(theta) = sin(theta - phi)), by Newton's method
    // from delta = 0, mrcal's start, at most kNewtonSteps steps. delta
    // itself is the unknown so that it keeps its relative precision where it is far smaller
    // than phi (q in distort needs it). omega and l are cos(phi) and sin(phi): sin(theta)
    // and cos(theta) follow from those of delta, one sine and cosine per step.
    template <class Coefficients, class T>
    static Angles<T> angles(const Coefficients& k, const T& phi, const T& omega, const T& l) {
        using std::cos;
        using std::sin;
        const T e0(k[5]), e1(k[6]), e2(k[7]), one(1);
        T delta(0), theta = phi, s = l, c = omega, slope(1), h(0);
        for (int i = 0; i <= kNewtonSteps; ++i) {
            const T sin_delta = sin(delta), cos_delta = cos(delta);
            theta = phi + delta;
            s = l * cos_delta + omega * sin_delta;
            c = omega * cos_delta - l * sin_delta;
            h = theta_minus_sin(theta, s);
            const T theta2 = theta * theta;
            const T e = e0 + theta2 * (e1 + theta2 * e2);
            const T d_e = theta * (T(2) * e1 + T(4) * e2 * theta2);
            const T value = sin_delta - h * e;
            // Newton's slope; its few roundings near theta = 0 only slow the step.
            slope = cos_delta - (one - c) * e - h * d_e;
            if (i == kNewtonSteps) break;  // the last pass only evaluates the slope
            const T step = value / slope;
            // Plain numbers stop once delta has stopped moving (two or three steps for
            // most lenses); a Jet takes every step, so that its derivatives converge too.
            if constexpr (std::is_floating_point_v<T> || is_lane_v<T>) {
                using std::abs;
                if (!(abs(step) > T(std::numeric_limits<decltype(lane_value(value))>::epsilon()) * abs(delta))) break;
            }
            delta -= step;
        }
        const T inverse_slope = one / slope;
        return {theta, delta, slope, -s * inverse_slope, c * inverse_slope, h * inverse_slope};
    }

    // chi(theta) - tan(phi), to a few roundings of its own size however small: the part
    // from delta, chi(theta) - chi(phi), by the difference formulas of tan and sin, and
    // chi(phi) - tan(phi) near the axis with the terms linear in phi taken out exactly,
    // past it with tan(phi) = l / omega and cos(phi) = omega (tan and cos of phi itself
    // lose digits near 90 degrees).
    template <class T>
    static T chi_minus_tan(const T& linearity, const T& phi, const T& omega, const T& l, const Angles<T>& a) {
        using std::cos;
        using std::sin;
        using std::tan;
        const bool near_axis = phi < T(kSeriesAngle);
        const T tan_phi = l / omega;
        const T tan_minus_phi = near_axis ? tan_minus_angle(phi) : tan_phi - phi;
        const T x = linearity * phi;
        if (linearity > T(kLinearZero)) {
            // tan(x) - tan(y) = sin(x - y) / (cos(x) cos(y))
            const T from_delta = sin(linearity * a.delta) / (linearity * cos(linearity * a.theta) * cos(x));
            // Past the axis, for L near 1 (where the two nearly cancel): tan(L phi) / L - tan(phi)
            // = (tan(L phi) - tan(phi)) / L + (1 / L - 1) tan(phi), whose terms are of the size
            // of their sum times |1 - L| / L.
            const T from_phi = near_axis              ? tan_minus_angle(x) / linearity - tan_minus_phi
                               : linearity > T(0.5) ? (sin(x - phi) / (cos(x) * omega) + (T(1) - linearity) * tan_phi) / linearity
                                                      : tan(x) / linearity - tan_phi;
            return from_delta + from_phi;
        }
        if (linearity < T(-kLinearZero)) {
            // sin(x) - sin(y) = 2 cos((x + y) / 2) sin((x - y) / 2)
            const T two(2);
            const T from_delta = two * cos(linearity * (a.theta + phi) / two) * sin(linearity * a.delta / two) / linearity;
            const T sin_x = sin(x);
            const T from_phi = near_axis ? -(theta_minus_sin(x, sin_x) / linearity + tan_minus_phi) : sin_x / linearity - tan_phi;
            return from_delta + from_phi;
        }
        return a.delta - tan_minus_phi;
    }

    // Below this angle tan(x) - x comes from its series.
    static constexpr double kSeriesAngle = 0.1;

    // tan(x) - x, and x - sin(x) from x and its sine: by their series near 0, where the
    // subtraction would cancel, and past it directly, losing at most a few digits.
    template <class T>
    static T tan_minus_angle(const T& x) {
        using std::abs;
        using std::tan;
        if (!(abs(x) < T(kSeriesAngle))) return tan(x) - x;
        // Taylor coefficients of tan from x^3 to x^23: at |x| < 0.1 the terms left out are
        // below 1e-26 of the sum.
        static const T c[] = {T(1) / T(3),
                              T(2) / T(15),
                              T(17) / T(315),
                              T(62) / T(2835),
                              T(1382) / T(155925),
                              T(21844) / T(6081075),
                              T(929569) / T(638512875),
                              T(6404582) / T(10854718875.0),
                              T(443861162) / T(1856156927625.0),
                              T(18888466084.0) / T(194896477400625.0),
                              T(113927491862.0) / T(2900518163668125.0)};
        return series_in_square(c, x);
    }
    template <class T>
    static T theta_minus_sin(const T& x, const T& sin_x) {
        using std::abs;
        if (!(abs(x) < T(0.5))) return x - sin_x;
        // 1/3! - x^2/5! + ... to x^23/23!: at |x| < 0.5 the terms left out are below 1e-33.
        static const T c[] = {T(1) / T(6),
                              T(-1) / T(120),
                              T(1) / T(5040),
                              T(-1) / T(362880),
                              T(1) / T(39916800),
                              T(-1) / T(6227020800.0),
                              T(1) / T(1307674368000.0),
                              T(-1) / T(355687428096000.0),
                              T(1) / T(121645100408832000.0),
                              T(-1) / T(51090942171709440000.0),
                              T(1) / T(25852016738884976640000.0)};
        return series_in_square(c, x);
    }
    // x^3 (c0 + c1 x^2 + c2 x^4 + ...), Horner from the smallest term.
    template <class T, std::size_t N>
    static T series_in_square(const T (&c)[N], const T& x) {
        const T x2 = x * x;
        T sum = c[N - 1];
        for (std::size_t i = N - 1; i-- > 0;) sum = c[i] + x2 * sum;
        return x * x2 * sum;
    }

    template <class T>
    struct Chi {
        T value, d_theta, d_linearity;
    };

    // chi(theta) for the linearity L, and its derivatives in theta and L.
    template <class T>
    static Chi<T> chi_of(const T& linearity, const T& theta) {
        using std::cos;
        using std::sin;
        using std::tan;
        const T x = linearity * theta;
        if (linearity > T(kLinearZero)) {
            const T t = tan(x);
            const T value = t / linearity;
            return {value, T(1) + t * t, (x * (T(1) + t * t) - t) / (linearity * linearity)};
        }
        if (linearity < T(-kLinearZero)) {
            const T s = sin(x), c = cos(x);
            return {s / linearity, c, (x * c - s) / (linearity * linearity)};
        }
        return {theta, T(1), T(0)};
    }

    template <class Coefficients, class T>
    static T mu_of(const Coefficients& k, const T& chi) {
        const T chi2 = chi * chi;
        return T(k[2]) + chi2 * (T(k[3]) + chi2 * T(k[4]));
    }

    template <class T>
    static T atan2_of(const T& y, const T& x) {
        using std::atan2;
        return atan2(y, x);
    }
};

}  // namespace libcam
