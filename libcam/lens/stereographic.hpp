#pragma once
// STEREOGRAPHIC: mrcal's LENSMODEL_STEREOGRAPHIC.
//
//   m = 2 tan(theta / 2) (X, Y) / |(X, Y)| = 2 (X, Y) / (|p| + Z)
//
// with theta the angle from the optical axis (mrcal: q = f m + c).
// unproject: the ray (mx, my, 1 - |m|^2 / 4), as mrcal_unproject_stereographic returns.
//
// Valid domain: every point but the origin and the backward axis (X = Y = 0, Z < 0),
// where |p| + Z = 0. For Z < 0, |p| + Z is evaluated as (X^2 + Y^2) / (|p| - Z), which
// does not cancel. Where X^2 + Y^2 is no longer a normal number (within ~1e-154 rad of
// the backward axis for |p| ~ 1, 1e-19 rad in float; Camera and Projector scale a point
// far from |p| ~ 1 first, see camera/detail/point_scale.hpp) m overflows and the point is
// flagged. Every m has a ray.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <span>

#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"

namespace libcam {

template <class Scalar>
struct StereographicLens {
    static constexpr LensType type = LensType::Stereographic;
    static constexpr int num_coefficients = 0;
    template <class Other>
    using InScalar = StereographicLens<Other>;
    using Parameters = LensParameters<Scalar, 0>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;

    static Parameters parameters(std::span<const double>) { return {}; }

    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters&, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr = nullptr) {
        using std::sqrt;
        const Scalar rho2 = point.x() * point.x() + point.y() * point.y();
        const Scalar norm = sqrt(rho2 + point.z() * point.z());
        const Scalar denominator = norm_plus_z(rho2, norm, point.z());
        if (!(denominator > Scalar(0))) return false;
        const Scalar scale = Scalar(2) / denominator;
        m = Vec2T(point.x() * scale, point.y() * scale);
        if constexpr (is_requested<PointJacobianPtr>) {
            // dm_i/dp_j = (2 delta_ij - m_i d(denominator)/dp_j) / denominator
            const Vec3T d_denominator = point / norm + Vec3T::UnitZ();
            const Scalar inv = Scalar(1) / denominator;
            d_m_d_point->row(0) = -m.x() * inv * d_denominator.transpose();
            d_m_d_point->row(1) = -m.y() * inv * d_denominator.transpose();
            (*d_m_d_point)(0, 0) += scale;
            (*d_m_d_point)(1, 1) += scale;
        }
        // False where rho2, and with it the denominator, is no longer a normal number (near
        // the backward axis, see above): 2 / denominator overflows.
        return all_finite(m);
    }

    // False where |m|^2 overflows (a ray within ~1e-154 rad of the backward axis).
    static bool unproject(const Parameters&, const Vec2T& m, Vec3T& ray) {
        ray = Vec3T(m.x(), m.y(), Scalar(1) - m.squaredNorm() / Scalar(4));
        return all_finite(ray);
    }
};

}  // namespace libcam
