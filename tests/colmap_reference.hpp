#pragma once
// COLMAP's camera models as COLMAP evaluates them (ImgFromCam in COLMAP's
// src/colmap/sensor/models.h, written out again here model by model, in its own order
// of operations and in long double), for points in front of the camera. COLMAP's pixel
// centres are at +0.5: the result is in COLMAP's pixels. The tests' independent
// reference for libcam's COLMAP conversion and its COLMAP models.

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace libcam::test {

using Real = long double;

namespace colmap_detail {

// FisheyeFromNormal: the equidistant point of (u, v) = (X/Z, Y/Z).
inline void fisheye_from_normal(Real u, Real v, Real& uu, Real& vv) {
    uu = u;
    vv = v;
    const Real r = std::sqrt(u * u + v * v);
    if (r > Real(2.220446049250313e-16)) {
        const Real theta = std::atan(r);
        uu *= theta / r;
        vv *= theta / r;
    }
}

// OpenCVFisheye's Distortion: du = u (k1 t2 + k2 t4 + k3 t6 + k4 t8), t2 = uu^2 + vv^2.
inline void kb4_distortion(const Real* k, Real u, Real v, Real& du, Real& dv) {
    const Real theta2 = u * u + v * v, theta4 = theta2 * theta2, theta6 = theta4 * theta2, theta8 = theta4 * theta4;
    const Real radial = k[0] * theta2 + k[1] * theta4 + k[2] * theta6 + k[3] * theta8;
    du = u * radial;
    dv = v * radial;
}

inline void thin_prism_distortion(const Real* e, Real u, Real v, Real& du, Real& dv) {
    const Real k1 = e[0], k2 = e[1], p1 = e[2], p2 = e[3], k3 = e[4], k4 = e[5], sx1 = e[6], sy1 = e[7];
    const Real u2 = u * u, uv = u * v, v2 = v * v, r2 = u2 + v2, r4 = r2 * r2, r6 = r4 * r2, r8 = r6 * r2;
    const Real radial = k1 * r2 + k2 * r4 + k3 * r6 + k4 * r8;
    du = u * radial + 2 * p1 * uv + p2 * (r2 + 2 * u2) + sx1 * r2;
    dv = v * radial + 2 * p2 * uv + p1 * (r2 + 2 * v2) + sy1 * r2;
}

inline void rad_tan_thin_prism_distortion(const Real* e, Real u, Real v, Real& du, Real& dv) {
    const Real p0 = e[6], p1 = e[7], s0 = e[8], s1 = e[9], s2 = e[10], s3 = e[11];
    const Real theta2 = u * u + v * v;
    Real th_radial = 1, theta_power = 1;
    for (int i = 0; i < 6; ++i) {
        theta_power *= theta2;
        th_radial += e[i] * theta_power;
    }
    const Real x = th_radial * u, y = th_radial * v;
    const Real x2 = x * x, y2 = y * y, xy = x * y, r2 = x2 + y2, r4 = r2 * r2;
    const Real dx_tang = 2 * p1 * xy + p0 * (r2 + 2 * x2);
    const Real dy_tang = 2 * p0 * xy + p1 * (r2 + 2 * y2);
    du = x + dx_tang + s0 * r2 + s1 * r4 - u;
    dv = y + dy_tang + s2 * r2 + s3 * r4 - v;
}

// The distortion of the perspective models on (u, v) = (X/Z, Y/Z) (SIMPLE_RADIAL and
// RADIAL are OPENCV's with the missing terms zero, as COLMAP's code is).
inline void opencv_distortion(const Real* e, int count, Real u, Real v, Real& du, Real& dv) {
    const Real k1 = e[0], k2 = count > 1 ? e[1] : 0, p1 = count > 2 ? e[2] : 0, p2 = count > 3 ? e[3] : 0;
    const Real u2 = u * u, uv = u * v, v2 = v * v, r2 = u2 + v2;
    const Real radial = k1 * r2 + k2 * r2 * r2;
    du = u * radial + 2 * p1 * uv + p2 * (r2 + 2 * u2);
    dv = v * radial + 2 * p2 * uv + p1 * (r2 + 2 * v2);
}

inline void full_opencv_distortion(const Real* e, Real u, Real v, Real& du, Real& dv) {
    const Real k1 = e[0], k2 = e[1], p1 = e[2], p2 = e[3], k3 = e[4], k4 = e[5], k5 = e[6], k6 = e[7];
    const Real u2 = u * u, uv = u * v, v2 = v * v, r2 = u2 + v2, r4 = r2 * r2, r6 = r4 * r2;
    const Real radial = (1 + k1 * r2 + k2 * r4 + k3 * r6) / (1 + k4 * r2 + k5 * r4 + k6 * r6);
    du = u * radial + 2 * p1 * uv + p2 * (r2 + 2 * u2) - u;
    dv = v * radial + 2 * p2 * uv + p1 * (r2 + 2 * v2) - v;
}

// FOV's "Distortion" returns the distorted point itself, not an increment. Its series
// branches are chosen as COLMAP chooses them, in double.
inline void fov_distortion(Real omega, Real u, Real v, Real& x, Real& y) {
    const Real radius2 = u * u + v * v, omega2 = omega * omega;
    const double epsilon = 1e-4, omega_d = static_cast<double>(omega);
    const double u_d = static_cast<double>(u), v_d = static_cast<double>(v);
    Real factor;
    if (omega_d * omega_d < epsilon) {
        factor = (omega2 * radius2) / 3 - omega2 / 12 + 1;
    } else if (u_d * u_d + v_d * v_d < epsilon) {
        const Real tan_half_omega = std::tan(omega / 2);
        factor = (-2 * tan_half_omega * (4 * radius2 * tan_half_omega * tan_half_omega - 3)) / (3 * omega);
    } else {
        const Real radius = std::sqrt(radius2);
        factor = std::atan(radius * 2 * std::tan(omega / 2)) / (radius * omega);
    }
    x = u * factor;
    y = v * factor;
}

}  // namespace colmap_detail

// COLMAP's pixel of the camera point (X, Y, Z), Z > 0, for the model and parameters as
// COLMAP writes them; nullopt where COLMAP would refuse the point.
inline std::optional<Eigen::Vector2d> colmap_img_from_cam(std::string_view model, const std::vector<double>& params,
                                                          const Eigen::Vector3d& point) {
    using namespace colmap_detail;
    std::vector<Real> p(params.begin(), params.end());
    const Real u = point.x(), v = point.y(), w = point.z();
    if (!(w >= Real(2.220446049250313e-16))) return std::nullopt;
    const bool one_focal = model.starts_with("SIMPLE_") || model == "RADIAL" || model == "RADIAL_FISHEYE";
    const Real fx = p[0], fy = one_focal ? p[0] : p[1];
    const std::size_t c = one_focal ? 1 : 2;
    const Real cx = p[c], cy = p[c + 1];
    const Real* extra = p.data() + c + 2;
    const int extra_count = static_cast<int>(p.size() - c - 2);
    Real x = 0, y = 0;
    if (model == "SIMPLE_PINHOLE" || model == "PINHOLE") {
        x = u / w;
        y = v / w;
    } else if (model == "SIMPLE_RADIAL" || model == "RADIAL" || model == "OPENCV" || model == "FULL_OPENCV") {
        Real du, dv;
        if (model == "FULL_OPENCV") {
            full_opencv_distortion(extra, u / w, v / w, du, dv);
        } else {
            opencv_distortion(extra, extra_count, u / w, v / w, du, dv);
        }
        x = u / w + du;
        y = v / w + dv;
    } else if (model == "FOV") {
        fov_distortion(extra[0], u / w, v / w, x, y);
    } else if (model == "SIMPLE_DIVISION" || model == "DIVISION") {
        // The distorted point m with m / (1 + k |m|^2) = (u, v) / w: m = (u, v) / D,
        // D = (w + sqrt(w^2 - 4 k (u^2 + v^2))) / 2; none past the fold.
        const Real k = extra[0], discriminant = w * w - 4 * k * (u * u + v * v);
        if (!(discriminant > 0)) return std::nullopt;
        const Real d = (w + std::sqrt(discriminant)) / 2;
        x = u / d;
        y = v / d;
    } else if (model == "EUCM") {
        const Real alpha = extra[0], beta = extra[1];
        const Real rho = std::sqrt(beta * (u * u + v * v) + w * w);
        const Real den = alpha * rho + (1 - alpha) * w;
        x = u / den;
        y = v / den;
    } else {
        // The perspective fisheyes: the equidistant point, then the model's distortion.
        Real uu, vv, du = 0, dv = 0;
        fisheye_from_normal(u / w, v / w, uu, vv);
        const Real kb4[4] = {extra_count > 0 ? extra[0] : 0, extra_count > 1 ? extra[1] : 0,
                             extra_count > 2 ? extra[2] : 0, extra_count > 3 ? extra[3] : 0};
        if (model == "OPENCV_FISHEYE" || model == "SIMPLE_RADIAL_FISHEYE" || model == "RADIAL_FISHEYE") {
            kb4_distortion(kb4, uu, vv, du, dv);
        } else if (model == "THIN_PRISM_FISHEYE") {
            thin_prism_distortion(extra, uu, vv, du, dv);
        } else if (model == "RAD_TAN_THIN_PRISM_FISHEYE") {
            rad_tan_thin_prism_distortion(extra, uu, vv, du, dv);
        } else if (model != "SIMPLE_FISHEYE" && model != "FISHEYE") {
            throw std::invalid_argument("colmap_img_from_cam: no reference for " + std::string(model));
        }
        x = uu + du;
        y = vv + dv;
    }
    return Eigen::Vector2d(static_cast<double>(fx * x + cx), static_cast<double>(fy * y + cy));
}

}  // namespace libcam::test
