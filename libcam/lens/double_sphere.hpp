#pragma once
// DOUBLE_SPHERE: the Double Sphere camera of Usenko, Demmel and Cremers ("The Double
// Sphere Camera Model", 3DV 2018), as basalt (camera type "ds") and Kalibr ("ds-none")
// define it, with coefficients (xi, alpha):
//
//   d1 = |p|,  zeta = xi d1 + z,  d2 = sqrt(x^2 + y^2 + zeta^2)
//   m  = (x, y) / (alpha d2 + (1 - alpha) zeta)
//
// (the pixel is K m). The point is projected onto a unit sphere, then onto a second
// unit sphere xi further along the axis, then by a pinhole camera moved alpha / (1 - alpha)
// off that sphere's centre. With alpha = 0 it is the unified camera model (UCM, and
// OpenCV's cv::omnidir without distortion) with the same xi.
//
// Unprojection is closed form (the paper's equations 45-47):
//
//   r^2 = mx^2 + my^2,  mz = (1 - alpha^2 r^2) / (alpha sqrt(1 - (2 alpha - 1) r^2) + 1 - alpha)
//   ray = (mz xi + sqrt(mz^2 + (1 - xi^2) r^2)) / (mz^2 + r^2) (mx, my, mz) - (0, 0, xi)
//
// a unit vector.
//
// Valid domain: the projection is one-to-one where the point, carried onto the second
// sphere, is in front of the tangent cone of the pinhole that images that sphere:
//   z2 = (xi |p| + z) / d2 > -w1,  w1 = alpha / (1 - alpha) if alpha <= 1/2, else (1 - alpha) / alpha.
// As an angle theta from the optical axis: cos(theta) > c_min with
//   c_min = -xi (1 - w1^2) - w1 sqrt(1 - xi^2 (1 - w1^2))
// (the root of (c + xi)^2 = w1^2 (1 + 2 xi c + xi^2) with c + xi <= 0), so
// valid_radius() = acos(c_min), up to pi. With alpha = 0 this is the unified model's
// z > -xi |p|. (The paper's equation 43 writes the bound as w2 = (w1 + xi) /
// sqrt(2 w1 xi + xi^2 + 1), and basalt flags with it: a cone a degree or so narrower
// for the usual coefficients, inside which the two agree. Its edge is not the model's:
// the closed-form unprojection below gives rays past it, to the image's rim.)
// A point m has a ray when alpha <= 1/2, or r^2 < 1 / (2 alpha - 1) (inside the rim). The
// coefficients must satisfy -1 < xi <= 1 and 0 <= alpha <= 1 (the paper's bounds);
// Lens::validate refuses others.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <span>
#include <string>

#include "libcam/lens/lane.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"

namespace libcam {

template <class Scalar>
struct DoubleSphereLens {
    static constexpr LensType type = LensType::DoubleSphere;
    static constexpr int num_coefficients = 2;
    template <class Other>
    using InScalar = DoubleSphereLens<Other>;
    using Parameters = LensParameters<Scalar, 2>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian23 = Eigen::Matrix<Scalar, 2, 3>;

    // The largest angle from the optical axis the lens images: acos(c_min) (above).
    static double valid_radius(std::span<const double> c) {
        const double xi = c[0], alpha = c[1];
        const double w1 = alpha <= 0.5 ? alpha / (1 - alpha) : (1 - alpha) / alpha;
        const double shrink = 1 - w1 * w1;
        const double c_min = -xi * shrink - w1 * std::sqrt(std::max(0.0, 1 - xi * xi * shrink));
        return std::acos(std::clamp(c_min, -1.0, 1.0));
    }

    static Parameters parameters(std::span<const double> c) { return lens_parameters<Scalar, 2>(c, valid_radius(c)); }

    // Where `libcam fit` starts (lens_models.hpp's fit_start): xi = 0, alpha = 1/2, the
    // stereographic projection 2 tan(theta / 2) with K's focal length, which reaches every
    // direction but the backward axis, so that a wide scene projects from the start.
    static std::array<double, 2> fit_start() { return {0.0, 0.5}; }

    // The paper's bounds (see above); InvalidArgument naming the coefficient otherwise.
    static void check_coefficients(std::span<const double> c, const char* field) {
        if (!(c[0] > -1 && c[0] <= 1)) {
            throw InvalidArgument(std::string(field) + "[0] (xi): must be in (-1, 1], got " + format_number(c[0]));
        }
        if (!(c[1] >= 0 && c[1] <= 1)) {
            throw InvalidArgument(std::string(field) + "[1] (alpha): must be in [0, 1], got " + format_number(c[1]));
        }
    }

