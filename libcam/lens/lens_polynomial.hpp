#pragma once
// FISHEYE_LENS_POLYNOMIAL: Blender's polynomial fisheye (Cycles' panorama type of that
// name, intern/cycles/kernel/camera/projection.h, fisheye_lens_polynomial_to_direction),
// which gives the angle from the optical axis as a polynomial of the image radius:
//
//   r = |m|,  theta(r) = -(k0 + k1 r + k2 r^2 + k3 r^3 + k4 r^4)
//   ray = (sin(theta) m / r, cos(theta))
//
// Coefficients k0..k4 (Blender's fisheye_polynomial_k0..k4). Blender measures r in
// millimetres on the sensor: a camera built from Blender's (convert/blender_camera.hpp)
// has fx = fy = pixels per millimetre, so m is in millimetres. Blender's default
// polynomial has k1 = -0.02, so theta grows with r; one with k1 > 0 gives negative angles,
// the image turned half a turn (sin(theta) < 0), and is modelled as such.
//
// unproject is the formula; project solves theta(r) = the point's angle for r by the
// certified 1-D solver of undistort.hpp (bracketed Newton).
//
// Valid domain: the disc r < valid_radius where theta is one-to-one: below the first
// r > 0 where theta'(r) = 0 (the fold) or |theta(r)| reaches pi (the backward axis), and
// where sigma theta(r) > 0, sigma the sign of theta'(0) = -k1 (past a root of theta near
// the centre two pixels would share a ray). A pixel at r = 0 exactly has a ray only if
// k0 = 0: otherwise Blender gives it an angle -k0 in a direction of its own choosing.
// Directions within |k0| of the axis have no pixel (the image's centre is a ring of
// directions around the axis). valid_angle() gives the largest angle imaged, |theta| at
// the valid radius. Blender also blacks out pixels past its fisheye_fov / 2; that
// is the camera's image circle, not the lens model's domain. k1 = 0 is refused.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <string>

#include "libcam/error.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/undistort.hpp"
#include "libcam/lens/valid_radius.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

template <class Scalar>
struct LensPolynomialLens {
    static constexpr LensType type = LensType::LensPolynomial;
    static constexpr int num_coefficients = 5;
    template <class Other>
    using InScalar = LensPolynomialLens<Other>;
    using Parameters = LensParameters<Scalar, 5>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;

    static void check_coefficients(std::span<const double> k, const char* field) {
        if (!(k[1] != 0.0)) {
            throw InvalidArgument(std::string(field) + "[1] (k1): must not be 0 (the angle must grow with the radius " +
                                  "at the centre), got " + format_number(k[1]));
        }
    }

    // Where `libcam fit` starts (lens_models.hpp's fit_start): the equidistant lens
    // theta = radians_per_unit r (k1 = -radians_per_unit), whose domain reaches pi.
    static std::array<double, 5> fit_start(double radians_per_unit) { return {0.0, -radians_per_unit, 0.0, 0.0, 0.0}; }

    // The radius (in m's units) below which theta is one-to-one and within pi of the axis.
    static double valid_radius(std::span<const double> k) {
        if (!(k[1] != 0.0)) return 0.0;
        const double pi = std::numbers::pi;
        const double slope[] = {k[1], 2 * k[2], 3 * k[3], 4 * k[4]};
        const double at_plus_pi[] = {k[0] + pi, k[1], k[2], k[3], k[4]};   // theta = -pi
        const double at_minus_pi[] = {k[0] - pi, k[1], k[2], k[3], k[4]};  // theta = pi
        return std::min({smallest_positive_root(slope), smallest_positive_root(at_plus_pi),
                         smallest_positive_root(at_minus_pi)});
    }

    // The largest angle from the axis imaged: |theta| at the valid radius.
    static double valid_angle(std::span<const double> k, double radius) {
        if (!(radius > 0.0)) return 0.0;
        if (!std::isfinite(radius)) return std::numbers::pi;
        double slope = 0.0;
        return std::min(std::abs(angle(k, radius, slope)), std::numbers::pi);
    }

    // The angle about the axis no pixel sees: sigma theta(0) = sigma (-k0) when positive.
    static double blind_angle(std::span<const double> k) { return std::max(0.0, -orientation(k[1]) * k[0]); }

    static Parameters parameters(std::span<const double> k) { return lens_parameters<Scalar, 5>(k, valid_radius(k)); }

