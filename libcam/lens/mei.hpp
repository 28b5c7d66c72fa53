#pragma once
// MEI: the unified camera model with radial-tangential distortion (Mei and Rives,
// "Single View Point Omnidirectional Camera Calibration from Planar Grids", ICRA 2007),
// as OpenCV's cv::omnidir, camodocal ("MEI") and Kalibr ("omni-radtan") define it, with
// coefficients xi k1 k2 p1 p2:
//
//   q = (x, y) / (z + xi |p|)                       UCM (ucm.hpp)
//   m = q R(|q|^2) + tangential(q)                  OPENCV4 (opencv.hpp) applied to q
//
// (the pixel is K m; cv::omnidir's K may have a skew, camodocal's has none). With k1 k2
// p1 p2 zero it is UCM.
//
// Unprojection has no closed form: the shared solver (undistort.hpp) finds q from m in
// OPENCV4's way, then UCM's closed form gives the ray. The solver works in q, where the
// distortion is a polynomial, well conditioned even where q goes to infinity (xi <= 1,
// an unbounded image); the angle theta would not be (its |q| = sin(theta) /
// (cos(theta) + xi) cancels there).
//
// Valid domain: UCM's (z / |p| > -w, w = xi up to 1, then 1 / xi), and |q| below
// valid_radius(), the smaller of UCM's rim (1 / sqrt(xi^2 - 1) for xi > 1, the image of
// the edge) and the radius where OPENCV4's radial part q (1 + k1 q^2 + k2 q^4) folds
// over (the tangential terms are taken to be small, as for OpenCV's models). valid_radius
// is a radius in the plane of q, not an angle: valid_angle() gives the angle, UCM's
// inverse of it (|q| grows with the angle up to UCM's edge). xi must be above -1.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>

#include "libcam/lens/lane.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/opencv.hpp"
#include "libcam/lens/ucm.hpp"
#include "libcam/lens/undistort.hpp"

namespace libcam {

template <class Scalar>
struct MeiLens {
    static constexpr LensType type = LensType::Mei;
    static constexpr int num_coefficients = 5;
    template <class Other>
    using InScalar = MeiLens<Other>;
    using Parameters = LensParameters<Scalar, 5>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;
    using Jacobian23 = Eigen::Matrix<Scalar, 2, 3>;

    // The largest |q| the lens images (above); infinity for none.
    static double valid_radius(std::span<const double> c) {
        const double xi = c[0];
        const double rim = xi > 1 ? 1 / std::sqrt(xi * xi - 1) : std::numeric_limits<double>::infinity();
        return std::min(rim, OpenCvLens<double, 4>::valid_radius(c.subspan(1)));
    }

    // The largest angle from the optical axis: the angle of the ray through |q| =
    // valid_radius, or UCM's edge when that is unbounded.
    static double valid_angle(std::span<const double> c, double radius) {
        const double xi = c[0];
        if (!std::isfinite(radius)) return UcmLens<double>::valid_radius(c.first(1));
        // UCM's inverse: the ray s (q, 0) - (0, 0, xi); the radicand is 0 on the rim.
        const double s = (xi + std::sqrt(std::max(0.0, 1 + (1 - xi * xi) * radius * radius))) / (1 + radius * radius);
        return std::atan2(s * radius, s - xi);
    }

    static Parameters parameters(std::span<const double> c) { return lens_parameters<Scalar, 5>(c, valid_radius(c)); }

    static void check_coefficients(std::span<const double> c, const char* field) {
        UcmLens<double>::check_coefficients(c.first(1), field);
    }

    // False outside the valid domain (UCM's, or |q| at or past valid_radius) and where m
    // is not finite; evaluated without branches (pinhole.hpp).
    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        Vec2T q;
        Jacobian23 d_q_d_point;
        Vec2T d_q_d_xi;
        const bool in_ucm_domain = UcmLens<Scalar>::project(ucm_parameters(lens), point, q,
                                                            pass_request<PointJacobianPtr>(&d_q_d_point),
                                                            pass_request<CoefficientJacobianPtr>(&d_q_d_xi));
        // d m / d q serves both Jacobians (d m / d xi = d m / d q  d q / d xi).
        constexpr bool kChain = is_requested<PointJacobianPtr> || is_requested<CoefficientJacobianPtr>;
        Jacobian22 d_m_d_q;
        Eigen::Matrix<Scalar, 2, 4> d_m_d_radtan;
        bool inside = false;
        if constexpr (kChain) {
            inside = distort(lens, q, m, &d_m_d_q, pass_request<CoefficientJacobianPtr>(&d_m_d_radtan));
        } else {
            inside = distort(lens, q, m);
        }
        if constexpr (is_requested<PointJacobianPtr>) *d_m_d_point = d_m_d_q * d_q_d_point;
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            d_m_d_coefficients->col(0) = d_m_d_q * d_q_d_xi;
            d_m_d_coefficients->template rightCols<4>() = d_m_d_radtan;
        }
        return in_ucm_domain & inside & all_finite(m);
    }

    // A unit ray through m, by the shared iterative solver.
    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        return unproject_solved<MeiLens>(lens, m, ray);
    }

    // The unit ray through q, by UCM's closed form (q inside the rim, as the solver's
    // answers are).
    static Vec3T ray_from_undistorted(const Parameters& lens, const Vec2T& q) {
        Vec3T ray;
        UcmLens<Scalar>::unproject(ucm_parameters(lens), q, ray);
        return ray;
    }

    // m = OPENCV4's distortion of q; false for |q| at or past valid_radius.
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& q, Vec2T& m, UJacobianPtr d_m_d_q = nullptr,
                        CoefficientJacobianPtr d_m_d_radtan = nullptr) {
        return OpenCvLens<Scalar, 4>::distort(radtan_parameters(lens), q, m, d_m_d_q, d_m_d_radtan);
    }

    // The radial part alone, r (1 + k1 r^2 + k2 r^4), and its slope: the 1-D start of unproject.
    static Scalar radial_distortion(const Parameters& lens, const Scalar& r, Scalar& slope) {
        return OpenCvLens<Scalar, 4>::radial_distortion(radtan_parameters(lens), r, slope);
    }

private:
    static typename UcmLens<Scalar>::Parameters ucm_parameters(const Parameters& lens) {
        typename UcmLens<Scalar>::Parameters ucm;
        ucm.coefficients(0) = by_value(lens.coefficients(0));
        return ucm;
    }

    // k1 k2 p1 p2 as OPENCV4's, bounded by this lens's valid radius.
    static typename OpenCvLens<Scalar, 4>::Parameters radtan_parameters(const Parameters& lens) {
        typename OpenCvLens<Scalar, 4>::Parameters radtan;
        radtan.coefficients = lens.coefficients.template tail<4>();
        radtan.valid_radius = lens.valid_radius;
        return radtan;
    }
};

}  // namespace libcam