    // False outside the valid domain (the angle from the axis at or past valid_radius, or
    // the origin) and where m is not finite; evaluated without branches (pinhole.hpp).
    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        using std::cos;
        using std::sqrt;
        const Scalar xi = by_value(lens.coefficients(0)), alpha = by_value(lens.coefficients(1));
        const Scalar x = point.x(), y = point.y(), z = point.z();
        const Scalar rho2 = x * x + y * y;
        const Scalar d1 = sqrt(rho2 + z * z);
        const Scalar zeta = xi * d1 + z;
        const Scalar d2 = sqrt(rho2 + zeta * zeta);
        // alpha d2 + (1 - alpha) zeta; behind the first sphere's equator (zeta < 0) the two
        // terms cancel, and the same number is taken as
        // (alpha^2 rho^2 + (2 alpha - 1) zeta^2) / (alpha d2 - (1 - alpha) zeta),
        // whose denominator does not cancel (nor its numerator for alpha >= 1/2).
        const Scalar sum = alpha * d2 + (Scalar(1) - alpha) * zeta;
        const Scalar difference_form = (alpha * alpha * rho2 + (Scalar(2) * alpha - Scalar(1)) * zeta * zeta) /
                                       (alpha * d2 - (Scalar(1) - alpha) * zeta);
        const Scalar denominator = zeta >= Scalar(0) ? by_value(sum) : by_value(difference_form);
        // cos(theta) > c_min, as z > cos(valid_radius) |p|, so that the bound is the one
        // valid_radius() reports (pi bounds nothing but the backward axis itself).
        const bool in_domain = z > cos(lens.valid_radius) * d1;
        const Scalar inverse = Scalar(1) / denominator;
        m = Vec2T(x * inverse, y * inverse);
        if constexpr (is_requested<PointJacobianPtr>) {
            const Vec3T d_d1 = point / d1;
            const Vec3T d_zeta = xi * d_d1 + Vec3T::UnitZ();
            const Vec3T d_d2 = (Vec3T(x, y, Scalar(0)) + zeta * d_zeta) / d2;
            ratio_point_jacobian(m, inverse, Vec3T(alpha * d_d2 + (Scalar(1) - alpha) * d_zeta), d_m_d_point);
        }
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            // d D / d xi and d D / d alpha.
            const Vec2T d_denominator((alpha * zeta / d2 + (Scalar(1) - alpha)) * d1, d2 - zeta);
            ratio_coefficient_jacobian(m, inverse, d_denominator, d_m_d_coefficients);
        }
        return in_domain & (denominator > Scalar(0)) & all_finite(m);
    }

    // The unit ray through m; false where m has none: alpha > 1/2 and m on or past the
    // image's rim r^2 = 1 / (2 alpha - 1), which is the domain's edge (project() excludes
    // it). For alpha <= 1/2 every finite m has a ray inside the cone: the image is
    // unbounded and the cone is where m goes to infinity. The flag is decided on m, not
    // by comparing the ray with the cone: near the cone a ray cannot be rounded closer to
    // it than eps, while m says on which side it lies exactly.
    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        using std::sqrt;
        const Scalar xi = by_value(lens.coefficients(0)), alpha = by_value(lens.coefficients(1));
        const Scalar r2 = m.squaredNorm();
        const Scalar rim_term = Scalar(2) * alpha - Scalar(1);
        const Scalar radicand = Scalar(1) - rim_term * r2;
        const Scalar mz = (Scalar(1) - alpha * alpha * r2) / (alpha * sqrt(radicand) + Scalar(1) - alpha);
        const Scalar scale = (mz * xi + sqrt(mz * mz + (Scalar(1) - xi * xi) * r2)) / (mz * mz + r2);
        ray = Vec3T(scale * m.x(), scale * m.y(), scale * mz - xi);
        const bool inside_rim = (rim_term <= Scalar(0)) | (radicand > Scalar(0));
        // mz^2 + r^2 past the type's range (|m| beyond about 1e154 in double) would give
        // the ray (0, 0, -xi): flagged (scale is positive for every other m).
        return inside_rim & (scale > Scalar(0)) & all_finite(ray);
    }
};

}  // namespace libcam
