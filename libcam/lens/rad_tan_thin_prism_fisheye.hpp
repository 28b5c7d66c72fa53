#pragma once
// RAD_TAN_THIN_PRISM_FISHEYE: Project Aria's "Fisheye624" (six radial, two tangential,
// four thin-prism coefficients), as COLMAP's RadTanThinPrismFisheyeModel defines it,
// coefficients in COLMAP's order k0 k1 k2 k3 k4 k5 p0 p1 s0 s1 s2 s3:
//
//   u  = theta (X, Y) / |(X, Y)|,   theta = atan2(|(X, Y)|, Z)     the equidistant point
//   v  = u (1 + k0 theta^2 + k1 theta^4 + ... + k5 theta^12)       radial, in theta
//   r2 = |v|^2
//   m  = v + (2 p1 v_x v_y + p0 (r2 + 2 v_x^2),  p1 (r2 + 2 v_y^2) + 2 p0 v_x v_y)
//          + (s0 r2 + s1 r2^2,  s2 r2 + s3 r2^2)
//
// Unlike THIN_PRISM_FISHEYE, the decentering and prism terms act on the radially
// distorted point v. p0 plays the part of OpenCV's p2 and p1 of OpenCV's p1
// (decentering.hpp writes them OpenCV's way). COLMAP takes points in front of the
// camera only; this formula in theta carries on behind it (the same map where both are
// defined). The pixel is K m; COLMAP's pixel centres are at +0.5.
//
// Valid domain: theta < valid_radius(), the smallest of pi, the first theta where the
// radial part folds over, and the theta whose |v| is rho*, where the decentering and
// prism terms could first fold the image: m = v + g(v) is one-to-one on the disc
// |v| < rho* if |dg/dv| < 1 there, and |dg/dv| <= 12 (|p0| + |p1|) rho + 2 (|s0| + |s2|)
// rho + 4 (|s1| + |s3|) rho^3 (a bound of its Frobenius norm). Those terms grow with
// |v|^4 while the radial part grows with theta: far out (a lens calibrated to 100
// degrees, evaluated at 170) they would dominate. Points on or next to the backward axis
// are flagged (fisheye.hpp).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>
#include <numbers>
#include <span>

#include "libcam/lens/decentering.hpp"
#include "libcam/lens/fisheye.hpp"
#include "libcam/lens/lane.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/undistort.hpp"
#include "libcam/lens/valid_radius.hpp"

namespace libcam {

template <class Scalar>
struct RadTanThinPrismFisheyeLens : OnEquidistantPoint<RadTanThinPrismFisheyeLens<Scalar>, Scalar> {
    static constexpr LensType type = LensType::RadTanThinPrismFisheye;
    static constexpr int num_coefficients = 12;
    template <class Other>
    using InScalar = RadTanThinPrismFisheyeLens<Other>;
    using Parameters = LensParameters<Scalar, 12>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;

    static constexpr int kRadial = 6;  // k0..k5

    // The angle theta (radians) that bounds the valid domain (above).
    static double valid_radius(std::span<const double> k) {
        const double stretch[] = {1.0, k[0], k[1], k[2], k[3], k[4], k[5]};
        const double fold = FisheyeLens<double>::angle_fold(stretch);
        // rho*: where the bound on |dg/dv| reaches 1.
        using std::abs;
        const double bound[] = {-1.0, 12.0 * (abs(k[6]) + abs(k[7])) + 2.0 * (abs(k[8]) + abs(k[10])), 0.0,
                                4.0 * (abs(k[9]) + abs(k[11]))};
        const double rho = smallest_positive_root(bound);
        return std::min(fold, angle_of_radius(k, rho, fold));
    }

    static Parameters parameters(std::span<const double> k) { return lens_parameters<Scalar, 12>(k, valid_radius(k)); }

    // project, unproject and ray_from_undistorted: OnEquidistantPoint's (fisheye.hpp).

