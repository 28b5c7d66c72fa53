#pragma once
// CAHVOR: the radial distortion about an optical axis O that need not be the camera's z
// axis, as JPL's camera models (Gennery, "Least-squares camera calibration including lens
// distortion and automatic editing of calibration points", 2001) and mrcal's
// LENSMODEL_CAHVOR define it. Coefficients alpha beta r0 r1 r2, in mrcal's order (its
// intrinsics are fx fy cx cy followed by these):
//
//   o     = (sin(alpha) cos(beta), sin(beta), cos(alpha) cos(beta))   the optical axis
//   omega = p . o                          p the camera point
//   tau   = |p|^2 / omega^2 - 1            tan^2 of p's angle phi from o
//   mu    = r0 + r1 tau + r2 tau^2
//   p'    = p + mu (p - omega o)           the part of p across o stretched by 1 + mu
//   m     = (p'_x / p'_z, p'_y / p'_z)     a pinhole about the camera's z axis
//
// With alpha = beta = 0 the distortion is radial about z: tan(phi') = g(tan(phi)) with
// g(t) = t (1 + r0 + r1 t^2 + r2 t^4). Unprojection solves m = distort(u) for the
// pinhole point u = (X/Z, Y/Z) with the certified solver (undistort.hpp), started from g.
//
// Valid domain: the pinhole points |u| < valid_radius(), which is worked out so that
// every point of that disc (a cone of half-angle atan(valid_radius) about z) lies within
// phi_max of o, where phi_max is the smallest of
//   - the fold: the first t where g'(t) = 1 + r0 + 3 r1 t^2 + 5 r2 t^4 reaches 0 (past
//     it two directions meet on one pixel),
//   - the angle at which the stretched point p' would reach the camera plane: g(tan(phi))
//     = cot(gamma), gamma the angle between o and z (for a tilted axis, mrcal's formula
//     goes on past it and mirrors such points),
//   - 90 degrees from o.
// On that disc each step above is one-to-one, so the map is. mrcal projects every point,
// and a point behind the camera to the pixel of its mirror image (q(-p) = q(p)); here
// points with Z <= 0, past the fold or outside the disc are flagged. The disc is a little
// smaller than the whole one-to-one region when o is tilted (by gamma on its far side).
// A lens with 1 + r0 <= 0 has an empty domain.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>

#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/pinhole.hpp"
#include "libcam/lens/undistort.hpp"
#include "libcam/lens/valid_radius.hpp"

namespace libcam {

namespace detail {

// CAHVOR's and CAHVORE's optical axis o from alpha and beta: a unit vector.
template <class T>
Eigen::Matrix<T, 3, 1> cahvor_axis(const T& alpha, const T& beta) {
    using std::cos;
    using std::sin;
    const T cb = cos(beta);
    return {sin(alpha) * cb, sin(beta), cos(alpha) * cb};
}

// The angle between the axis and the camera's z axis.
inline double cahvor_tilt(double alpha, double beta) {
    const Eigen::Vector3d o = cahvor_axis(alpha, beta);
    return std::atan2(std::hypot(o.x(), o.y()), o.z());
}

// The radius of the largest disc of pinhole points about z whose directions all lie
// within phi_max of an axis tilted by gamma from z: tan(phi_max - gamma).
inline double disc_within_angle(double phi_max, double gamma) {
    return phi_max > gamma ? std::tan(phi_max - gamma) : 0.0;
}

// Left to right in every scalar type: Eigen's dot() pairs the terms differently in
// double (SSE) than in Lane<double>, and the batch paths must give the same bits.
template <class Vec3>
auto dot3(const Vec3& a, const Vec3& b) {
    return a.x() * b.x() + a.y() * b.y() + a.z() * b.z();
}

template <class Vec3>
Vec3 cross3(const Vec3& a, const Vec3& b) {
    return {a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x()};
}

}  // namespace detail

template <class Scalar>
struct CahvorLens : OnPinholePoint<CahvorLens<Scalar>, Scalar> {
    static constexpr LensType type = LensType::Cahvor;
    static constexpr int num_coefficients = 5;
    template <class Other>
    using InScalar = CahvorLens<Other>;
    using Parameters = LensParameters<Scalar, 5>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;
    using Jacobian23 = Eigen::Matrix<Scalar, 2, 3>;
    using CoefficientJacobian = Eigen::Matrix<Scalar, 2, 5>;

    // The radius of the disc of pinhole points u = (X/Z, Y/Z) that bounds the valid
    // domain (above); +infinity for an untilted lens that never folds.
    static double valid_radius(std::span<const double> k) {
        using std::atan;
        using std::tan;
        const double r0 = k[2], r1 = k[3], r2 = k[4];
        if (!(1.0 + r0 > 0.0)) return 0.0;
        const double stretch = 1.0 + r0;
        // g'(t) = (1 + r0) (1 + 3 (r1 / (1 + r0)) t^2 + 5 (r2 / (1 + r0)) t^4): g's fold is
        // that of a radial factor 1 + (r1 / (1 + r0)) s + (r2 / (1 + r0)) s^2.
        const double numerator[] = {1.0, r1 / stretch, r2 / stretch};
        const double denominator[] = {1.0};
        const double fold = radial_valid_radius(numerator, denominator);
        const double gamma = detail::cahvor_tilt(k[0], k[1]);
        if (gamma == 0.0) return fold;  // the disc is the fold's cone
        const double half_turn = std::numbers::pi / 2;
        double phi_max = std::isinf(fold) ? half_turn : atan(fold);
        // The stretched point stays in front of the camera while g(tan(phi)) < cot(gamma).
        const double cot_gamma = 1.0 / tan(gamma);
        const auto g = [&](double t) {
            double slope;
            return axial_stretch(k, t, slope);
        };
        double high = phi_max < half_turn ? tan(phi_max) : 1.0;
        if (phi_max == half_turn) {
            while (g(high) < cot_gamma && high < 1e300) high *= 2;
        }
        if (g(high) >= cot_gamma) {
            double low = 0.0;  // g(low) < cot_gamma <= g(high), g increasing between
            for (int i = 0; i < 200 && high - low > 1e-16 * high; ++i) {
                const double middle = low + (high - low) / 2;
                (g(middle) < cot_gamma ? low : high) = middle;
            }
            phi_max = std::min(phi_max, atan(low));
        }
        return detail::disc_within_angle(phi_max, gamma);
    }

