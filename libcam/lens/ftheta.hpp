#pragma once
// FTHETA: NVIDIA's F-theta model (DriveWorks' rig files, NCore's FThetaCameraModelParameters,
// 3DGUT's and gsplat's FThetaCameraModel) with its backward polynomial as the reference:
// the angle from the optical axis is a polynomial of the distance from the principal point
// in the sensor plane, behind an affine [c d; e 1]:
//
//   n = A^-1 m,  A = [c d; e 1]   (m the normalised image point, (u - cx, v - cy) / f)
//   r = |n|,     theta(r) = k1 r + k2 r^2 + k3 r^3 + k4 r^4 + k5 r^5
//   ray = (sin(theta) n / r, cos(theta))
//
// Coefficients c, d, e, k1..k5, max_angle. NVIDIA's files hold the polynomial in pixels
// (pixeldist_to_angle_poly, DriveWorks' "bw-poly" or "polynomial" with "polynomial-type":
// "pixeldistance-to-angle": b0 + b1 p + ... + b5 p^5 radians at p pixels); with K's
// fx = fy = f, k_i = b_i f^i (io/detail/driveworks_rig.cpp takes f = 1 / b1, so k1 = 1).
// b0 must be 0: the principal point is the axis. Their affine maps the sensor offset to
// the pixel offset, (du, dv) = (c sx + d sy, e sx + sy), as here (gsplat's
// camera_ray_to_image_point, 3DGUT's projectPoint). Their principal point has the first
// pixel's centre at (0, 0), as libcam's.
//
// unproject is the formula. project finds the radius r with theta(r) = atan2(|(X, Y)|, Z)
// by the certified 1-D solver of undistort.hpp (Newton's method inside a bracket that
// bisection shrinks), as OCAMCALIB's does: theta increases on the valid domain, so the
// root there is unique. (NVIDIA's own projection runs three Newton steps from the file's
// forward polynomial, its approximate inverse; libcam solves to the last digit.)
//
// Valid domain: the disc r < valid_radius of the sensor plane below the first r > 0 where
// theta'(r) = 0 (the fold), theta(r) = max_angle or theta(r) = pi, whichever comes first:
// past 90 degrees when the lens sees that far. max_angle (radians, in (0, pi]) is NCore's
// and 3DGUT's bound on the rays the calibration holds; rays past it are flagged, as 3DGUT
// flags them. k1 > 0 and c - d e > 0 (check_coefficients).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <span>
#include <string>

#include "libcam/error.hpp"
#include "libcam/lens/arctangent.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/sine_cosine.hpp"
#include "libcam/lens/undistort.hpp"
#include "libcam/lens/valid_radius.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

template <class Scalar>
struct FThetaLens {
    static constexpr LensType type = LensType::FTheta;
    static constexpr int num_coefficients = 9;
    static constexpr int kDegree = 5;
    static constexpr int kMaxAngle = 8;  // the index of max_angle
    template <class Other>
    using InScalar = FThetaLens<Other>;
    using Parameters = LensParameters<Scalar, 9>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;

    static void check_coefficients(std::span<const double> k, const char* field) {
        const double determinant = k[0] - k[1] * k[2];
        if (!(determinant > 0.0)) {
            throw InvalidArgument(std::string(field) + " (c, d, e): the affine's determinant c - d e must be positive, got " +
                                  format_number(determinant));
        }
        if (!(k[3] > 0.0)) {
            throw InvalidArgument(std::string(field) + "[3] (k1): must be positive (the angle must grow with the " +
                                  "radius at the centre), got " + format_number(k[3]));
        }
        if (!(k[kMaxAngle] > 0.0 && k[kMaxAngle] <= std::numbers::pi)) {
            throw InvalidArgument(std::string(field) + "[8] (max_angle): must be in (0, pi] radians, got " +
                                  format_number(k[kMaxAngle]));
        }
    }

    // The sensor radius below which theta is one-to-one, below max_angle and below pi.
    static double valid_radius(std::span<const double> k) {
        if (!(k[3] > 0.0) || !(k[kMaxAngle] > 0.0)) return 0.0;
        const double slope[] = {k[3], 2 * k[4], 3 * k[5], 4 * k[6], 5 * k[7]};
        const double limit = std::min(k[kMaxAngle], std::numbers::pi);
        const double at_limit[] = {-limit, k[3], k[4], k[5], k[6], k[7]};
        return std::min(smallest_positive_root(slope), smallest_positive_root(at_limit));
    }

    // The largest angle from the axis imaged: theta at the valid radius.
    static double valid_angle(std::span<const double> k, double radius) {
        if (!(radius > 0.0)) return 0.0;
        if (!std::isfinite(radius)) return std::min(k[kMaxAngle], std::numbers::pi);
        double slope = 0.0;
        return std::clamp(angle(k.subspan(3, 5), radius, slope), 0.0, std::numbers::pi);
    }

    static Parameters parameters(std::span<const double> k) { return lens_parameters<Scalar, 9>(k, valid_radius(k)); }

