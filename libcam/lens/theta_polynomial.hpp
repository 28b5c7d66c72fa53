#pragma once
// THETA_POLYNOMIAL: the image radius as a polynomial of the angle from the axis, with
// every power of the angle (Valeo's WoodScape calibrations, their "radial_poly" model:
// the dataset's scripts/calibration/projection.py, RadialPolyCamProjection):
//
//   theta = atan2(|(X, Y)|, Z)
//   rho   = k1 theta + k2 theta^2 + k3 theta^3 + k4 theta^4
//   m     = rho (X, Y) / |(X, Y)|
//
// OpenCV's FISHEYE has the odd powers only (theta (1 + k1 theta^2 + ...)), so neither
// contains the other. WoodScape gives rho in pixels: its camera is this lens with
// fx = 1 and fy = its aspect_ratio (io/detail/woodscape_format.hpp), so that m is in
// pixels and the coefficients are WoodScape's own numbers.
//
// Internally u = theta (X, Y) / |(X, Y)| (FISHEYE's equidistant point, |u| = theta) and
// m = S(theta) u with S(theta) = k1 + k2 theta + k3 theta^2 + k4 theta^3.
//
// Valid domain: theta < valid_radius() = min(pi, the first theta > 0 where rho stops
// increasing, a root of k1 + 2 k2 theta + 3 k3 theta^2 + 4 k4 theta^3). k1 must be
// positive (rho grows from the centre); WoodScape's own inverse likewise keeps the
// smallest angle below pi that reaches a radius.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <span>
#include <string>

#include "libcam/error.hpp"
#include "libcam/lens/fisheye.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/valid_radius.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

template <class Scalar>
struct ThetaPolynomialLens : OnEquidistantPoint<ThetaPolynomialLens<Scalar>, Scalar> {
    static constexpr LensType type = LensType::ThetaPolynomial;
    static constexpr int num_coefficients = 4;
    template <class Other>
    using InScalar = ThetaPolynomialLens<Other>;
    using Parameters = LensParameters<Scalar, 4>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;

    static void check_coefficients(std::span<const double> k, const char* field) {
        if (!(k[0] > 0.0)) {
            throw InvalidArgument(std::string(field) + "[0] (k1): must be positive (the radius must grow with the " +
                                  "angle at the centre), got " + format_number(k[0]));
        }
    }

    // The starting guess of `libcam fit` and the like: the equidistant lens rho = theta.
    static std::array<double, 4> fit_start(double) { return {1.0, 0.0, 0.0, 0.0}; }

    // The angle (radians, at most pi) past which rho stops increasing.
    static double valid_radius(std::span<const double> k) {
        if (!(k[0] > 0.0)) return 0.0;
        const double slope[] = {k[0], 2 * k[1], 3 * k[2], 4 * k[3]};
        return std::min(std::numbers::pi, smallest_positive_root(slope));
    }

    static Parameters parameters(std::span<const double> k) { return lens_parameters<Scalar, 4>(k, valid_radius(k)); }

    // m = S(theta) u for the equidistant point u (|u| = theta); false outside the domain.
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& u, Vec2T& m, UJacobianPtr d_m_d_u = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        using std::sqrt;
        const Scalar s = u.squaredNorm();
        const Scalar theta = sqrt(s);
        const bool in_domain = s < lens.valid_radius * lens.valid_radius;
        const Scalar factor = stretch(lens, theta);
        m = u * factor;
        if constexpr (is_requested<UJacobianPtr>) {
            // d S(|u|) / d u = S'(theta) u / theta; S'(theta) / theta = k2 / theta + 2 k3 + 3 k4 theta,
            // whose k2 term is singular at the centre: the outer product u u^T / theta vanishes there.
            const auto& k = lens.coefficients;
            const bool at_centre = !(theta > Scalar(0));
            const Scalar inverse_theta = at_centre ? Scalar(0) : Scalar(Scalar(1) / theta);
            const Scalar slope_over_theta =
                k(1) * inverse_theta + Scalar(2) * k(2) + Scalar(3) * k(3) * theta;
            *d_m_d_u = Jacobian22::Identity() * factor + slope_over_theta * u * u.transpose();
        }
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            Scalar power(1);
            for (int i = 0; i < 4; ++i, power *= theta) d_m_d_coefficients->col(i) = u * power;
        }
        return in_domain & all_finite(m);
    }

    // rho(theta) and its slope: the 1-D start of unproject.
    static Scalar radial_distortion(const Parameters& lens, const Scalar& theta, Scalar& slope) {
        const auto& k = lens.coefficients;
        slope = k(0) + theta * (Scalar(2) * k(1) + theta * (Scalar(3) * k(2) + theta * Scalar(4) * k(3)));
        return theta * stretch(lens, theta);
    }

private:
    // S(theta) = rho(theta) / theta.
    static Scalar stretch(const Parameters& lens, const Scalar& theta) {
        const auto& k = lens.coefficients;
        return k(0) + theta * (k(1) + theta * (k(2) + theta * k(3)));
    }
};

}  // namespace libcam
