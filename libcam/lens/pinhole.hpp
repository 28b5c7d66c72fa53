#pragma once
// PINHOLE: the ideal perspective lens, no distortion.
//
//   project:   (x, y, z) -> m = (x/z, y/z)
//   unproject: m -> ray (mx, my, 1)
//
// Valid domain: z > 0. A point on or behind the camera plane has no image (OpenCV's
// projectPoints mirrors it into the image instead; libcam flags it).

#include <Eigen/Core>
#include <cstddef>
#include <type_traits>

#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/undistort.hpp"

namespace libcam {

template <class Scalar>
struct PinholeLens {
    static constexpr LensType type = LensType::Pinhole;
    static constexpr int num_coefficients = 0;
    template <class Other>
    using InScalar = PinholeLens<Other>;
    // Starts from x / z and y / z: scaling the point changes nothing, not even rounding.
    static constexpr bool projects_ratios = true;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian23 = Eigen::Matrix<Scalar, 2, 3>;

    // Returns false for z <= 0 and where x/z or y/z overflows (m then meaningless). When
    // d_m_d_point is a Jacobian23 pointer it receives dm/d(x, y, z); passing nothing
    // costs nothing. Computed without branches (the flag is returned, not acted on) so
    // that a loop over many points vectorises; the same holds for every model's
    // distort(). m is x / z, not x * (1 / z): 1 / z overflows for a subnormal z (and
    // (0, 0, 5e-324) would give 0 * inf = NaN) where x / z is exact.
    template <class JacobianPtr = std::nullptr_t>
    static bool project(const Vec3T& point, Vec2T& m, JacobianPtr d_m_d_point = nullptr) {
        const bool in_front = point.z() > Scalar(0);
        m = Vec2T(point.x() / point.z(), point.y() / point.z());
        if constexpr (!std::is_same_v<JacobianPtr, std::nullptr_t>) {
            const Scalar inv_z = Scalar(1) / point.z();
            *d_m_d_point << inv_z, Scalar(0), -m.x() * inv_z,  //
                Scalar(0), inv_z, -m.y() * inv_z;
        }
        return in_front & all_finite(m);  // &, not &&: no branch
    }

    // Every finite normalised point has a ray; its z is 1.
    static bool unproject(const Vec2T& m, Vec3T& ray) {
        ray = Vec3T(m.x(), m.y(), Scalar(1));
        return all_finite(m);
    }

    // The interface every model shares (see lens_models.hpp); PINHOLE has no
    // coefficients and no bound beyond z > 0.
    using Parameters = LensParameters<Scalar, 0>;
    static Parameters parameters(std::span<const double>) { return {}; }
    template <class JacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters&, const Vec3T& point, Vec2T& m, JacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr = nullptr) {
        return project(point, m, d_m_d_point);
    }
    static bool unproject(const Parameters&, const Vec2T& m, Vec3T& ray) { return unproject(m, ray); }
};

// What a model that distorts the pinhole point u = (X/Z, Y/Z) shares (OpenCV's models,
// CAHVOR): project through PINHOLE then Model::distort, unproject by the shared
// iterative solver, and the ray (u, 1). The model derives from OnPinholePoint<Model,
// Scalar> and writes distort and radial_distortion.
template <class Model, class Scalar>
struct OnPinholePoint {
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    static constexpr bool projects_ratios = true;  // through PinholeLens::project: x / z, y / z

    // m for a camera point; false outside the valid domain (m then meaningless). Jacobians
    // dm/d(X, Y, Z) and dm/d(coefficients) on request.
    template <class Parameters, class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        Vec2T u;
        Eigen::Matrix<Scalar, 2, 3> d_u_d_point;
        const bool in_front = PinholeLens<Scalar>::project(point, u, pass_request<PointJacobianPtr>(&d_u_d_point));
        Eigen::Matrix<Scalar, 2, 2> d_m_d_u;
        const bool in_domain = Model::distort(lens, u, m, pass_request<PointJacobianPtr>(&d_m_d_u), d_m_d_coefficients);
        if constexpr (is_requested<PointJacobianPtr>) *d_m_d_point = d_m_d_u * d_u_d_point;
        // Also false where m overflows (the thin prism's r^4 past r ~ 1e77).
        return in_front & in_domain & all_finite(m);  // &, not &&: no branch
    }

    // The ray (x, y, 1) through m, by the shared iterative solver; false where no
    // accurate solution lies inside the valid domain.
    template <class Parameters>
    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        return unproject_solved<Model>(lens, m, ray);
    }

    // The ray through the undistorted point u: (x, y, 1).
    template <class Parameters>
    static Vec3T ray_from_undistorted(const Parameters&, const Vec2T& u) {
        return Vec3T(u.x(), u.y(), Scalar(1));
    }
};

}  // namespace libcam
