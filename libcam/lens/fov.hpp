#pragma once
// FOV: Devernay and Faugeras' field-of-view model ("Straight lines have to be straight",
// Machine Vision and Applications 2001) with one coefficient omega, as basalt ("fov"),
// COLMAP ("FOV") and Kalibr ("pinhole-fov") define it:
//
//   r = |(X, Y)| / Z,   r_d = atan(2 tan(omega / 2) r) / omega,   m = r_d (X, Y) / |(X, Y)|
//
// COLMAP and Kalibr apply it to (X/Z, Y/Z), so points in front of the camera only; basalt
// writes atan(2 tan(omega / 2) r) as atan2(2 tan(omega / 2) |(X, Y)|, Z), which goes on
// past 90 degrees, and so does libcam: with a = 2 tan(omega / 2) it is the equidistant
// angle of the point (a X, a Y, Z) over omega,
//
//   m = u(a X, a Y, Z) / omega,   u(p) = atan2(|(X, Y)|, Z) (X, Y) / |(X, Y)|
//
// (FISHEYE's equidistant point, with its series on and near the axis). That form has no
// 0 / 0 as omega -> 0, where r_d -> r: omega = 0 is the pinhole, exactly.
//
// Unprojection is closed form: phi = omega |m| is the angle of (a X, a Y, Z), so the ray
// is (m (omega / a) sin(phi) / phi, cos(phi)).
//
// Valid domain: 0 <= omega < pi. For omega > 0 every point but the origin and the
// backward axis (angle below valid_radius() = pi; as for FISHEYE, a point so close to
// that axis that a^2 (X^2 + Y^2) is no longer a normal number is flagged), and every m
// with omega |m| < pi (its image is the disc |m| < pi / omega). omega = 0: the pinhole,
// z > 0.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <string>

#include "libcam/lens/fisheye.hpp"
#include "libcam/lens/lane.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/pinhole.hpp"
#include "libcam/lens/sine_cosine.hpp"

namespace libcam {

template <class Scalar>
struct FovLens {
    static constexpr LensType type = LensType::Fov;
    static constexpr int num_coefficients = 1;
    template <class Other>
    using InScalar = FovLens<Other>;
    // The coefficient, and for the batch loops a = 2 tan(omega / 2) worked out once per
    // camera (see scale_a).
    struct Parameters {
        Eigen::Matrix<Scalar, 1, 1> coefficients;
        Scalar valid_radius = Scalar(std::numeric_limits<double>::infinity());
        Scalar a = Scalar(0);
    };
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian23 = Eigen::Matrix<Scalar, 2, 3>;

    // The largest angle from the optical axis: pi (all but the backward axis) for
    // omega > 0; the pinhole's pi / 2 for omega = 0.
    static double valid_radius(std::span<const double> c) {
        return c[0] > 0 ? std::numbers::pi : std::numbers::pi / 2;
    }

    static Parameters parameters(std::span<const double> c) { return parameters(c, valid_radius(c)); }

    // With the valid radius worked out before (the batch paths keep it per camera).
    static Parameters parameters(std::span<const double> c, double radius) {
        using std::tan;
        const LensParameters<Scalar, 1> given = lens_parameters<Scalar, 1>(c, radius);
        Parameters lens{given.coefficients, given.valid_radius};
        lens.a = Scalar(2) * tan(lens.coefficients(0) / Scalar(2));
        return lens;
    }

    // a = 2 tan(omega / 2). The batch loops (Lane) read it from the parameters, worked out
    // once per camera: a libm tangent per point took half of a batch projection's time and
    // kept the unprojection's loop scalar. Every other type works it out from the
    // coefficient it holds, the same bits, so that a caller who changes the coefficient (a
    // fit, a derivative by differences) never meets a stale value.
    static Scalar scale_a(const Parameters& lens) {
        if constexpr (is_lane_v<Scalar>) {
            return by_value(lens.a);
        } else {
            using std::tan;
            return Scalar(2) * tan(lens.coefficients(0) / Scalar(2));
        }
    }

    static void check_coefficients(std::span<const double> c, const char* field) {
        if (!(c[0] >= 0 && c[0] < std::numbers::pi)) {
            throw InvalidArgument(std::string(field) + "[0] (omega): must be in [0, pi) radians, got " + format_number(c[0]));
        }
    }

    // False for the origin and the backward axis (and z <= 0 when omega = 0), and where m
    // is not finite.
    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        const Scalar omega = by_value(lens.coefficients(0));
        if (omega == Scalar(0)) {  // the same for every point of the camera
            if constexpr (is_requested<CoefficientJacobianPtr>) d_m_d_coefficients->setZero();  // r_d = r + O(omega^2)
            return PinholeLens<Scalar>::project(point, m, d_m_d_point) & all_finite(m);
        }
        const Scalar a = scale_a(lens);
        const Vec3T scaled(a * point.x(), a * point.y(), point.z());
        Vec2T u = Vec2T::Zero();  // equidistant_point leaves it unset where it flags the point
        Jacobian23 d_u_d_scaled;
        constexpr bool kChain = is_requested<PointJacobianPtr> || is_requested<CoefficientJacobianPtr>;
        bool imaged = false;
        if constexpr (kChain) {
            imaged = FisheyeLens<Scalar>::equidistant_point(scaled, u, &d_u_d_scaled);
        } else {
            imaged = FisheyeLens<Scalar>::equidistant_point(scaled, u);
        }
        const Scalar inverse_omega = Scalar(1) / omega;
        m = u * inverse_omega;
        if constexpr (is_requested<PointJacobianPtr>) {
            *d_m_d_point = d_u_d_scaled * inverse_omega;
            d_m_d_point->template leftCols<2>() *= a;
        }
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            // m = u(a(omega)) / omega: d m / d omega = (du/da  da/domega - m) / omega, with
            // du/da = d u / d scaled (X, Y, 0) and da/domega = 1 + a^2 / 4. (The two terms
            // cancel as omega -> 0, where the derivative itself goes to 0 like omega.)
            const Vec2T d_u_d_a = d_u_d_scaled.template leftCols<2>() * point.template head<2>();
            d_m_d_coefficients->col(0) = (d_u_d_a * (Scalar(1) + a * a / Scalar(4)) - m) * inverse_omega;
        }
        return imaged & all_finite(m);
    }

    // The ray through m; false where omega |m| reaches pi (past the image's disc).
    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        using std::sqrt;
        // No branch, which would stop the batch loops' vectoriser: omega = 0, the pinhole, is
        // (m, 1), chosen at the end.
        const Scalar omega = by_value(lens.coefficients(0));
        const bool pinhole = omega == Scalar(0);
        const Scalar phi = omega * sqrt(m.squaredNorm());
        Scalar sin_phi, cos_phi;
        sine_cosine(phi, sin_phi, cos_phi);  // arithmetic, so the batch loops vectorise
        // sin(phi) / phi, 1 on the axis.
        const Scalar sinc = phi > Scalar(0) ? Scalar(sin_phi / phi) : Scalar(1);
        const Scalar scale = pinhole ? Scalar(1) : Scalar(omega / scale_a(lens) * sinc);
        ray = Vec3T(m.x() * scale, m.y() * scale, pinhole ? Scalar(1) : cos_phi);
        return (pinhole | (phi < Scalar(std::numbers::pi))) & all_finite(ray);
    }
};

}  // namespace libcam
