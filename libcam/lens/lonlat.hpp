#pragma once
// LONLAT: mrcal's LENSMODEL_LONLAT, the equirectangular projection.
//
//   m = (longitude, latitude) = (atan2(X, Z), asin(Y / |p|))
//
// (mrcal: q = f m + c). Latitude is evaluated as atan2(Y, |(X, Z)|), the same angle
// without asin's loss of accuracy near the poles.
// unproject: the unit ray (cos(lat) sin(lon), sin(lat), cos(lat) cos(lon)).
//
// Valid domain: every point off the Y axis (|(X, Z)| > 0; on it the longitude is
// undefined), so also behind the camera. A pixel has a ray only for |lon| <= pi and
// |lat| <= pi/2: outside, the ray would project back to another pixel.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <span>

#include "libcam/geometry/vector_math.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"

namespace libcam {

template <class Scalar>
struct LonlatLens {
    static constexpr LensType type = LensType::Lonlat;
    static constexpr int num_coefficients = 0;
    template <class Other>
    using InScalar = LonlatLens<Other>;
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
        if (!(h2 > Scalar(0))) return false;
        const Scalar h = sqrt(h2);
        m = Vec2T(atan2(x, z), atan2(y, h));
        if constexpr (is_requested<PointJacobianPtr>) {
            const Scalar inv_h2 = Scalar(1) / h2, inv_n2 = Scalar(1) / (h2 + y * y);
            const Scalar lat_across = -y * inv_n2 / h;  // d(lat)/dh / h
            *d_m_d_point << z * inv_h2, Scalar(0), -x * inv_h2,  //
                x * lat_across, h * inv_n2, z * lat_across;
        }
        return all_finite(m);  // false for a NaN coordinate
    }

    static bool unproject(const Parameters&, const Vec2T& m, Vec3T& ray) {
        using std::abs;
        using std::cos;
        using std::sin;
        const Scalar pi = pi_in<Scalar>();
        const Scalar lon = m.x(), lat = m.y();
        if (!(abs(lon) <= pi && abs(lat) <= pi / Scalar(2))) return false;
        const Scalar cos_lat = cos(lat);
        ray = Vec3T(cos_lat * sin(lon), sin(lat), cos_lat * cos(lon));
        return true;
    }
};

}  // namespace libcam
