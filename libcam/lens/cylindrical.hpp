#pragma once
// CYLINDRICAL: the central cylindrical projection, a panorama whose verticals stay
// straight (the cylinder X^2 + Z^2 = 1 about the camera's Y axis, unrolled):
//
//   m = (longitude, height on the cylinder) = (atan2(X, Z), Y / |(X, Z)|)
//
// Across, it is LONLAT (square pixels per radian of longitude); down, it is a pinhole
// (per unit of tan(latitude)). OpenCV's stitching module draws the same projection
// (cv::detail::CylindricalWarper: u = s atan2(x, z), v = s y / sqrt(x^2 + z^2)), as do
// Hugin and PTGui ("cylindrical").
// unproject: the ray (sin(lon), m_y, cos(lon)), which has |(X, Z)| = 1.
//
// Valid domain: every point off the Y axis (|(X, Z)| > 0; on it the longitude is
// undefined and the height infinite), so also behind the camera. A point whose X^2 + Z^2
// is not a normal number (within about 1e-154 rad of the Y axis in double, once libcam
// has scaled the point towards unit length: its height would be past 1e154, off any
// image, and no longer accurate) is flagged. A pixel has a ray for |lon| <= pi and any
// height.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <span>

#include "libcam/geometry/vector_math.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"

namespace libcam {

template <class Scalar>
struct CylindricalLens {
    static constexpr LensType type = LensType::Cylindrical;
    static constexpr int num_coefficients = 0;
    template <class Other>
    using InScalar = CylindricalLens<Other>;
    using Parameters = LensParameters<Scalar, 0>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;

    static Parameters parameters(std::span<const double>) { return {}; }

    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters&, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr = nullptr) {
        using std::atan2;
        using std::sqrt;
        const Scalar x = point.x(), y = point.y(), z = point.z();
        const Scalar h2 = x * x + z * z;  // squared distance from the Y axis
        const Scalar h = sqrt(h2);
        m = Vec2T(atan2(x, z), y / h);
        if constexpr (is_requested<PointJacobianPtr>) {
            // d(lon) = (z dx - x dz) / h^2; d(y / h) = dy / h - y (x dx + z dz) / h^3.
            const Scalar inv_h2 = Scalar(1) / h2;
            const Scalar height_across = -m.y() * inv_h2;  // -y / h^3
            *d_m_d_point << z * inv_h2, Scalar(0), -x * inv_h2,  //
                x * height_across, Scalar(1) / h, z * height_across;
        }
        return (h2 >= smallest_normal<Scalar>()) & all_finite(m);  // (near) the Y axis: no image
    }

    static bool unproject(const Parameters&, const Vec2T& m, Vec3T& ray) {
        using std::abs;
        using std::cos;
        using std::sin;
        const Scalar lon = m.x();
        ray = Vec3T(sin(lon), m.y(), cos(lon));
        return (abs(lon) <= pi_in<Scalar>()) & all_finite(m);
    }
};

}  // namespace libcam
