#pragma once
// BROWN_K4: Brown's radial-tangential lens with a fourth radial coefficient, the r^8 term
// of Agisoft Metashape's frame camera (its manual's appendix "Camera models") and of
// RealityCapture's brown4 and brown4t2. Coefficients in OpenCV's order, k4 last:
//
//     k1 k2 p1 p2 k3 k4
//
//   u = (x, y) = (X/Z, Y/Z),   r2 = x^2 + y^2,
//   R = 1 + k1 r2 + k2 r2^2 + k3 r2^3 + k4 r2^4
//   m = ( x R + 2 p1 x y + p2 (r2 + 2 x^2),
//         y R + p1 (r2 + 2 y^2) + 2 p2 x y )
//
// With k4 = 0 this is OPENCV5. It is not OPENCV8, whose k4 divides (1 + k4 r2 + ...).
// Metashape writes the tangential pair the other way round (its P1 is p2 here, its P2 is
// p1), and so does RealityCapture (its t1 is p2, its t2 is p1): the readers swap them.
//
// Valid domain: Z > 0 and r below valid_radius(), the first r where the radial part r R(r)
// folds over (from k1..k4: the tangential terms are taken to be small, as for OpenCV's
// models); +infinity where it never does. Where R overflows (r^8 past the largest number)
// m is not finite and project() flags the point. unproject solves distort with the
// certified solver (undistort.hpp), started from the radial part.

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/pinhole.hpp"
#include "libcam/lens/undistort.hpp"
#include "libcam/lens/valid_radius.hpp"

namespace libcam {

template <class Scalar>
struct BrownK4Lens : OnPinholePoint<BrownK4Lens<Scalar>, Scalar> {
    static constexpr LensType type = LensType::BrownK4;
    static constexpr int num_coefficients = 6;
    template <class Other>
    using InScalar = BrownK4Lens<Other>;
    using Parameters = LensParameters<Scalar, 6>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;
    using CoefficientJacobian = Eigen::Matrix<Scalar, 2, 6>;

    // The normalised radius r past which r R(r) folds over; +infinity if it never does.
    static double valid_radius(std::span<const double> k) {
        const double numerator[] = {1.0, k[0], k[1], k[4], k[5]};
        const double denominator[] = {1.0};
        return radial_valid_radius(numerator, denominator);
    }

    static Parameters parameters(std::span<const double> k) { return lens_parameters<Scalar, 6>(k, valid_radius(k)); }

    // project, unproject and ray_from_undistorted: OnPinholePoint's (pinhole.hpp).

    // m of the pinhole point u; false outside the valid domain (no branch: see pinhole.hpp).
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& u, Vec2T& m, UJacobianPtr d_m_d_u = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        const auto& k = lens.coefficients;
        const Scalar x = u.x(), y = u.y(), p1 = k(2), p2 = k(3), two(2);
        const Scalar r2 = x * x + y * y;
        Scalar d_radial_d_r2;
        const Scalar radial = radial_factor(lens, r2, d_radial_d_r2);
        const Scalar xy2 = two * x * y;
        m = Vec2T(x * radial + p1 * xy2 + p2 * (r2 + two * x * x), y * radial + p1 * (r2 + two * y * y) + p2 * xy2);
        const bool in_domain = r2 < lens.valid_radius * lens.valid_radius;
        if constexpr (is_requested<UJacobianPtr>) {
            const Scalar mixed = xy2 * d_radial_d_r2 + two * (p1 * x + p2 * y);
            Jacobian22 jacobian;
            jacobian << radial + two * x * x * d_radial_d_r2 + two * p1 * y + Scalar(6) * p2 * x, mixed,  //
                mixed, radial + two * y * y * d_radial_d_r2 + Scalar(6) * p1 * y + two * p2 * x;
            *d_m_d_u = jacobian;
        }
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            const Scalar r4 = r2 * r2;
            d_m_d_coefficients->col(0) = u * r2;
            d_m_d_coefficients->col(1) = u * r4;
            d_m_d_coefficients->col(2) = Vec2T(xy2, r2 + two * y * y);
            d_m_d_coefficients->col(3) = Vec2T(r2 + two * x * x, xy2);
            d_m_d_coefficients->col(4) = u * (r4 * r2);
            d_m_d_coefficients->col(5) = u * (r4 * r4);
        }
        return in_domain;
    }

    // The radial part alone, d(r) = r R(r^2), and its slope: the solver's 1-D start.
    static Scalar radial_distortion(const Parameters& lens, const Scalar& r, Scalar& slope) {
        const Scalar r2 = r * r;
        Scalar d_radial_d_r2;
        const Scalar radial = radial_factor(lens, r2, d_radial_d_r2);
        slope = radial + Scalar(2) * r2 * d_radial_d_r2;
        return r * radial;
    }

private:
    // R(r2) = 1 + k1 r2 + k2 r2^2 + k3 r2^3 + k4 r2^4 by Horner, and dR/d(r2).
    static Scalar radial_factor(const Parameters& lens, const Scalar& r2, Scalar& d_r2) {
        const auto& k = lens.coefficients;
        const Scalar k1 = k(0), k2 = k(1), k3 = k(4), k4 = k(5);
        d_r2 = k1 + r2 * (Scalar(2) * k2 + r2 * (Scalar(3) * k3 + r2 * Scalar(4) * k4));
        return Scalar(1) + r2 * (k1 + r2 * (k2 + r2 * (k3 + r2 * k4)));
    }
};

}  // namespace libcam
