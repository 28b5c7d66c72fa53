#pragma once
// FTHETA_FORWARD: NVIDIA's F-theta model with its forward polynomial as the reference
// (NCore's reference_poly ANGLE_TO_PIXELDIST, DriveWorks' "polynomial-type":
// "angle-to-pixeldistance"): the distance from the principal point on the sensor is a
// polynomial of the angle from the optical axis, behind the affine [c d; e 1] of FTHETA
// (ftheta.hpp, where the backward polynomial is the reference):
//
//   theta = atan2(|(X, Y)|, Z),  u = theta (X, Y) / |(X, Y)|   (FISHEYE's equidistant point)
//   rho(theta) = k1 theta + k2 theta^2 + k3 theta^3 + k4 theta^4 + k5 theta^5
//   m = A rho(theta) (X, Y) / |(X, Y)| = A S(theta) u,  S(theta) = rho(theta) / theta
//
// Coefficients c, d, e, k1..k5, max_angle. NVIDIA's files give the polynomial in pixels,
// a0 + a1 theta + ... + a5 theta^5 (angle_to_pixeldist_poly); with K's fx = fy = f,
// k_i = a_i / f (io/detail/driveworks_rig.cpp takes f = a1, so k1 = 1); a0 must be 0.
// THETA_POLYNOMIAL (WoodScape's) is this lens of degree 4 without the affine.
//
// project is the formula (gsplat's camera_ray_to_image_point, 3DGUT's projectPoint with
// ANGLE_TO_PIXELDIST). unproject is the certified solver of undistort.hpp (NVIDIA runs
// three Newton steps from its backward polynomial, the fitted approximate inverse).
//
// Valid domain: theta < valid_radius = the first angle where rho stops growing (a root of
// k1 + 2 k2 theta + ... + 5 k5 theta^4), max_angle or pi, whichever comes first. k1 > 0,
// c - d e > 0 and max_angle in (0, pi] (check_coefficients).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <span>
#include <string>

#include "libcam/error.hpp"
#include "libcam/lens/fisheye.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/valid_radius.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

template <class Scalar>
struct FThetaForwardLens : OnEquidistantPoint<FThetaForwardLens<Scalar>, Scalar> {
    static constexpr LensType type = LensType::FThetaForward;
    static constexpr int num_coefficients = 9;
    static constexpr int kMaxAngle = 8;  // the index of max_angle
    template <class Other>
    using InScalar = FThetaForwardLens<Other>;
    using Parameters = LensParameters<Scalar, 9>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;

    static void check_coefficients(std::span<const double> k, const char* field) {
        const double determinant = k[0] - k[1] * k[2];
        if (!(determinant > 0.0)) {
            throw InvalidArgument(std::string(field) + " (c, d, e): the affine's determinant c - d e must be positive, got " +
                                  format_number(determinant));
        }
        if (!(k[3] > 0.0)) {
            throw InvalidArgument(std::string(field) + "[3] (k1): must be positive (the radius must grow with the " +
                                  "angle at the centre), got " + format_number(k[3]));
        }
        if (!(k[kMaxAngle] > 0.0 && k[kMaxAngle] <= std::numbers::pi)) {
            throw InvalidArgument(std::string(field) + "[8] (max_angle): must be in (0, pi] radians, got " +
                                  format_number(k[kMaxAngle]));
        }
    }

    // The angle (radians) below which rho grows, below max_angle and below pi.
    static double valid_radius(std::span<const double> k) {
        if (!(k[3] > 0.0) || !(k[kMaxAngle] > 0.0)) return 0.0;
        const double slope[] = {k[3], 2 * k[4], 3 * k[5], 4 * k[6], 5 * k[7]};
        return std::min({smallest_positive_root(slope), k[kMaxAngle], std::numbers::pi});
    }

    static Parameters parameters(std::span<const double> k) { return lens_parameters<Scalar, 9>(k, valid_radius(k)); }

    // m = A S(theta) u for the equidistant point u (|u| = theta); false outside the domain.
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& u, Vec2T& m, UJacobianPtr d_m_d_u = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        using std::sqrt;
        const auto& k = lens.coefficients;
        const Scalar s = u.squaredNorm();
        const Scalar theta = sqrt(s);
        const bool in_domain = s < lens.valid_radius * lens.valid_radius;
        const Scalar factor = stretch(k, theta);
        const Vec2T q = u * factor;
        m = affine(k, q);
        if constexpr (is_requested<UJacobianPtr>) {
            // d S(|u|) / d u = S'(theta) u / theta; S'(theta) / theta = k2 / theta + 2 k3 +
            // 3 k4 theta + 4 k5 theta^2, whose k2 term is singular at the centre: the outer
            // product u u^T / theta vanishes there.
            const bool at_centre = !(theta > Scalar(0));
            const Scalar inverse_theta = at_centre ? Scalar(0) : Scalar(Scalar(1) / theta);
            const Scalar slope_over_theta =
                k(4) * inverse_theta + Scalar(2) * k(5) + theta * (Scalar(3) * k(6) + theta * Scalar(4) * k(7));
            const Jacobian22 d_q_d_u = Jacobian22::Identity() * factor + slope_over_theta * u * u.transpose();
            Jacobian22 a;
            a << k(0), k(1), k(2), Scalar(1);
            *d_m_d_u = a * d_q_d_u;
        }
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            const Scalar zero(0);
            d_m_d_coefficients->col(0) = Vec2T(q.x(), zero);
            d_m_d_coefficients->col(1) = Vec2T(q.y(), zero);
            d_m_d_coefficients->col(2) = Vec2T(zero, q.x());
            const Vec2T along = affine(k, u);
            Scalar power(1);
            for (int i = 0; i < 5; ++i, power *= theta) d_m_d_coefficients->col(3 + i) = along * power;
            d_m_d_coefficients->col(kMaxAngle).setZero();  // a bound, not part of the map
        }
        return in_domain & all_finite(m);
    }

    // rho(theta) and its slope: the 1-D start of unproject.
    static Scalar radial_distortion(const Parameters& lens, const Scalar& theta, Scalar& slope) {
        const auto& k = lens.coefficients;
        slope = k(3) + theta * (Scalar(2) * k(4) + theta * (Scalar(3) * k(5) + theta * (Scalar(4) * k(6) + theta * Scalar(5) * k(7))));
        return theta * stretch(k, theta);
    }

private:
    // S(theta) = rho(theta) / theta.
    template <class Coefficients>
    static Scalar stretch(const Coefficients& k, const Scalar& theta) {
        return k(3) + theta * (k(4) + theta * (k(5) + theta * (k(6) + theta * k(7))));
    }

    template <class Coefficients>
    static Vec2T affine(const Coefficients& k, const Vec2T& q) {
        return Vec2T(k(0) * q.x() + k(1) * q.y(), k(2) * q.x() + q.y());
    }
};

}  // namespace libcam
