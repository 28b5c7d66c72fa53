#pragma once
// EQUISOLID: the equal-area (equisolid-angle) fisheye, as Blender's Cycles renders it
// (panorama type FISHEYE_EQUISOLID, r = 2 f sin(theta / 2)):
//
//   m = 2 sin(theta / 2) (X, Y) / |(X, Y)| = (X, Y) sqrt(2 / (|p| (|p| + Z)))
//
// with theta the angle from the optical axis (the second form from
// sin(theta / 2) = sqrt((|p| - Z) / (2 |p|)) and X^2 + Y^2 = (|p| - Z)(|p| + Z)).
// unproject: with c = sqrt(1 - |m|^2 / 4) = cos(theta / 2), the ray (c m, 1 - |m|^2 / 2).
//
// Valid domain: every point but the origin and the backward axis, where |p| + Z = 0;
// for Z < 0, |p| + Z is evaluated as (X^2 + Y^2) / (|p| - Z), which does not cancel, as
// STEREOGRAPHIC does; where X^2 + Y^2 is no longer a normal number there (within ~1e-154
// rad of the backward axis in double), the point is flagged. The image is the disc
// |m| < 2 (theta < pi); a pixel outside it has no ray.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <span>

#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"

namespace libcam {

template <class Scalar>
struct EquisolidLens {
    static constexpr LensType type = LensType::Equisolid;
    static constexpr int num_coefficients = 0;
    template <class Other>
    using InScalar = EquisolidLens<Other>;
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
        const Scalar sum = norm_plus_z(rho2, norm, point.z());  // |p| + Z
        const Scalar product = norm * sum;
        // Behind the camera, X^2 + Y^2 must be a normal number: |m| = rho sqrt(2 / product)
        // with product = |p| rho^2 / (|p| - Z) would otherwise mix rho and a rho^2 that has
        // lost its digits (the point is then within ~1e-154 rad of the backward axis).
        const bool in_domain = (product > Scalar(0)) & ((point.z() >= Scalar(0)) | (rho2 >= smallest_normal<Scalar>()));
        const Scalar scale = sqrt(Scalar(2) / product);
        m = Vec2T(point.x() * scale, point.y() * scale);
        if constexpr (is_requested<PointJacobianPtr>) {
            // m_i = p_i s, s = sqrt(2 / g), g = |p| (|p| + Z): dm_i/dp_j = s delta_ij - m_i (dg/dp_j) / (2 g),
            // dg/dp = (|p| + Z) p / |p| + p + |p| e_z.
            const Vec3T d_product = point * (sum / norm) + point + Vec3T::UnitZ() * norm;
            const Scalar half_inverse = Scalar(1) / (Scalar(2) * product);
            d_m_d_point->row(0) = -m.x() * half_inverse * d_product.transpose();
            d_m_d_point->row(1) = -m.y() * half_inverse * d_product.transpose();
            (*d_m_d_point)(0, 0) += scale;
            (*d_m_d_point)(1, 1) += scale;
        }
        // Also false where the product is no longer a normal number (next to the backward
        // axis): the scale overflows.
        return in_domain & all_finite(m);
    }

    // False outside the image disc |m| < 2.
    static bool unproject(const Parameters&, const Vec2T& m, Vec3T& ray) {
        using std::sqrt;
        const Scalar quarter = m.squaredNorm() / Scalar(4);  // sin^2(theta / 2)
        const bool inside = quarter < Scalar(1);
        const Scalar cos_half = sqrt(Scalar(1) - quarter);
        ray = Vec3T(m.x() * cos_half, m.y() * cos_half, Scalar(1) - Scalar(2) * quarter);
        return inside & all_finite(ray);
    }
};

}  // namespace libcam