    // theta(r) and its slope, increasing on [0, valid_radius): the solver's d(r).
    static Scalar radial_distortion(const Parameters& lens, const Scalar& r, Scalar& slope) {
        return angle(lens.coefficients.template segment<5>(3), r, slope);
    }

    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        using std::sqrt;
        const auto& k = lens.coefficients;
        const Scalar zero(0);
        const Scalar rho2 = point.x() * point.x() + point.y() * point.y();
        const Scalar rho = sqrt(rho2);
        const Scalar norm2 = rho2 + point.z() * point.z();
        const Scalar target = angle_from_axis(rho, point.z());
        Scalar r(0);
        detail::solve_radial<FThetaLens>(lens, target, r);
        Scalar slope(0);
        const Scalar reached = radial_distortion(lens, r, slope);
        // On the axis r / rho tends to 1 / (theta'(0) z) = 1 / (k1 z).
        const bool on_axis = !(rho > zero);
        const Scalar scale = on_axis ? Scalar(1) / (slope * point.z()) : r / rho;
        const Vec2T n(scale * point.x(), scale * point.y());
        m = affine(k, n);
        const Scalar tolerance = unprojection_tolerance(abs_of(target));
        // The backward axis has no azimuth, so no pixel.
        const bool not_backward = (rho > zero) | (point.z() > zero);
        const bool in_domain = (r < lens.valid_radius) & (norm2 > zero) & not_backward &
                               (abs_of(reached - target) <= tolerance) & all_finite(m);
        if constexpr (is_requested<PointJacobianPtr> || is_requested<CoefficientJacobianPtr>) {
            const Scalar d_r_d_target = Scalar(1) / slope;
            const Scalar inverse_rho = on_axis ? zero : Scalar(1) / rho;
            const Vec2T along(point.x() * inverse_rho, point.y() * inverse_rho);
            if constexpr (is_requested<PointJacobianPtr>) {
                Eigen::Matrix<Scalar, 2, 3> d_n_d_point;
                if (on_axis) {
                    d_n_d_point.setZero();
                    d_n_d_point(0, 0) = d_n_d_point(1, 1) = scale;
                } else {
                    // d target / d p = (X z / rho, Y z / rho, -rho) / |p|^2.
                    const Scalar inverse_norm2 = Scalar(1) / norm2;
                    const Vec3T d_target(along.x() * point.z() * inverse_norm2, along.y() * point.z() * inverse_norm2,
                                         -rho * inverse_norm2);
                    for (int i = 0; i < 2; ++i) {
                        d_n_d_point.row(i) = (along(i) * d_r_d_target) * d_target.transpose();
                        // r d(along_i) / d(X, Y) = r (delta_ij - along_i along_j) / rho
                        for (int j = 0; j < 2; ++j) {
                            const Scalar delta = i == j ? Scalar(1) : zero;
                            d_n_d_point(i, j) += scale * (delta - along(i) * along(j));
                        }
                    }
                }
                for (int j = 0; j < 3; ++j) d_m_d_point->col(j) = affine(k, Vec2T(d_n_d_point.col(j)));
            }
            if constexpr (is_requested<CoefficientJacobianPtr>) {
                // m_x = c n_x + d n_y, m_y = e n_x + n_y.
                d_m_d_coefficients->col(0) = Vec2T(n.x(), zero);
                d_m_d_coefficients->col(1) = Vec2T(n.y(), zero);
                d_m_d_coefficients->col(2) = Vec2T(zero, n.x());
                // theta(r) = target: d r / d k_i = -r^i / theta'(r).
                const Vec2T direction = on_axis ? Vec2T::Zero().eval() : affine(k, along);
                Scalar power = r;
                for (int i = 0; i < kDegree; ++i) {
                    d_m_d_coefficients->col(3 + i) = direction * (-power * d_r_d_target);
                    power *= r;
                }
                d_m_d_coefficients->col(kMaxAngle).setZero();  // a bound, not part of the map
            }
        }
        return in_domain;
    }

    // False past the valid radius.
    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        using std::sqrt;
        const auto& k = lens.coefficients;
        const Scalar zero(0);
        // A^-1 = [1 -d; -e c] / (c - d e).
        const Scalar inverse_determinant = Scalar(1) / (k(0) - k(1) * k(2));
        const Vec2T n((m.x() - k(1) * m.y()) * inverse_determinant, (k(0) * m.y() - k(2) * m.x()) * inverse_determinant);
        const Scalar r = sqrt(n.squaredNorm());
        Scalar slope(0);
        const Scalar theta = radial_distortion(lens, r, slope);
        // sine_cosine takes [0, pi]; outside the domain theta may leave it, and is flagged.
        const Scalar pi(std::numbers::pi);
        const Scalar bounded = theta < zero ? zero : (theta > pi ? pi : theta);
        Scalar sin_theta, cos_theta;
        sine_cosine(bounded, sin_theta, cos_theta);
        // sin(theta) / r, and its limit theta'(0) = k1 at the centre.
        const bool at_centre = !(r > zero);
        const Scalar ratio = at_centre ? Scalar(k(3)) : Scalar(sin_theta / r);
        ray = Vec3T(ratio * n.x(), ratio * n.y(), at_centre ? Scalar(1) : cos_theta);
        return (r < lens.valid_radius) & all_finite(ray);
    }

private:
    // theta(r) = k1 r + ... + k5 r^5 and theta'(r), from the polynomial's five coefficients.
    template <class T, class Polynomial>
    static T angle(const Polynomial& k, const T& r, T& slope) {
        slope = T(k[0]) + r * (T(2) * T(k[1]) + r * (T(3) * T(k[2]) + r * (T(4) * T(k[3]) + r * T(5) * T(k[4]))));
        return r * (T(k[0]) + r * (T(k[1]) + r * (T(k[2]) + r * (T(k[3]) + r * T(k[4])))));
    }

    static Vec2T affine(const Eigen::Matrix<Scalar, 9, 1>& k, const Vec2T& n) {
        return Vec2T(k(0) * n.x() + k(1) * n.y(), k(2) * n.x() + n.y());
    }

    static Scalar abs_of(const Scalar& x) {
        using std::abs;
        return abs(x);
    }
};

}  // namespace libcam
