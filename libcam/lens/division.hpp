#pragma once
// DIVISION: Fitzgibbon's one-parameter division model ("Simultaneous linear estimation of
// multiple view geometry and lens distortion", CVPR 2001), as COLMAP ("DIVISION": fx, fy,
// cx, cy, k; "SIMPLE_DIVISION": f, cx, cy, k) defines it, with one coefficient k. The
// undistorted point is the distorted one divided by a polynomial of the distorted radius:
//
//   u = m / (1 + k |m|^2)
//
// so the ray through m is (mx, my, 1 + k |m|^2) (unprojection in closed form), and the
// pixel is K m. OpenImuCameraCalibrator's DIVISION_UNDISTORTION (Theia's
// DivisionUndistortionCameraModel) and RealityCapture's "division" are the same map with
// k measured in other units (io/detail/openicc_format.cpp says how).
//
// Projection solves for the scale s with m = s (X, Y): the ray condition
// 1 + k s^2 rho^2 = s Z (rho^2 = X^2 + Y^2) is a quadratic in s whose root nearest the
// axis is, with the discriminant Delta = Z^2 - 4 k rho^2,
//
//   m = (X, Y) / D,   D = (Z + sqrt(Delta)) / 2 = 2 k rho^2 / (Z - sqrt(Delta))
//
// (COLMAP's ImgFromCam: its r is 1 / D). The first form cancels for Z < 0 and the second
// for Z > 0; each is taken where it does not.
//
// Valid domain: r_u(r_d) = r_d / (1 + k r_d^2) rises until r_d = 1 / sqrt(k) for k > 0,
// where it reaches 1 / (2 sqrt(k)) and folds back (Delta = 0): the domain is the angle
// from the axis below atan(1 / (2 sqrt(k))) and |m| < 1 / sqrt(k). For k < 0 the ray's
// z, 1 + k |m|^2, crosses 0 at |m| = 1 / sqrt(-k) and the angle of the ray keeps rising
// (its derivative is proportional to 1 - k |m|^2 > 0) towards pi as |m| grows: every
// direction but the backward axis is imaged, once (a point behind the camera so close to
// that axis that X^2 + Y^2 is no longer a normal number is flagged). k = 0 is the pinhole,
// z > 0. So valid_radius() is that angle: atan2(1, 2 sqrt(k)), pi / 2 or pi.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <span>

#include "libcam/lens/lane.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"

namespace libcam {

template <class Scalar>
struct DivisionLens {
    static constexpr LensType type = LensType::Division;
    static constexpr int num_coefficients = 1;
    template <class Other>
    using InScalar = DivisionLens<Other>;
    using Parameters = LensParameters<Scalar, 1>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;

    // The largest angle from the optical axis the lens images (above).
    static double valid_radius(std::span<const double> c) {
        const double k = c[0];
        if (k > 0) return std::atan2(1.0, 2.0 * std::sqrt(k));
        return k == 0 ? std::numbers::pi / 2 : std::numbers::pi;
    }

    static Parameters parameters(std::span<const double> c) { return lens_parameters<Scalar, 1>(c, valid_radius(c)); }

    // False outside the valid domain (past the fold for k > 0, on or behind the camera
    // plane for k = 0, on the backward axis for k < 0) and where m is not finite;
    // evaluated without branches (pinhole.hpp).
    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        using std::sqrt;
        const Scalar k = by_value(lens.coefficients(0));
        const Scalar x = point.x(), y = point.y(), z = point.z();
        const Scalar rho2 = x * x + y * y;
        const Scalar discriminant = z * z - Scalar(4) * k * rho2;
        const bool before_fold = discriminant > Scalar(0);
        const Scalar root = sqrt(before_fold ? by_value(discriminant) : Scalar(0));
        const Scalar sum_form = (z + root) / Scalar(2);
        const Scalar difference_form = Scalar(2) * k * rho2 / (z - root);
        const Scalar denominator = z >= Scalar(0) ? by_value(sum_form) : by_value(difference_form);
        const Scalar inverse = Scalar(1) / denominator;
        m = Vec2T(x * inverse, y * inverse);
        // dD/dz = (1 + z / root) / 2 = D / root, which does not cancel for z < 0.
        const Scalar inverse_root = Scalar(1) / root;
        if constexpr (is_requested<PointJacobianPtr>) {
            const Scalar slope = Scalar(-2) * k * inverse_root;
            ratio_point_jacobian(m, inverse, Vec3T(slope * x, slope * y, denominator * inverse_root), d_m_d_point);
        }
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            ratio_coefficient_jacobian(m, inverse, Eigen::Matrix<Scalar, 1, 1>(-rho2 * inverse_root),
                                       d_m_d_coefficients);  // dD/dk
        }
        // Behind the camera near the backward axis, rho^2 below the normal range loses its
        // digits (m ~ Z / (k rho^2)): flagged, as FISHEYE flags it.
        const bool in_domain =
            before_fold & ((z > Scalar(0)) | ((k < Scalar(0)) & (rho2 >= smallest_normal<Scalar>())));
        return in_domain & (denominator > Scalar(0)) & all_finite(m);
    }

    // The ray (mx, my, 1 + k |m|^2) through m; false where m has none: k > 0 and m on or
    // past the fold, |m|^2 >= 1 / k.
    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        const Scalar k = by_value(lens.coefficients(0));
        const Scalar k_r2 = k * m.squaredNorm();
        ray = Vec3T(m.x(), m.y(), Scalar(1) + k_r2);
        return (k_r2 < Scalar(1)) & all_finite(ray);
    }
};

}  // namespace libcam
