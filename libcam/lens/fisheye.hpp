#pragma once
// FISHEYE: OpenCV's fisheye model (cv::fisheye, Kannala-Brandt) with k1..k4:
//
//   theta   = the angle between the point and the optical axis = atan2(|(X, Y)|, Z)
//             (arctangent.hpp's, which the batch loops vectorise)
//   theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8)
//   m       = theta_d (X, Y) / |(X, Y)|
//
// For Z > 0 this is cv::fisheye::projectPoints (which writes theta = atan(r) with
// r = |(X/Z, Y/Z)|); the formula in theta carries on past 90 degrees, so libcam's
// FISHEYE sees beyond the camera plane, where OpenCV's would mirror.
//
// Internally u = theta (X, Y) / |(X, Y)| (the equidistant point, |u| = theta) and
// m = D(theta^2) u with D(s) = 1 + k1 s + k2 s^2 + k3 s^3 + k4 s^4.
//
// Valid domain: theta < valid_radius() = min(pi, the first theta where theta_d stops
// increasing), less the points so close to the backward axis that X^2 + Y^2 is no longer
// a normal number (flagged). On and near the axis, theta / |(X, Y)| and its derivative
// are evaluated by their series in t = |(X, Y)| / Z: no 0/0, no cancellation.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <span>

#include "libcam/lens/arctangent.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/sine_cosine.hpp"
#include "libcam/lens/undistort.hpp"
#include "libcam/lens/valid_radius.hpp"

namespace libcam {

template <class Scalar>
struct FisheyeLens {
    static constexpr LensType type = LensType::Fisheye;
    static constexpr int num_coefficients = 4;
    template <class Other>
    using InScalar = FisheyeLens<Other>;
    using Parameters = LensParameters<Scalar, 4>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;
    using Jacobian23 = Eigen::Matrix<Scalar, 2, 3>;
    using CoefficientJacobian = Eigen::Matrix<Scalar, 2, 4>;

    // The angle theta (radians) past which theta_d folds over, at most pi.
    static double valid_radius(std::span<const double> k) {
        const double stretch[] = {1.0, k[0], k[1], k[2], k[3]};
        return angle_fold(stretch);
    }

    // The angle theta, at most pi, past which theta D(theta^2) stops increasing, for the
    // stretch D given by its coefficients in theta^2 (1, k1, k2, ...): the valid radius of
    // every model whose radial part is a polynomial in theta.
    static double angle_fold(std::span<const double> stretch) {
        const double denominator[] = {1.0};
        return std::min(std::numbers::pi, radial_valid_radius(stretch, denominator));
    }

    static Parameters parameters(std::span<const double> k) {
        return lens_parameters<Scalar, 4>(k, valid_radius(k));
    }

    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        Vec2T u;
        Jacobian23 d_u_d_point;
        const bool defined = equidistant_point(point, u, pass_request<PointJacobianPtr>(&d_u_d_point));
        Jacobian22 d_m_d_u;
        const bool in_domain = distort(lens, u, m, pass_request<PointJacobianPtr>(&d_m_d_u), d_m_d_coefficients);
        if constexpr (is_requested<PointJacobianPtr>) *d_m_d_point = d_m_d_u * d_u_d_point;
        return defined & in_domain;  // &, not &&: no branch
    }

