#pragma once
// EQUIDISTANT_RADIAL, EQUISOLID_RADIAL, STEREOGRAPHIC_RADIAL: a fisheye projection
// followed by a radial polynomial of the projected radius, as lensfun corrects its
// fisheye lenses and PanoTools (Hugin) its fisheye projections with a b c:
//
//   theta = the angle from the optical axis,  dir = (X, Y) / |(X, Y)|
//   u     = P(theta) dir   with P(theta) = theta           (equidistant: lensfun's "fisheye",
//                                                            Hugin's f2 and f3)
//                                   2 sin(theta / 2)        (equisolid: lensfun's "equisolid",
//                                                            Hugin's f21)
//                                   2 tan(theta / 2)        (stereographic: lensfun's
//                                                            "stereographic", Hugin's f10)
//   r     = |u|,  m = u (1 + c r + b r^2 + a r^3 + k2 r^4)
//
// Coefficients a b c k2, in units of the focal length. a b c are PTLENS's (PanoTools' and
// lensfun's ptlens, rescaled to the focal length with d = 1: ptlens.hpp says how); lensfun's
// poly3 is b alone, its poly5 b and k2. lensfun applies its distortion after its geometry
// step, on the lens's own projection (mod-coord.cpp: the geometry callbacks at priority
// 500, then the distortion callbacks at 750, for an output pixel going back to the
// source), which is what m is here; with every coefficient 0 the model is its bare
// projection (FISHEYE with zero coefficients, EQUISOLID, STEREOGRAPHIC).
//
// Valid domain: theta below the projection's edge (pi, less the points too near the
// backward axis that the bare projection flags) and r below the first r > 0 where
// g(r) = r (1 + c r + b r^2 + a r^3 + k2 r^4) folds over: g'(r) = 1 + 2 c r + 3 b r^2
// + 4 a r^3 + 5 k2 r^4 = 0. valid_radius is that bound on r (in the plane of u, not an
// angle; valid_angle() gives the angle, P's inverse of it). unproject solves g for u with
// the certified solver (undistort.hpp), then inverts P.
//
// The polynomial is PTLENS's (panotools_distort, ptlens.hpp), r evaluated as sqrt(r^2 +
// FLT_MIN) there: the derivative of c r u at u = 0 is then its limit, not 0 / 0, in every
// scalar type.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>

#include "libcam/lens/equisolid.hpp"
#include "libcam/lens/fisheye.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/ptlens.hpp"
#include "libcam/lens/stereographic.hpp"
#include "libcam/lens/undistort.hpp"
#include "libcam/lens/valid_radius.hpp"

namespace libcam {

// The three projections: the point u = P(theta) dir of a camera point (false where the
// bare projection flags it), the ray through u, and P's edge and inverse.
template <class Scalar>
struct EquidistantProjection {
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    static constexpr double kEdgeRadius = std::numbers::pi;  // P(pi)
    template <class JacobianPtr>
    static bool point(const Vec3T& p, Vec2T& u, JacobianPtr d_u_d_p) {
        return FisheyeLens<Scalar>::equidistant_point(p, u, d_u_d_p);
    }
    static Vec3T ray(const Vec2T& u) { return FisheyeLens<Scalar>::ray_from_equidistant(u); }
    static double angle(double radius) { return radius; }
};

template <class Scalar>
struct EquisolidProjection {
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    static constexpr double kEdgeRadius = 2.0;
    template <class JacobianPtr>
    static bool point(const Vec3T& p, Vec2T& u, JacobianPtr d_u_d_p) {
        return EquisolidLens<Scalar>::project({}, p, u, d_u_d_p);
    }
    // Inside the disc |u| < 2, which the valid radius keeps u to.
    static Vec3T ray(const Vec2T& u) {
        Vec3T out;
        EquisolidLens<Scalar>::unproject({}, u, out);
        return out;
    }
    static double angle(double radius) { return 2.0 * std::asin(std::min(radius / 2.0, 1.0)); }
};

template <class Scalar>
struct StereographicProjection {
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    static constexpr double kEdgeRadius = std::numeric_limits<double>::infinity();
    template <class JacobianPtr>
    static bool point(const Vec3T& p, Vec2T& u, JacobianPtr d_u_d_p) {
        return StereographicLens<Scalar>::project({}, p, u, d_u_d_p);
    }
    static Vec3T ray(const Vec2T& u) {
        Vec3T out;
        StereographicLens<Scalar>::unproject({}, u, out);
        return out;
    }
    static double angle(double radius) { return 2.0 * std::atan(radius / 2.0); }
};

template <template <class> class Projection, LensType Type, class Scalar>
struct FisheyeRadialLens {
    static constexpr LensType type = Type;
    static constexpr int num_coefficients = 4;
    template <class Other>
    using InScalar = FisheyeRadialLens<Projection, Type, Other>;
    using Parameters = LensParameters<Scalar, 4>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;
    using Jacobian23 = Eigen::Matrix<Scalar, 2, 3>;

