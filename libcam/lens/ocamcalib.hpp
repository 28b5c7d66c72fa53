#pragma once
// OCAMCALIB: Scaramuzza's omnidirectional model (OCamCalib, "A Toolbox for Easily
// Calibrating Omnidirectional Cameras", IROS 2006; the C functions cam2world and world2cam
// of its ocam_functions.cpp), in libcam's axes and units. A pixel's ray is a polynomial of
// its radius in the sensor plane:
//
//   n = A^-1 m,  A = [1 e; d c]   (m the normalised image point, (u - cx, v - cy) / f)
//   r = |n|,     ray = (n_x, n_y, g(r)),  g(r) = 1 + k1 r + k2 r^2 + k3 r^3 + k4 r^4 + k5 r^5
//
// Coefficients c, d, e, k1..k5. The toolbox's own numbers (calib_results.txt) are the
// same model in its axes: its x runs down the rows and y along the columns, its z is
// backwards (its a0 < 0), the centre (xc, yc) is (row, column) and its affine
// [c d; e 1] acts on (row, column). With f = -a0 (K's fx = fy), its polynomial
// pol(rho) = a0 + a1 rho + ... + a5 rho^5 in pixels is g's: k_i = -a_i f^(i - 1)
// (io/detail/ocamcalib_format.cpp converts). The toolbox fits degree 4 by default
// (every file seen has five coefficients, camodocal's SCARAMUZZA holds five too);
// degree 5 is the most this model holds.
//
// unproject is the formula. project finds the radius r whose ray has the point's angle
// from the axis, theta(r) = atan2(r, g(r)) = atan2(|(X, Y)|, Z), by the certified 1-D
// solver of undistort.hpp (Newton's method inside a bracket that bisection shrinks):
// theta increases on the valid domain, so the root there is unique, and it is the
// smallest positive root of r Z - g(r) |(X, Y)| that the toolbox's MATLAB world2cam
// takes. (The toolbox's C world2cam evaluates invpol, a polynomial fitted to that
// inverse, instead: io/ocamcalib.hpp measures how far it lands from this.)
//
// Valid domain: the disc r < valid_radius of the sensor plane where theta is one-to-one,
// below the first r > 0 where theta'(r) = 0, that is where
// h(r) = g(r) - r g'(r) = 1 - k2 r^2 - 2 k3 r^3 - 3 k4 r^4 - 4 k5 r^5 reaches 0 (k1 drops
// out); the angle reaches past 90 degrees where g < 0 (catadioptric cameras see 110
// degrees off the axis and more), never pi. valid_angle() gives theta at the valid
// radius. The affine needs c - d e > 0 (check_coefficients).

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <string>

#include "libcam/error.hpp"
#include "libcam/lens/arctangent.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/undistort.hpp"
#include "libcam/lens/valid_radius.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

template <class Scalar>
struct OcamCalibLens {
    static constexpr LensType type = LensType::OcamCalib;
    static constexpr int num_coefficients = 8;
    static constexpr int kDegree = 5;
    template <class Other>
    using InScalar = OcamCalibLens<Other>;
    using Parameters = LensParameters<Scalar, 8>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;

    static void check_coefficients(std::span<const double> k, const char* field) {
        const double determinant = k[0] - k[1] * k[2];
        if (!(determinant > 0.0)) {
            throw InvalidArgument(std::string(field) + " (c, d, e): the affine's determinant c - d e must be positive, got " +
                                  format_number(determinant));
        }
    }

    // The sensor radius below which theta is one-to-one: the smallest positive root of h.
    static double valid_radius(std::span<const double> k) {
        const double h[] = {1.0, 0.0, -k[4], -2 * k[5], -3 * k[6], -4 * k[7]};
        return smallest_positive_root(h);
    }

    // The largest angle from the axis imaged: theta at the valid radius, or theta's limit
    // when h never reaches 0 (the top nonzero k_i of degree >= 2 is then negative, and
    // theta tends to pi; with k1 alone it tends to atan2(1, k1)).
    static double valid_angle(std::span<const double> k, double radius) {
        if (!(radius > 0.0)) return 0.0;
        if (std::isfinite(radius)) {
            double slope = 0.0;
            return std::min(angle(k.subspan(3), radius, slope), std::numbers::pi);
        }
        for (std::size_t i = 4; i < 8; ++i) {
            if (k[i] != 0.0) return std::numbers::pi;
        }
        return std::atan2(1.0, k[3]);
    }

    static Parameters parameters(std::span<const double> k) { return lens_parameters<Scalar, 8>(k, valid_radius(k)); }