    // A ray through m (unit length), by the shared iterative solver.
    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        return unproject_solved<FisheyeLens>(lens, m, ray);
    }

    // The unit ray at the angle theta = |u| from the axis, towards u.
    static Vec3T ray_from_undistorted(const Parameters&, const Vec2T& u) { return ray_from_equidistant(u); }

    // The same for any model built on the equidistant point (thin_prism_fisheye.hpp, ...).
    // No branch and no libm call (sine_cosine), so that the batch loops vectorise it.
    static Vec3T ray_from_equidistant(const Vec2T& u) {
        const Scalar theta = u.norm();
        Scalar sin_theta, cos_theta;
        sine_cosine(theta, sin_theta, cos_theta);
        const bool on_axis = !(theta > Scalar(0));  // the ray (0, 0, 1) there
        const Scalar scale = on_axis ? Scalar(0) : Scalar(sin_theta / theta);
        return Vec3T(u.x() * scale, u.y() * scale, on_axis ? Scalar(1) : cos_theta);
    }

    // u = theta (X, Y) / |(X, Y)|; false, and u = 0, for the origin and the backward axis,
    // where the direction or the angle is undefined. Without branches: both forms of
    // theta / rho are worked out and one chosen, so the batch loops vectorise it.
    template <class PointJacobianPtr = std::nullptr_t>
    static bool equidistant_point(const Vec3T& point, Vec2T& u, PointJacobianPtr d_u_d_point = nullptr) {
        using std::sqrt;
        const Scalar x = point.x(), y = point.y(), z = point.z();
        const Scalar rho2 = x * x + y * y;
        // u = g (x, y) with g = theta / rho; dg/dx = h x, dg/dy = h y, dg/dz = -1 / |p|^2.
        // Near the axis in front (t = rho / z below 1e-3) g and h by their series in t, whose
        // next terms are below 1e-18:
        //   atan(t)/t = 1 - t^2/3 + t^4/5 - t^6/7;  (t/(1+t^2) - atan t)/t^3 = -2/3 + 4t^2/5 - 6t^4/7
        constexpr double kSeriesBelow = 1e-3;
        const bool series = (z > Scalar(0)) & (rho2 < Scalar(kSeriesBelow * kSeriesBelow) * z * z);
        const Scalar t2 = rho2 / (z * z), inv_z = Scalar(1) / z;
        const Scalar series_g =
            (Scalar(1) - t2 * (Scalar(1) / Scalar(3) - t2 * (Scalar(1) / Scalar(5) - t2 / Scalar(7)))) * inv_z;
        // Elsewhere theta = atan2(rho, z). Near the backward axis, where rho^2 is no longer a
        // normal number (within ~1e-154 rad of it in double, 1e-19 rad in float, for
        // |p| ~ 1), rho would carry few digits: the point is flagged, as STEREOGRAPHIC
        // flags it.
        const bool defined = series | (rho2 >= smallest_normal<Scalar>());
        const Scalar rho = sqrt(rho2), theta = angle_from_axis(rho, z);
        const Scalar g = defined ? (series ? series_g : theta / rho) : Scalar(0);
        u = Vec2T(g * x, g * y);
        if constexpr (is_requested<PointJacobianPtr>) {
            const Scalar series_h =
                (Scalar(-2) / Scalar(3) + t2 * (Scalar(4) / Scalar(5) - t2 * Scalar(6) / Scalar(7))) * inv_z * inv_z * inv_z;
            const Scalar h = series ? series_h : (z * rho / (rho2 + z * z) - theta) / (rho2 * rho);
            const Scalar inv_n2 = Scalar(1) / (rho2 + z * z);
            *d_u_d_point << g + h * x * x, h * x * y, -x * inv_n2,  //
                h * x * y, g + h * y * y, -y * inv_n2;
        }
        return defined;
    }

    // m = D(theta^2) u for the equidistant point u (|u| = theta); false outside the
    // valid domain (m then meaningless; evaluated without branches, see pinhole.hpp).
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& u, Vec2T& m, UJacobianPtr d_m_d_u = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        const Scalar s = u.squaredNorm();
        const bool in_domain = s < lens.valid_radius * lens.valid_radius;
        const Scalar factor = stretch(lens, s);
        m = u * factor;
        if constexpr (is_requested<UJacobianPtr>) {
            *d_m_d_u = Jacobian22::Identity() * factor + (Scalar(2) * stretch_slope(lens, s)) * u * u.transpose();
        }
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            Scalar power = s;
            for (int i = 0; i < 4; ++i, power *= s) d_m_d_coefficients->col(i) = u * power;
        }
        return in_domain;
    }

    // theta_d(theta) = theta D(theta^2) and its slope: the 1-D start of unproject.
    static Scalar radial_distortion(const Parameters& lens, const Scalar& theta, Scalar& slope) {
        const Scalar s = theta * theta;
        const Scalar factor = stretch(lens, s);
        slope = factor + Scalar(2) * s * stretch_slope(lens, s);
        return theta * factor;
    }

private:
    // D(s) and dD/ds.
    static Scalar stretch(const Parameters& lens, const Scalar& s) {
        const auto& k = lens.coefficients;
        return Scalar(1) + s * (k(0) + s * (k(1) + s * (k(2) + s * k(3))));
    }
    static Scalar stretch_slope(const Parameters& lens, const Scalar& s) {
        const auto& k = lens.coefficients;
        return k(0) + s * (Scalar(2) * k(1) + s * (Scalar(3) * k(2) + s * Scalar(4) * k(3)));
    }
};

// What the models built on the equidistant point u share (THIN_PRISM_FISHEYE,
// RAD_TAN_THIN_PRISM_FISHEYE): project is u, then the model's distort(u); unproject is
// the shared solver, then the ray at the angle |u|. The model derives from this and
// provides distort and radial_distortion.
template <class Model, class Scalar>
struct OnEquidistantPoint {
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;

    template <class Parameters, class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        Vec2T u;
        Eigen::Matrix<Scalar, 2, 3> d_u_d_point;
        const bool defined = FisheyeLens<Scalar>::equidistant_point(point, u, pass_request<PointJacobianPtr>(&d_u_d_point));
        Eigen::Matrix<Scalar, 2, 2> d_m_d_u;
        const bool in_domain = Model::distort(lens, u, m, pass_request<PointJacobianPtr>(&d_m_d_u), d_m_d_coefficients);
        if constexpr (is_requested<PointJacobianPtr>) *d_m_d_point = d_m_d_u * d_u_d_point;
        return defined & in_domain & all_finite(m);  // &, not &&: no branch
    }

    // A ray through m (unit length), by the shared iterative solver.
    template <class Parameters>
    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        return unproject_solved<Model>(lens, m, ray);
    }

    // The unit ray at the angle theta = |u| from the axis, towards u.
    template <class Parameters>
    static Vec3T ray_from_undistorted(const Parameters&, const Vec2T& u) {
        return FisheyeLens<Scalar>::ray_from_equidistant(u);
    }
};

}  // namespace libcam