    // sigma theta(r) and its slope: increasing on [0, valid_radius), the solver's d(r).
    static Scalar radial_distortion(const Parameters& lens, const Scalar& r, Scalar& slope) {
        const Scalar sigma = orientation(lens);
        const Scalar value = sigma * angle(lens.coefficients, r, slope);
        slope *= sigma;
        return value;
    }

    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        using std::atan2;
        using std::sqrt;
        const auto& k = lens.coefficients;
        const Scalar zero(0);
        const Scalar rho2 = point.x() * point.x() + point.y() * point.y();
        const Scalar rho = sqrt(rho2);
        const Scalar norm2 = rho2 + point.z() * point.z();
        const Scalar target = atan2(rho, point.z());  // the point's angle from the axis
        const Scalar sigma = orientation(lens);
        Scalar r(0);
        detail::solve_radial<LensPolynomialLens>(lens, target, r);
        Scalar slope(0);
        const Scalar reached = radial_distortion(lens, r, slope);  // sigma theta(r), slope > 0 inside
        // On the axis (rho = 0) r / rho tends to 1 / (sigma theta'(0) z).
        const bool on_axis = !(rho > zero);
        const Scalar scale = on_axis ? Scalar(1) / (slope * point.z()) : r / rho;
        m = Vec2T(sigma * scale * point.x(), sigma * scale * point.y());
        const Scalar tolerance = unprojection_tolerance(abs_of(target));
        const bool centre_ok = (r > zero) | (k(0) == zero);
        // The backward axis has no azimuth, so no pixel (it lies at |theta| = pi, on the
        // domain's edge, where a rounded r can still land inside).
        const bool not_backward = (rho > zero) | (point.z() > zero);
        const bool in_domain = (r < lens.valid_radius) & (reached >= zero) & centre_ok & not_backward & (norm2 > zero) &
                               (abs_of(reached - target) <= tolerance) & all_finite(m);
        if constexpr (is_requested<PointJacobianPtr> || is_requested<CoefficientJacobianPtr>) {
            const Scalar d_r_d_target = Scalar(1) / slope;
            // The unit vector of (X, Y), and the limit on the axis.
            const Scalar inverse_rho = on_axis ? zero : Scalar(1) / rho;
            const Vec2T along(point.x() * inverse_rho, point.y() * inverse_rho);
            if constexpr (is_requested<PointJacobianPtr>) {
                if (on_axis) {
                    // m = sigma (X, Y) / (sigma theta'(0) z) near the axis.
                    d_m_d_point->setZero();
                    (*d_m_d_point)(0, 0) = (*d_m_d_point)(1, 1) = sigma * scale;
                } else {
                    // d target / d p = (X z / rho, Y z / rho, -rho) / |p|^2.
                    const Scalar inverse_norm2 = Scalar(1) / norm2;
                    const Vec3T d_target(along.x() * point.z() * inverse_norm2, along.y() * point.z() * inverse_norm2,
                                         -rho * inverse_norm2);
                    for (int i = 0; i < 2; ++i) {
                        d_m_d_point->row(i) = (sigma * along(i) * d_r_d_target) * d_target.transpose();
                        // r d(along_i) / d(X, Y) = r (delta_ij - along_i along_j) / rho
                        for (int j = 0; j < 2; ++j) {
                            const Scalar delta = i == j ? Scalar(1) : zero;
                            (*d_m_d_point)(i, j) += sigma * scale * (delta - along(i) * along(j));
                        }
                    }
                }
            }
            if constexpr (is_requested<CoefficientJacobianPtr>) {
                // sigma theta(r) = target with theta = -(k0 + k1 r + ...): d r / d k_i =
                // sigma r^i / (sigma theta'(r)) = sigma r^i / slope.
                Scalar power(1);
                const Vec2T direction = on_axis ? Vec2T::Zero().eval() : Vec2T(sigma * along);
                for (int i = 0; i < 5; ++i) {
                    d_m_d_coefficients->col(i) = direction * (sigma * power * d_r_d_target);
                    power *= r;
                }
            }
        }
        return in_domain;
    }

    // False past the valid radius, where sigma theta(r) <= 0, and at r = 0 when k0 != 0.
    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        using std::cos;
        using std::sin;
        using std::sqrt;
        const auto& k = lens.coefficients;
        const Scalar zero(0);
        const Scalar r = sqrt(m.squaredNorm());
        Scalar slope(0);
        const Scalar theta = angle(k, r, slope);
        // sin(theta) / r, and its limit -k1 = theta'(0) at the centre (theta(0) = 0 there).
        const Scalar ratio = r > zero ? Scalar(sin(theta) / r) : Scalar(-k(1));
        ray = Vec3T(ratio * m.x(), ratio * m.y(), cos(theta));
        const bool oriented = r > zero ? orientation(lens) * theta > zero : k(0) == zero;
        return (r < lens.valid_radius) & oriented & all_finite(ray);
    }

private:
    // theta(r) = -(k0 + k1 r + k2 r^2 + k3 r^3 + k4 r^4) and its slope, in any container.
    template <class T, class Coefficients>
    static T angle(const Coefficients& k, const T& r, T& slope) {
        slope = -(T(k[1]) + r * (T(2) * T(k[2]) + r * (T(3) * T(k[3]) + r * T(4) * T(k[4]))));
        return -(T(k[0]) + r * (T(k[1]) + r * (T(k[2]) + r * (T(k[3]) + r * T(k[4])))));
    }

    // sigma: +1 when theta grows with r at the centre (k1 < 0, Blender's default), else -1.
    template <class T>
    static T orientation(const T& k1) {
        return k1 < T(0) ? T(1) : T(-1);
    }
    static Scalar orientation(const Parameters& lens) { return orientation(lens.coefficients(1)); }

    static Scalar abs_of(const Scalar& x) {
        using std::abs;
        return abs(x);
    }
};

}  // namespace libcam