    // theta(r) and its slope, increasing on [0, valid_radius): the solver's d(r).
    static Scalar radial_distortion(const Parameters& lens, const Scalar& r, Scalar& slope) {
        return angle(lens.coefficients.template tail<5>(), r, slope);
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
        // Behind the camera the angle is solved as its distance from the backward axis,
        // which keeps its digits near 180 degrees (where r grows without bound).
        const bool behind = point.z() < zero;
        const Scalar solved_target = behind ? Scalar(-angle_from_axis(rho, Scalar(-point.z()))) : target;
        Scalar r(0);
        if (behind) {
            detail::solve_radial<FromBackwardAxis>(lens, solved_target, r);
        } else {
            detail::solve_radial<OcamCalibLens>(lens, solved_target, r);
        }
        Scalar slope(0);
        const Scalar reached = behind ? FromBackwardAxis::radial_distortion(lens, r, slope) : radial_distortion(lens, r, slope);
        // On the axis r / rho tends to 1 / (theta'(0) z) = 1 / z.
        const bool on_axis = !(rho > zero);
        const Scalar scale = on_axis ? Scalar(1) / (slope * point.z()) : r / rho;
        const Vec2T n(scale * point.x(), scale * point.y());
        m = affine(k, n);
        const Scalar tolerance = unprojection_tolerance(abs_of(solved_target));
        const bool in_domain = (r < lens.valid_radius) & (norm2 > zero) & (abs_of(reached - solved_target) <= tolerance) &
                               all_finite(m);
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
                // m_x = n_x + e n_y, m_y = d n_x + c n_y.
                d_m_d_coefficients->col(0) = Vec2T(zero, n.y());
                d_m_d_coefficients->col(1) = Vec2T(zero, n.x());
                d_m_d_coefficients->col(2) = Vec2T(n.y(), zero);
                // theta = atan2(r, g): d theta / d k_i = -r^(i + 1) / (r^2 + g^2), and
                // theta' = h / (r^2 + g^2), so d r / d k_i = r^(i + 1) / h(r).
                Scalar g_slope(0);
                const Scalar g = forward(k.template tail<5>(), r, g_slope);
                const Scalar inverse_h = Scalar(1) / (g - r * g_slope);
                const Vec2T direction = on_axis ? Vec2T::Zero().eval() : affine(k, along);
                Scalar power = r * r;
                for (int i = 0; i < kDegree; ++i) {
                    d_m_d_coefficients->col(3 + i) = direction * (power * inverse_h);
                    power *= r;
                }
            }
        }
        return in_domain;
    }

    // False past the valid radius.
    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        using std::sqrt;
        const auto& k = lens.coefficients;
        // A^-1 = [c -e; -d 1] / (c - d e).
        const Scalar inverse_determinant = Scalar(1) / (k(0) - k(1) * k(2));
        const Vec2T n((k(0) * m.x() - k(2) * m.y()) * inverse_determinant, (m.y() - k(1) * m.x()) * inverse_determinant);
        const Scalar r = sqrt(n.squaredNorm());
        Scalar slope(0);
        ray = Vec3T(n.x(), n.y(), forward(k.template tail<5>(), r, slope));
        return (r < lens.valid_radius) & all_finite(ray);
    }

    // g(r) = 1 + k1 r + ... + k5 r^5 and g'(r), from the polynomial's five coefficients.
    template <class T, class Polynomial>
    static T forward(const Polynomial& k, const T& r, T& slope) {
        slope = T(k[0]) + r * (T(2) * T(k[1]) + r * (T(3) * T(k[2]) + r * (T(4) * T(k[3]) + r * T(5) * T(k[4]))));
        return T(1) + r * (T(k[0]) + r * (T(k[1]) + r * (T(k[2]) + r * (T(k[3]) + r * T(k[4])))));
    }

    // theta(r) - pi = -atan2(r, -g(r)) and its slope theta'(r): the solver's d(r) for a
    // point behind the camera.
    struct FromBackwardAxis {
        static Scalar radial_distortion(const Parameters& lens, const Scalar& r, Scalar& slope) {
            Scalar g_slope(0);
            const Scalar g = forward(lens.coefficients.template tail<5>(), r, g_slope);
            slope = (g - r * g_slope) / (r * r + g * g);
            return -angle_from_axis(r, Scalar(-g));
        }
    };

private:
    // theta(r) = atan2(r, g(r)) and theta'(r) = h(r) / (r^2 + g^2), h = g - r g'.
    template <class T, class Polynomial>
    static T angle(const Polynomial& k, const T& r, T& slope) {
        T g_slope(0);
        const T g = forward(k, r, g_slope);
        slope = (g - r * g_slope) / (r * r + g * g);
        return angle_from_axis(r, g);
    }

    static Vec2T affine(const Eigen::Matrix<Scalar, 8, 1>& k, const Vec2T& n) {
        return Vec2T(n.x() + k(2) * n.y(), k(1) * n.x() + k(0) * n.y());
    }

    static Scalar abs_of(const Scalar& x) {
        using std::abs;
        return abs(x);
    }
};

}  // namespace libcam
