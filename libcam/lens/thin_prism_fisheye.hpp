#pragma once
// THIN_PRISM_FISHEYE: COLMAP's fisheye with radial, decentering and thin-prism terms
// (COLMAP's ThinPrismFisheyeCameraModel, after Weng et al., "Camera Calibration with
// Distortion Models and Accuracy Evaluation", TPAMI 1992), coefficients in COLMAP's
// order k1 k2 p1 p2 k3 k4 sx1 sy1:
//
//   u  = theta (X, Y) / |(X, Y)|,   theta = atan2(|(X, Y)|, Z)     the equidistant point
//   s  = |u|^2 = theta^2
//   m  = u (1 + k1 s + k2 s^2 + k3 s^3 + k4 s^4)
//        + (2 p1 u_x u_y + p2 (s + 2 u_x^2),  p1 (s + 2 u_y^2) + 2 p2 u_x u_y)
//        + (sx1 s,  sy1 s)
//
// All the terms act on u, the undistorted point, as in COLMAP (where the radial part
// with p1 p2 sx1 sy1 zero is FISHEYE's). COLMAP writes theta = atan(|(X/Z, Y/Z)|) and so
// takes points in front of the camera only; this formula in theta carries on behind it,
// as FISHEYE's does (the same map where both are defined). The pixel is K m; COLMAP's
// pixel centres are at +0.5 (convert/colmap_models.hpp).
//
// Valid domain: theta < valid_radius(), the smallest of pi, the first theta where the
// radial part theta (1 + k1 theta^2 + ...) stops increasing, and the theta up to which
// the decentering and prism terms provably cannot fold the image (their derivative,
// bounded by (12 (|p1| + |p2|) + 2 (|sx1| + |sy1|)) theta, stays below the radial part's
// smallest stretch). Points on the backward axis, or so
// close to it that X^2 + Y^2 is not a normal number, are flagged (fisheye.hpp).

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
struct ThinPrismFisheyeLens : OnEquidistantPoint<ThinPrismFisheyeLens<Scalar>, Scalar> {
    static constexpr LensType type = LensType::ThinPrismFisheye;
    static constexpr int num_coefficients = 8;
    template <class Other>
    using InScalar = ThinPrismFisheyeLens<Other>;
    using Parameters = LensParameters<Scalar, 8>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;

    // The angle theta (radians) that bounds the valid domain (above).
    static double valid_radius(std::span<const double> k) {
        const double stretch[] = {1.0, k[0], k[1], k[4], k[5]};
        const double fold = FisheyeLens<double>::angle_fold(stretch);
        return std::min(fold, injective_radius(k, fold));
    }

    static Parameters parameters(std::span<const double> k) { return lens_parameters<Scalar, 8>(k, valid_radius(k)); }

    // project, unproject and ray_from_undistorted: OnEquidistantPoint's (fisheye.hpp).

    // m of the equidistant point u; false outside the valid domain.
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& u, Vec2T& m, UJacobianPtr d_m_d_u = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        const auto k = [&lens](int i) { return by_value(lens.coefficients(i)); };  // as numbers: see by_value
        const Scalar s = u.squaredNorm(), two(2);
        const bool in_domain = s < lens.valid_radius * lens.valid_radius;
        Scalar stretch_slope;
        const Scalar factor = stretch(lens, s, stretch_slope);
        const Vec2T prism(k(6), k(7));
        m = u * factor + detail::decentering(k(2), k(3), u) + prism * s;
        if constexpr (is_requested<UJacobianPtr>) {
            *d_m_d_u = Jacobian22::Identity() * factor + (two * stretch_slope) * u * u.transpose() +
                       detail::decentering_jacobian(k(2), k(3), u) + two * prism * u.transpose();
        }
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            const Scalar zero(0), s2 = s * s;
            d_m_d_coefficients->col(0) = u * s;
            d_m_d_coefficients->col(1) = u * s2;
            d_m_d_coefficients->template middleCols<2>(2) = detail::decentering_coefficient_jacobian(u);
            d_m_d_coefficients->col(4) = u * (s2 * s);
            d_m_d_coefficients->col(5) = u * (s2 * s2);
            d_m_d_coefficients->col(6) << s, zero;
            d_m_d_coefficients->col(7) << zero, s;
        }
        return in_domain;
    }

    // The radial part alone, theta (1 + k1 theta^2 + ...), and its slope: the 1-D start
    // of unproject.
    static Scalar radial_distortion(const Parameters& lens, const Scalar& theta, Scalar& slope) {
        const Scalar s = theta * theta;
        Scalar stretch_slope;
        const Scalar factor = stretch(lens, s, stretch_slope);
        slope = factor + Scalar(2) * s * stretch_slope;
        return theta * factor;
    }

private:
    // The largest theta <= fold up to which the decentering and prism terms g(u) provably
    // cannot fold the image: m = R(u) + g(u) with R the radial part is one-to-one where
    // |dg/du| / sigma < 1, sigma the smallest singular value of dR/du over the disc so far
    // (min(D, D + 2 s D'), the stretch across and along the radius) and |dg/du| <=
    // (12 (|p1| + |p2|) + 2 (|sx1| + |sy1|)) theta. Scanned in steps of fold / 4096: once
    // per camera.
    static double injective_radius(std::span<const double> k, double fold) {
        using std::abs;
        const double growth = 12.0 * (abs(k[2]) + abs(k[3])) + 2.0 * (abs(k[6]) + abs(k[7]));
        if (growth == 0.0) return fold;
        const std::array<double, 4> c{k[0], k[1], k[4], k[5]};
        constexpr int kSteps = 4096;
        double sigma = 1.0;
        for (int i = 1; i <= kSteps; ++i) {
            const double theta = fold * i / kSteps, s = theta * theta;
            double slope = 0;
            const double stretch = stretch_polynomial(c, s, slope);
            sigma = std::min(sigma, std::min(stretch, stretch + 2.0 * s * slope));
            if (!(growth * theta < sigma)) return fold * (i - 1) / kSteps;
        }
        return fold;
    }

    // The radial stretch 1 + k s + ... in s = theta^2, and its derivative in s.
    static Scalar stretch(const Parameters& lens, const Scalar& s, Scalar& slope) {
        const auto k = [&lens](int i) { return by_value(lens.coefficients(i)); };  // as numbers: see by_value
        return stretch_polynomial(std::array<Scalar, 4>{k(0), k(1), k(4), k(5)}, s, slope);
    }
};

}  // namespace libcam
