#pragma once
// PTLENS: PanoTools' radial polynomial (Helmut Dersch's PanoTools, "Lens correction
// model"; Hugin's a b c; lensfun's "ptlens" model), in units of the focal length:
//
//   u = (x, y) = (X/Z, Y/Z),  r = |u|,
//   m = u (1 + c r + b r^2 + a r^3)
//
// Coefficients a b c (in PanoTools' order). PanoTools writes the polynomial
// r_src = r (a r^3 + b r^2 + c r + d), d = 1 - a - b - c, with r = 1 at half the shorter
// side of the image; lensfun rescales it to r in units of the focal length with d = 1
// (rescale_polynomial_coefficients: a' = a s^3 / d^4, b' = b s^2 / d^3, c' = c s / d^2,
// s the real focal length over half the shorter side), and these are those a' b' c'. The
// odd powers of r (a and c) are what no OpenCV model has: with a = c = 0 this is OPENCV4
// with k1 = b.
//
// Valid domain: Z > 0 and r below the first r > 0 where the radial map g(r) = r (1 + c r
// + b r^2 + a r^3) folds over, g'(r) = 1 + 2 c r + 3 b r^2 + 4 a r^3 = 0 (infinity where it
// never does); g(0) = 0 and g' > 0 below it, so g is one-to-one there. unproject solves
// distort for u with the certified solver (undistort.hpp), started from g.
//
// r is evaluated as sqrt(x^2 + y^2 + FLT_MIN): at u = 0 the derivative of r u (0) is then
// the limit, not 0 / 0, in every scalar type (Jets included); elsewhere the term moves r
// by less than a rounding where r > 1e-11 and by less than 1e-19 anywhere.

#include <Eigen/Core>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <span>

#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/pinhole.hpp"
#include "libcam/lens/undistort.hpp"
#include "libcam/lens/valid_radius.hpp"

namespace libcam {

// PanoTools' radial polynomial of a point u, r = |u|: m = u (1 + c r + b r^2 + a r^3 + k2 r^4),
// and d m / d u when asked; returns r^2, for the caller's domain check. PTLENS's (k2 = 0, u
// the pinhole point) and the fisheye *_RADIAL models' (u their projection's point,
// fisheye_radial.hpp). The derivative of the factor is (c + 2 b r + 3 a r^2 + 4 k2 r^3) u / r.
template <class Scalar, class UJacobianPtr>
Scalar panotools_distort(const Eigen::Matrix<Scalar, 2, 1>& u, const Scalar& a, const Scalar& b, const Scalar& c,
                         const Scalar& k2, Eigen::Matrix<Scalar, 2, 1>& m, UJacobianPtr d_m_d_u, Scalar& r) {
    using std::sqrt;
    const Scalar r2 = u.x() * u.x() + u.y() * u.y();
    r = sqrt(r2 + Scalar(FLT_MIN));
    const Scalar factor = Scalar(1) + r * (c + r * (b + r * (a + r * k2)));
    m = u * factor;
    if constexpr (is_requested<UJacobianPtr>) {
        const Scalar along = c / r + Scalar(2) * b + r * (Scalar(3) * a + Scalar(4) * k2 * r);
        const Scalar xy = along * u.x() * u.y();
        Eigen::Matrix<Scalar, 2, 2> jacobian;
        jacobian << factor + along * u.x() * u.x(), xy,  //
            xy, factor + along * u.y() * u.y();
        *d_m_d_u = jacobian;
    }
    return r2;
}

// The radial map g(r) = r (1 + c r + b r^2 + a r^3 + k2 r^4) and its slope: the solver's 1-D start.
template <class Scalar>
Scalar panotools_radial(const Scalar& r, const Scalar& a, const Scalar& b, const Scalar& c, const Scalar& k2,
                        Scalar& slope) {
    const Scalar one(1);
    slope = one + r * (Scalar(2) * c + r * (Scalar(3) * b + r * (Scalar(4) * a + r * Scalar(5) * k2)));
    return r * (one + r * (c + r * (b + r * (a + r * k2))));
}

template <class Scalar>
struct PtlensLens : OnPinholePoint<PtlensLens<Scalar>, Scalar> {
    static constexpr LensType type = LensType::Ptlens;
    static constexpr int num_coefficients = 3;
    template <class Other>
    using InScalar = PtlensLens<Other>;
    using Parameters = LensParameters<Scalar, 3>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;
    using CoefficientJacobian = Eigen::Matrix<Scalar, 2, 3>;

    // The radius where g folds over (above); +infinity if it never does.
    static double valid_radius(std::span<const double> k) {
        const double slope[] = {1.0, 2.0 * k[2], 3.0 * k[1], 4.0 * k[0]};
        return smallest_positive_root(slope);
    }

    static Parameters parameters(std::span<const double> k) { return lens_parameters<Scalar, 3>(k, valid_radius(k)); }

    // project, unproject and ray_from_undistorted: OnPinholePoint's (pinhole.hpp).

    // m of the pinhole point u; false outside the valid domain.
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& u, Vec2T& m, UJacobianPtr d_m_d_u = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        const auto& k = lens.coefficients;
        Scalar r;
        const Scalar r2 = panotools_distort(u, Scalar(k(0)), Scalar(k(1)), Scalar(k(2)), Scalar(0), m, d_m_d_u, r);
        const bool in_domain = (r2 < lens.valid_radius * lens.valid_radius) & all_finite(m);  // &: no branch
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            d_m_d_coefficients->col(2) = u * r;
            d_m_d_coefficients->col(1) = u * r2;
            d_m_d_coefficients->col(0) = u * (r2 * r);
        }
        return in_domain;
    }

    // The radial map g(r) and its slope g'(r): the solver's 1-D start.
    static Scalar radial_distortion(const Parameters& lens, const Scalar& r, Scalar& slope) {
        const auto& k = lens.coefficients;
        return panotools_radial(r, Scalar(k(0)), Scalar(k(1)), Scalar(k(2)), Scalar(0), slope);
    }
};

}  // namespace libcam
