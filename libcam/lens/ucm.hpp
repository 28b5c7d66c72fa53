#pragma once
// UCM: the unified camera model (Geyer and Daniilidis 2000; Mei and Rives, "Single View
// Point Omnidirectional Camera Calibration from Planar Grids", ICRA 2007) with one
// coefficient xi, as OpenCV's cv::omnidir (without its distortion), camodocal and
// Kalibr ("omni-none") define it:
//
//   m = (x, y) / (z + xi |p|)
//
// (the pixel is K m). The point is carried onto the unit sphere, then imaged by a
// pinhole xi behind its centre. It is DOUBLE_SPHERE with alpha = 0 for xi <= 1, and
// goes on past it: calibrations of real fisheye lenses often have xi > 1 (the pinhole
// outside the sphere). basalt's "ucm" is the same model written as EUCM with beta = 1:
// its alpha is xi / (1 + xi) and its focal length 1 / (1 + xi) times this one's.
//
// Unprojection is closed form (Mei and Rives): with r^2 = mx^2 + my^2,
//
//   s   = (xi + sqrt(1 + (1 - xi^2) r^2)) / (1 + r^2)
//   ray = (s mx, s my, s - xi)
//
// a unit vector.
//
// Valid domain: z / |p| > -w, w = xi for xi <= 1 (the denominator's zero: m goes to
// infinity, the image is unbounded), 1 / xi for xi > 1 (the tangent cone of the pinhole,
// whose image is the rim r^2 = 1 / (xi^2 - 1)). So valid_radius() = acos(-w): past 90
// degrees for xi > 0, short of it for xi < 0. xi must be above -1; Lens::validate
// refuses others.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <string>

#include "libcam/lens/lane.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"

namespace libcam {

template <class Scalar>
struct UcmLens {
    static constexpr LensType type = LensType::Ucm;
    static constexpr int num_coefficients = 1;
    template <class Other>
    using InScalar = UcmLens<Other>;
    using Parameters = LensParameters<Scalar, 1>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;

    // The largest angle from the optical axis the lens images: acos(-w) (above).
    static double valid_radius(std::span<const double> c) {
        const double xi = c[0];
        const double w = xi <= 1 ? xi : 1 / xi;
        return std::acos(std::clamp(-w, -1.0, 1.0));
    }

    static Parameters parameters(std::span<const double> c) { return lens_parameters<Scalar, 1>(c, valid_radius(c)); }

    static void check_coefficients(std::span<const double> c, const char* field) {
        if (!(c[0] > -1)) {
            throw InvalidArgument(std::string(field) + "[0] (xi): must be above -1, got " + format_number(c[0]));
        }
    }

    // False outside the valid domain (z / |p| at or below -w, or the origin) and where m
    // is not finite; evaluated without branches (pinhole.hpp).
    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        using std::sqrt;
        const Scalar xi = by_value(lens.coefficients(0));
        const Scalar x = point.x(), y = point.y(), z = point.z();
        const Scalar rho2 = x * x + y * y;
        const Scalar d = sqrt(rho2 + z * z);
        // z + xi d; where z and xi d have opposite signs the two cancel, and the same
        // number is taken as ((1 - xi^2) z^2 - xi^2 rho^2) / (z - xi d), whose
        // denominator does not cancel (nor its numerator for xi >= 1).
        const Scalar sum = z + xi * d;
        const Scalar difference_form = ((Scalar(1) - xi * xi) * z * z - xi * xi * rho2) / (z - xi * d);
        const bool terms_cancel = (z < Scalar(0)) == (xi > Scalar(0));
        const Scalar denominator = terms_cancel ? difference_form : sum;
        const Scalar w = xi <= Scalar(1) ? xi : Scalar(1) / xi;
        const bool in_domain = z > -w * d;
        const Scalar inverse = Scalar(1) / denominator;
        m = Vec2T(x * inverse, y * inverse);
        if constexpr (is_requested<PointJacobianPtr>) {
            ratio_point_jacobian(m, inverse, Vec3T(xi * point / d + Vec3T::UnitZ()), d_m_d_point);
        }
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            ratio_coefficient_jacobian(m, inverse, Eigen::Matrix<Scalar, 1, 1>(d), d_m_d_coefficients);  // d D / d xi
        }
        return in_domain & (denominator > Scalar(0)) & all_finite(m);
    }

    // The unit ray through m; false where m has none: xi > 1 and m on or past the rim,
    // the domain's edge. For xi <= 1 every finite m has a ray inside the domain. Decided
    // on m, as for DOUBLE_SPHERE (double_sphere.hpp).
    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        using std::sqrt;
        const Scalar xi = by_value(lens.coefficients(0));
        const Scalar r2 = m.squaredNorm();
        const Scalar radicand = Scalar(1) + (Scalar(1) - xi * xi) * r2;
        const Scalar s = (xi + sqrt(radicand)) / (Scalar(1) + r2);
        ray = Vec3T(s * m.x(), s * m.y(), s - xi);
        const bool inside_rim = (xi <= Scalar(1)) | (radicand > Scalar(0));
        // 1 + r^2 past the type's range would give the ray (0, 0, -xi): flagged (s is
        // positive for every other m).
        return inside_rim & (s > Scalar(0)) & all_finite(ray);
    }
};

}  // namespace libcam
