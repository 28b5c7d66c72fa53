#pragma once
// EUCM: the Enhanced Unified Camera Model of Khomutenko, Garcia and Martinet ("An
// Enhanced Unified Camera Model", IEEE RA-L 2016), as basalt (camera type "eucm") and
// Kalibr ("eucm-none") define it, with coefficients (alpha, beta):
//
//   d = sqrt(beta (x^2 + y^2) + z^2)
//   m = (x, y) / (alpha d + (1 - alpha) z)
//
// (the pixel is K m). The point is carried onto the ellipsoid beta (x^2 + y^2) + z^2 = 1,
// then imaged by a pinhole alpha / (1 - alpha) behind its centre. With beta = 1 it is the
// unified model in basalt's parametrisation (a UCM with xi = alpha / (1 - alpha) and a
// focal length 1 / (1 - alpha) times as long).
//
// Unprojection is closed form: with r^2 = mx^2 + my^2,
//
//   k = (1 - alpha^2 beta r^2) / (alpha sqrt(1 - (2 alpha - 1) beta r^2) + 1 - alpha)
//   ray = (mx, my, k) / sqrt(r^2 + k^2)
//
// a unit vector (k is z over the denominator, for the point on the ellipsoid).
//
// Valid domain: with w = alpha / (1 - alpha) for alpha <= 1/2, (1 - alpha) / alpha
// otherwise, the point's z / d > -w. For alpha <= 1/2 that is where the denominator
// is positive (m goes to infinity at the edge: the image is unbounded); for alpha > 1/2
// the pinhole lies outside the ellipsoid and its tangent cone touches it exactly at
// z / d = -w, whatever beta (the tangent condition beta x^2 + z (z + 1/w) = 0 with the
// ellipsoid gives z = -w); its image is the rim r^2 = 1 / ((2 alpha - 1) beta). As an
// angle theta from the optical axis: cos(theta) > c_min = -w sqrt(beta / (1 - w^2 + w^2 beta)),
// so valid_radius() = acos(c_min). The coefficients must satisfy 0 <= alpha <= 1 and
// beta > 0 (basalt's bounds); Lens::validate refuses others.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <string>

#include "libcam/lens/lane.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"

namespace libcam {

template <class Scalar>
struct EucmLens {
    static constexpr LensType type = LensType::Eucm;
    static constexpr int num_coefficients = 2;
    template <class Other>
    using InScalar = EucmLens<Other>;
    using Parameters = LensParameters<Scalar, 2>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;

    // The largest angle from the optical axis the lens images: acos(c_min) (above).
    static double valid_radius(std::span<const double> c) {
        const double alpha = c[0], beta = c[1];
        const double w = alpha <= 0.5 ? alpha / (1 - alpha) : (1 - alpha) / alpha;
        const double c_min = -w * std::sqrt(beta / (1 - w * w + w * w * beta));
        return std::acos(std::clamp(c_min, -1.0, 1.0));
    }

    static Parameters parameters(std::span<const double> c) { return lens_parameters<Scalar, 2>(c, valid_radius(c)); }

    // Where `libcam fit` starts (lens_models.hpp's fit_start): alpha = 1/2, beta = 1, the
    // stereographic projection 2 tan(theta / 2) with K's focal length (as DOUBLE_SPHERE's).
    static std::array<double, 2> fit_start() { return {0.5, 1.0}; }

    // basalt's bounds (see above); InvalidArgument naming the coefficient otherwise.
    static void check_coefficients(std::span<const double> c, const char* field) {
        if (!(c[0] >= 0 && c[0] <= 1)) {
            throw InvalidArgument(std::string(field) + "[0] (alpha): must be in [0, 1], got " + format_number(c[0]));
        }
        if (!(c[1] > 0)) {
            throw InvalidArgument(std::string(field) + "[1] (beta): must be positive, got " + format_number(c[1]));
        }
    }

    // False outside the valid domain (z / d at or below -w, or the origin) and where m
    // is not finite; evaluated without branches (pinhole.hpp).
    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        using std::sqrt;
        const Scalar alpha = by_value(lens.coefficients(0)), beta = by_value(lens.coefficients(1));
        const Scalar x = point.x(), y = point.y(), z = point.z();
        const Scalar rho2 = x * x + y * y;
        const Scalar d = sqrt(beta * rho2 + z * z);
        // alpha d + (1 - alpha) z; for z < 0 the two terms cancel, and the same number is
        // taken as (alpha^2 beta rho^2 + (2 alpha - 1) z^2) / (alpha d - (1 - alpha) z),
        // whose denominator does not cancel (nor its numerator for alpha >= 1/2).
        const Scalar sum = alpha * d + (Scalar(1) - alpha) * z;
        const Scalar difference_form = (alpha * alpha * beta * rho2 + (Scalar(2) * alpha - Scalar(1)) * z * z) /
                                       (alpha * d - (Scalar(1) - alpha) * z);
        const Scalar denominator = z >= Scalar(0) ? by_value(sum) : by_value(difference_form);
        const Scalar w = alpha <= Scalar(0.5) ? alpha / (Scalar(1) - alpha) : (Scalar(1) - alpha) / alpha;
        const bool in_domain = z > -w * d;
        const Scalar inverse = Scalar(1) / denominator;
        m = Vec2T(x * inverse, y * inverse);
        if constexpr (is_requested<PointJacobianPtr>) {
            const Vec3T d_d = Vec3T(beta * x, beta * y, z) / d;
            ratio_point_jacobian(m, inverse, Vec3T(alpha * d_d + (Scalar(1) - alpha) * Vec3T::UnitZ()), d_m_d_point);
        }
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            // d D / d alpha and d D / d beta.
            const Vec2T d_denominator(d - z, alpha * rho2 / (Scalar(2) * d));
            ratio_coefficient_jacobian(m, inverse, d_denominator, d_m_d_coefficients);
        }
        return in_domain & (denominator > Scalar(0)) & all_finite(m);
    }

    // The unit ray through m; false where m has none: alpha > 1/2 and m on or past the
    // rim, which is the domain's edge. For alpha <= 1/2 every finite m has a ray inside
    // the domain. Decided on m, as for DOUBLE_SPHERE (double_sphere.hpp): near the edge
    // a ray cannot be rounded closer to it than eps.
    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        using std::sqrt;
        const Scalar alpha = by_value(lens.coefficients(0)), beta = by_value(lens.coefficients(1));
        const Scalar r2 = m.squaredNorm();
        const Scalar rim_term = (Scalar(2) * alpha - Scalar(1)) * beta;
        const Scalar radicand = Scalar(1) - rim_term * r2;
        const Scalar k = (Scalar(1) - alpha * alpha * beta * r2) / (alpha * sqrt(radicand) + Scalar(1) - alpha);
        const Scalar inverse_norm = Scalar(1) / sqrt(r2 + k * k);
        ray = Vec3T(m.x() * inverse_norm, m.y() * inverse_norm, k * inverse_norm);
        const bool inside_rim = (rim_term <= Scalar(0)) | (radicand > Scalar(0));
        // r^2 + k^2 past the type's range (|m| beyond about 1e154 in double) would give
        // a zero ray: flagged.
        return inside_rim & (inverse_norm > Scalar(0)) & all_finite(ray);
    }
};

}  // namespace libcam