    // The bound on r = |u|: where g folds over, or the projection's edge, whichever is first.
    static double valid_radius(std::span<const double> k) {
        const double slope[] = {1.0, 2.0 * k[2], 3.0 * k[1], 4.0 * k[0], 5.0 * k[3]};
        return std::min(smallest_positive_root(slope), Projection<double>::kEdgeRadius);
    }

    static Parameters parameters(std::span<const double> k) { return lens_parameters<Scalar, 4>(k, valid_radius(k)); }

    // The largest angle from the axis imaged: the angle whose projected radius is the valid radius.
    static double valid_angle(std::span<const double>, double radius) {
        return std::min(Projection<double>::angle(radius), std::numbers::pi);
    }

    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        // Zero where the projection flags the point without writing u (STEREOGRAPHIC's
        // origin and backward axis): distort then reads a value, and the flag says no.
        Vec2T u(Scalar(0), Scalar(0));
        Jacobian23 d_u_d_point;
        const bool defined = Projection<Scalar>::point(point, u, pass_request<PointJacobianPtr>(&d_u_d_point));
        Jacobian22 d_m_d_u;
        const bool in_domain = distort(lens, u, m, pass_request<PointJacobianPtr>(&d_m_d_u), d_m_d_coefficients);
        if constexpr (is_requested<PointJacobianPtr>) *d_m_d_point = d_m_d_u * d_u_d_point;
        return defined & in_domain & all_finite(m);  // &, not &&: no branch
    }

    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        return unproject_solved<FisheyeRadialLens>(lens, m, ray);
    }

    static Vec3T ray_from_undistorted(const Parameters&, const Vec2T& u) { return Projection<Scalar>::ray(u); }

    // m of the projected point u; false outside the valid domain.
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& u, Vec2T& m, UJacobianPtr d_m_d_u = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        const auto& k = lens.coefficients;
        Scalar r;
        const Scalar r2 = panotools_distort(u, Scalar(k(0)), Scalar(k(1)), Scalar(k(2)), Scalar(k(3)), m, d_m_d_u, r);
        const bool in_domain = (r2 < lens.valid_radius * lens.valid_radius) & all_finite(m);  // &: no branch
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            d_m_d_coefficients->col(2) = u * r;
            d_m_d_coefficients->col(1) = u * r2;
            d_m_d_coefficients->col(0) = u * (r2 * r);
            d_m_d_coefficients->col(3) = u * (r2 * r2);
        }
        return in_domain;
    }

    // g(r) and g'(r): the solver's 1-D start.
    static Scalar radial_distortion(const Parameters& lens, const Scalar& r, Scalar& slope) {
        const auto& k = lens.coefficients;
        return panotools_radial(r, Scalar(k(0)), Scalar(k(1)), Scalar(k(2)), Scalar(k(3)), slope);
    }
};

template <class Scalar>
using EquidistantRadialLens = FisheyeRadialLens<EquidistantProjection, LensType::EquidistantRadial, Scalar>;
template <class Scalar>
using EquisolidRadialLens = FisheyeRadialLens<EquisolidProjection, LensType::EquisolidRadial, Scalar>;
template <class Scalar>
using StereographicRadialLens = FisheyeRadialLens<StereographicProjection, LensType::StereographicRadial, Scalar>;

}  // namespace libcam