    static Parameters parameters(std::span<const double> k) { return lens_parameters<Scalar, 5>(k, valid_radius(k)); }

    // project, unproject and ray_from_undistorted: OnPinholePoint's (pinhole.hpp).

    // m of the pinhole point u = (X/Z, Y/Z); false outside the valid domain.
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& u, Vec2T& m, UJacobianPtr d_m_d_u = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        using std::cos;
        using std::sin;
        const auto& k = lens.coefficients;
        const Scalar one(1), two(2);
        const Vec3T o = detail::cahvor_axis(k(0), k(1));
        const Vec3T p(u.x(), u.y(), one);
        const Scalar omega = detail::dot3(p, o);
        const Scalar inverse_omega = one / omega;
        // tau and the part of p across the axis from c = p x o, each to a few roundings of
        // its own size: |p|^2 / omega^2 - 1 and p - omega o would cancel near the axis,
        // where a tilted lens's image centre comes from them (at f = 1e12 px, 1e-5 px).
        const Vec3T c = detail::cross3(p, o);
        const Scalar tau = detail::dot3(c, c) * inverse_omega * inverse_omega;
        const Scalar mu = k(2) + tau * (k(3) + tau * k(4));
        const Vec3T across = detail::cross3(o, c);  // p - omega o, o being a unit vector
        const Vec3T stretched = p + mu * across;
        const Scalar inverse_z = one / stretched.z();
        m = Vec2T(stretched.x() * inverse_z, stretched.y() * inverse_z);
        const bool in_domain = (u.squaredNorm() < lens.valid_radius * lens.valid_radius) & (omega > Scalar(0)) &
                               (stretched.z() > Scalar(0)) & all_finite(m);  // &, not &&: no branch

        if constexpr (is_requested<UJacobianPtr> || is_requested<CoefficientJacobianPtr>) {
            Jacobian23 d_m_d_stretched;
            d_m_d_stretched << inverse_z, Scalar(0), -m.x() * inverse_z,  //
                Scalar(0), inverse_z, -m.y() * inverse_z;
            const Scalar d_mu_d_tau = k(3) + two * tau * k(4);
            // d tau / d omega at fixed |p|: -2 |p|^2 / omega^3.
            const Scalar d_tau_d_omega = -two * (tau + one) * inverse_omega;
            if constexpr (is_requested<UJacobianPtr>) {
                Eigen::Matrix<Scalar, 3, 2> d_stretched_d_u;
                for (int j = 0; j < 2; ++j) {
                    const Scalar d_tau = two * u(j) * inverse_omega * inverse_omega + d_tau_d_omega * o(j);
                    d_stretched_d_u.col(j) = d_mu_d_tau * d_tau * across - (mu * o(j)) * o;
                    d_stretched_d_u(j, j) += one + mu;
                }
                *d_m_d_u = d_m_d_stretched * d_stretched_d_u;
            }
            if constexpr (is_requested<CoefficientJacobianPtr>) {
                const Scalar sa = sin(k(0)), ca = cos(k(0)), sb = sin(k(1)), cb = cos(k(1));
                const Vec3T d_o[2] = {Vec3T(ca * cb, Scalar(0), -sa * cb), Vec3T(-sa * sb, cb, -ca * sb)};
                for (int j = 0; j < 2; ++j) {
                    const Scalar d_omega = detail::dot3(p, d_o[j]);
                    const Scalar d_mu = d_mu_d_tau * d_tau_d_omega * d_omega;
                    const Vec3T d_across = -(d_omega * o + omega * d_o[j]);
                    d_m_d_coefficients->col(j) = d_m_d_stretched * (d_mu * across + mu * d_across);
                }
                const Vec2T d_m_d_r0 = d_m_d_stretched * across;
                d_m_d_coefficients->col(2) = d_m_d_r0;
                d_m_d_coefficients->col(3) = tau * d_m_d_r0;
                d_m_d_coefficients->col(4) = (tau * tau) * d_m_d_r0;
            }
        }
        return in_domain;
    }

    // The distortion as if the axis were z: g(r) = r (1 + r0 + r1 r^2 + r2 r^4) and its
    // slope, the 1-D start of unproject (exact for alpha = beta = 0).
    static Scalar radial_distortion(const Parameters& lens, const Scalar& r, Scalar& slope) {
        return axial_stretch(lens.coefficients, r, slope);
    }

private:
    // g(t) = t (1 + r0 + r1 t^2 + r2 t^4), tan of the stretched angle from the axis
    // against tan of the angle, and its slope g'(t), from coefficients k (alpha beta r0 r1
    // r2) in any container: the valid domain's (double) and the solver's start.
    template <class T, class Coefficients>
    static T axial_stretch(const Coefficients& k, const T& t, T& slope) {
        const T s = t * t, one(1);
        slope = one + T(k[2]) + s * (T(3) * T(k[3]) + T(5) * s * T(k[4]));
        return t * (one + T(k[2]) + s * (T(k[3]) + s * T(k[4])));
    }
};

}  // namespace libcam