    // m of the equidistant point u; false outside the valid domain.
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& u, Vec2T& m, UJacobianPtr d_m_d_u = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        const auto k = [&lens](int i) { return by_value(lens.coefficients(i)); };  // as numbers: see by_value
        const Scalar s = u.squaredNorm(), two(2), four(4);
        const bool in_domain = s < lens.valid_radius * lens.valid_radius;
        Scalar stretch_slope;
        const Scalar factor = stretch(lens, s, stretch_slope);
        const Vec2T v = u * factor;
        const Scalar r2 = v.squaredNorm();
        // Decentering in OpenCV's naming: OpenCV's p1 is p1 (index 7), its p2 is p0 (index 6).
        const Scalar p1 = k(7), p2 = k(6);
        m = v + detail::decentering(p1, p2, v) + Vec2T(r2 * (k(8) + r2 * k(9)), r2 * (k(10) + r2 * k(11)));
        if constexpr (is_requested<UJacobianPtr> || is_requested<CoefficientJacobianPtr>) {
            Jacobian22 d_m_d_v = Jacobian22::Identity() + detail::decentering_jacobian(p1, p2, v);
            d_m_d_v.row(0) += (two * k(8) + four * k(9) * r2) * v.transpose();
            d_m_d_v.row(1) += (two * k(10) + four * k(11) * r2) * v.transpose();
            if constexpr (is_requested<UJacobianPtr>) {
                const Jacobian22 d_v_d_u =
                    Jacobian22::Identity() * factor + (two * stretch_slope) * u * u.transpose();
                *d_m_d_u = d_m_d_v * d_v_d_u;
            }
            if constexpr (is_requested<CoefficientJacobianPtr>) {
                const Vec2T d_m_d_stretch = d_m_d_v * u;  // v = u factor; d factor / d k_i = s^(i + 1)
                Scalar power = s;
                for (int i = 0; i < kRadial; ++i, power *= s) d_m_d_coefficients->col(i) = d_m_d_stretch * power;
                const Jacobian22 d_decentering = detail::decentering_coefficient_jacobian(v);  // d/d p1, d/d p2
                d_m_d_coefficients->col(6) = d_decentering.col(1);
                d_m_d_coefficients->col(7) = d_decentering.col(0);
                const Scalar zero(0);
                d_m_d_coefficients->col(8) << r2, zero;
                d_m_d_coefficients->col(9) << r2 * r2, zero;
                d_m_d_coefficients->col(10) << zero, r2;
                d_m_d_coefficients->col(11) << zero, r2 * r2;
            }
        }
        return in_domain;
    }

    // The radial part alone, theta (1 + k0 theta^2 + ...), and its slope: the 1-D start
    // of unproject.
    static Scalar radial_distortion(const Parameters& lens, const Scalar& theta, Scalar& slope) {
        const Scalar s = theta * theta;
        Scalar stretch_slope;
        const Scalar factor = stretch(lens, s, stretch_slope);
        slope = factor + Scalar(2) * s * stretch_slope;
        return theta * factor;
    }

private:
    // The theta in [0, fold] whose radial image |v| = theta (1 + k0 theta^2 + ...) is
    // rho (fold if it never reaches rho there), by bisection: the radial part increases
    // on [0, fold]. Once per camera.
    static double angle_of_radius(std::span<const double> k, double rho, double fold) {
        const std::array<double, kRadial> c{k[0], k[1], k[2], k[3], k[4], k[5]};
        const auto radial = [&](double theta) {
            double slope = 0;
            return theta * stretch_polynomial(c, theta * theta, slope);
        };
        if (!(radial(fold) > rho)) return fold;
        double low = 0.0, high = fold;
        for (int i = 0; i < 200 && high - low > 1e-15 * high; ++i) {
            const double middle = 0.5 * (low + high);
            (radial(middle) < rho ? low : high) = middle;
        }
        return low;
    }

    // The radial stretch 1 + k s + ... in s = theta^2, and its derivative in s.
    static Scalar stretch(const Parameters& lens, const Scalar& s, Scalar& slope) {
        const auto k = [&lens](int i) { return by_value(lens.coefficients(i)); };  // as numbers: see by_value
        return stretch_polynomial(std::array<Scalar, 6>{k(0), k(1), k(2), k(3), k(4), k(5)}, s, slope);
    }
};

}  // namespace libcam
