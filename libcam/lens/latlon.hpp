#pragma once
// LATLON: mrcal's LENSMODEL_LATLON, the transverse equirectangular projection.
//
//   m = (latitude, longitude) = (asin(X / |p|), atan2(Y, Z))
//
// (mrcal: q = f m + c). This is LONLAT with X and Y exchanged, in the point and in m:
// latlon(X, Y, Z) = swap(lonlat(Y, X, Z)), so it is evaluated by LonlatLens, one
// implementation of the formula. unproject: (sin(lat), cos(lat) sin(lon), cos(lat) cos(lon)).
//
// Valid domain: every point off the X axis (|(Y, Z)| > 0); a pixel has a ray only for
// |lat| <= pi/2 and |lon| <= pi.

#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/lonlat.hpp"
#include "libcam/lens/model_support.hpp"

namespace libcam {

template <class Scalar>
struct LatlonLens {
    static constexpr LensType type = LensType::Latlon;
    static constexpr int num_coefficients = 0;
    template <class Other>
    using InScalar = LatlonLens<Other>;
    using Parameters = LensParameters<Scalar, 0>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian23 = Eigen::Matrix<Scalar, 2, 3>;

    static Parameters parameters(std::span<const double>) { return {}; }

    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr = nullptr) {
        Vec2T swapped_m;
        Jacobian23 swapped_jacobian;
        if (!LonlatLens<Scalar>::project(lens, swap_xy(point), swapped_m, pass_request<PointJacobianPtr>(&swapped_jacobian))) {
            return false;
        }
        m = Vec2T(swapped_m.y(), swapped_m.x());
        if constexpr (is_requested<PointJacobianPtr>) {
            // Rows (outputs) and the first two columns (inputs) both exchanged.
            *d_m_d_point << swapped_jacobian(1, 1), swapped_jacobian(1, 0), swapped_jacobian(1, 2),  //
                swapped_jacobian(0, 1), swapped_jacobian(0, 0), swapped_jacobian(0, 2);
        }
        return true;
    }

    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        Vec3T swapped_ray;
        if (!LonlatLens<Scalar>::unproject(lens, Vec2T(m.y(), m.x()), swapped_ray)) return false;
        ray = swap_xy(swapped_ray);
        return true;
    }

private:
    static Vec3T swap_xy(const Vec3T& v) { return Vec3T(v.y(), v.x(), v.z()); }
};

}  // namespace libcam
