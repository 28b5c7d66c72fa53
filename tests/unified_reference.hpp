#pragma once
// The unified family as its papers write it, transcribed here apart from libcam's
// lens/*.hpp and evaluated in long double (64-bit significand, 11 bits more than
// double): the expected values of the tests, independent of the code under test.
// - Double Sphere: Usenko, Demmel and Cremers, "The Double Sphere Camera Model", 3DV
//   2018, equations 40-47.
// - UCM: Mei and Rives, ICRA 2007 (the projection and its closed-form inverse).
// - EUCM: Khomutenko, Garcia and Martinet, RA-L 2016 (the projection); its inverse
//   solved here from the ellipsoid's equation, not with the paper's closed form.
// - FOV: Devernay and Faugeras, "Straight lines have to be straight", MVA 2001, in
//   basalt's form that goes on behind the camera; its inverse through the undistorted angle.
// - CYLINDRICAL: as OpenCV's stitching module writes it (cv::detail::CylindricalProjector:
//   u = atan2(x, z), v = y / sqrt(x^2 + z^2); back: (sin u, v, cos u)).
// - FTHETA: NVIDIA's F-theta as NCore's FThetaCameraModelParameters, gsplat's and 3DGUT's
//   FThetaCameraModel define it (the backward polynomial the reference; its projection
//   solved by bisection here); FTHETA_FORWARD, its forward polynomial the reference.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

#include "libcam/camera/camera.hpp"

namespace libcam::test {

using Long = long double;

// K (x, y) / denominator, the last step of every model here, rounded to double once.
inline Vec2 pixel_of(const Camera& camera, Long x, Long y, Long denominator) {
    const Intrinsics& k = camera.intrinsics;
    return Vec2(static_cast<double>(k.fx * x / denominator + k.cx), static_cast<double>(k.fy * y / denominator + k.cy));
}

// Equations 40-42: the pixel of a camera-frame point; nothing outside the domain, taken
// as the geometry the paper describes: the point carried onto the second sphere must be
// in front of the tangent cone of the pinhole alpha / (1 - alpha) behind that sphere's
// centre (z2 > -w1; equation 43's closed form for it is narrower, see
// lens/double_sphere.hpp).
inline std::optional<Vec2> double_sphere_paper_pixel(const Camera& camera, const Vec3& point) {
    const Long xi = camera.lens.coefficients.at(0), alpha = camera.lens.coefficients.at(1);
    const Long x = point.x(), y = point.y(), z = point.z();
    const Long d1 = std::sqrt(x * x + y * y + z * z);
    const Long d2 = std::sqrt(x * x + y * y + (xi * d1 + z) * (xi * d1 + z));
    const Long w1 = alpha <= Long(0.5) ? alpha / (1 - alpha) : (1 - alpha) / alpha;
    if (!((xi * d1 + z) / d2 > -w1)) return std::nullopt;
    const Long denominator = alpha * d2 + (1 - alpha) * (xi * d1 + z);
    return pixel_of(camera, x, y, denominator);
}

// Equations 45-47: the unit ray of a pixel, or nothing where it has none.
inline std::optional<Vec3> double_sphere_paper_ray(const Camera& camera, const Vec2& pixel) {
    const Long xi = camera.lens.coefficients.at(0), alpha = camera.lens.coefficients.at(1);
    const Intrinsics& k = camera.intrinsics;
    const Long mx = (Long(pixel.x()) - k.cx) / k.fx, my = (Long(pixel.y()) - k.cy) / k.fy;
    const Long r2 = mx * mx + my * my;
    if (alpha > Long(0.5) && !(r2 <= 1 / (2 * alpha - 1))) return std::nullopt;
    const Long mz = (1 - alpha * alpha * r2) / (alpha * std::sqrt(1 - (2 * alpha - 1) * r2) + 1 - alpha);
    const Long scale = (mz * xi + std::sqrt(mz * mz + (1 - xi * xi) * r2)) / (mz * mz + r2);
    return Vec3(static_cast<double>(scale * mx), static_cast<double>(scale * my), static_cast<double>(scale * mz - xi));
}

// UCM: m = (x, y) / (z + xi |p|), for z / |p| > -w (w = xi up to 1, then 1 / xi: the
// pinhole's tangent cone to the sphere).
inline std::optional<Vec2> ucm_paper_pixel(const Camera& camera, const Vec3& point) {
    const Long xi = camera.lens.coefficients.at(0);
    const Long x = point.x(), y = point.y(), z = point.z();
    const Long d = std::sqrt(x * x + y * y + z * z);
    const Long w = xi <= 1 ? xi : 1 / xi;
    if (!(z > -w * d)) return std::nullopt;
    return pixel_of(camera, x, y, z + xi * d);
}

// UCM's inverse (Mei and Rives): the unit ray, or nothing past the rim when xi > 1.
inline std::optional<Vec3> ucm_paper_ray(const Camera& camera, const Vec2& pixel) {
    const Long xi = camera.lens.coefficients.at(0);
    const Intrinsics& k = camera.intrinsics;
    const Long mx = (Long(pixel.x()) - k.cx) / k.fx, my = (Long(pixel.y()) - k.cy) / k.fy;
    const Long r2 = mx * mx + my * my;
    if (xi > 1 && !(r2 < 1 / (xi * xi - 1))) return std::nullopt;
    const Long s = (xi + std::sqrt(1 + (1 - xi * xi) * r2)) / (1 + r2);
    return Vec3(static_cast<double>(s * mx), static_cast<double>(s * my), static_cast<double>(s - xi));
}

// EUCM: m = (x, y) / (alpha d + (1 - alpha) z), d = sqrt(beta (x^2 + y^2) + z^2), for
// z / d > -w (w = alpha / (1 - alpha) up to alpha = 1/2, then (1 - alpha) / alpha).
inline std::optional<Vec2> eucm_paper_pixel(const Camera& camera, const Vec3& point) {
    const Long alpha = camera.lens.coefficients.at(0), beta = camera.lens.coefficients.at(1);
    const Long x = point.x(), y = point.y(), z = point.z();
    const Long d = std::sqrt(beta * (x * x + y * y) + z * z);
    const Long w = alpha <= Long(0.5) ? alpha / (1 - alpha) : (1 - alpha) / alpha;
    if (!(z > -w * d)) return std::nullopt;
    const Long denominator = alpha * d + (1 - alpha) * z;
    return pixel_of(camera, x, y, denominator);
}

// EUCM's inverse, from the geometry (alpha < 1): the ray meets the ellipsoid
// beta (X^2 + Y^2) + Z^2 = 1 at P = (mx s, my s, Z) with s = alpha + (1 - alpha) Z, so
// (1 + beta r^2 (1 - alpha)^2) s^2 - 2 alpha s + (2 alpha - 1) = 0; the larger root is
// the side the pinhole sees. Nothing where there is no root, or on or past the rim.
inline std::optional<Vec3> eucm_paper_ray(const Camera& camera, const Vec2& pixel) {
    const Long alpha = camera.lens.coefficients.at(0), beta = camera.lens.coefficients.at(1);
    const Intrinsics& k = camera.intrinsics;
    const Long mx = (Long(pixel.x()) - k.cx) / k.fx, my = (Long(pixel.y()) - k.cy) / k.fy;
    const Long r2 = mx * mx + my * my;
    if (alpha > Long(0.5) && !(r2 < 1 / ((2 * alpha - 1) * beta))) return std::nullopt;
    const Long a = 1 + beta * r2 * (1 - alpha) * (1 - alpha);
    const Long discriminant = alpha * alpha - a * (2 * alpha - 1);
    if (!(discriminant >= 0)) return std::nullopt;
    const Long s = (alpha + std::sqrt(discriminant)) / a;
    const Long X = mx * s, Y = my * s, Z = (s - alpha) / (1 - alpha);
    const Long norm = std::sqrt(X * X + Y * Y + Z * Z);
    return Vec3(static_cast<double>(X / norm), static_cast<double>(Y / norm), static_cast<double>(Z / norm));
}

// FOV (Devernay and Faugeras 2001): r_d = atan(2 tan(omega / 2) r) / omega, with basalt's
// atan2(2 tan(omega / 2) |(x, y)|, z) for atan(2 tan(omega / 2) r), which goes on behind
// the camera; nothing on the backward axis (or at the origin).
inline std::optional<Vec2> fov_paper_pixel(const Camera& camera, const Vec3& point) {
    const Long omega = camera.lens.coefficients.at(0), a = 2 * std::tan(omega / 2);
    const Long x = point.x(), y = point.y(), z = point.z();
    const Long rho = std::hypot(x, y);
    if (rho == 0) {
        if (!(z > 0)) return std::nullopt;
        return pixel_of(camera, 0, 0, 1);
    }
    const Long distorted = std::atan2(a * rho, z) / omega;
    return pixel_of(camera, x * distorted, y * distorted, rho);
}

// The inverse, by the undistorted angle: tan(theta) = tan(omega r_d) / (2 tan(omega / 2));
// nothing where omega r_d reaches pi.
inline std::optional<Vec3> fov_paper_ray(const Camera& camera, const Vec2& pixel) {
    const Long omega = camera.lens.coefficients.at(0), a = 2 * std::tan(omega / 2);
    const Intrinsics& k = camera.intrinsics;
    const Long mx = (Long(pixel.x()) - k.cx) / k.fx, my = (Long(pixel.y()) - k.cy) / k.fy;
    const Long distorted = std::hypot(mx, my), phi = omega * distorted;
    if (!(phi < std::numbers::pi_v<Long>)) return std::nullopt;
    if (distorted == 0) return Vec3(0, 0, 1);
    const Long theta = std::atan2(std::sin(phi), a * std::cos(phi));
    return Vec3(static_cast<double>(std::sin(theta) * mx / distorted), static_cast<double>(std::sin(theta) * my / distorted),
                static_cast<double>(std::cos(theta)));
}

// EQUISOLID: r = 2 sin(theta / 2), theta = atan2(rho, z), in the angle itself.
inline std::optional<Vec2> equisolid_paper_pixel(const Camera& camera, const Vec3& point) {
    const Long x = point.x(), y = point.y(), z = point.z(), rho = std::hypot(x, y);
    if (rho == 0) {
        if (!(z > 0)) return std::nullopt;
        return pixel_of(camera, 0, 0, 1);
    }
    const Long distorted = 2 * std::sin(std::atan2(rho, z) / 2);
    return pixel_of(camera, x * distorted, y * distorted, rho);
}

// theta = 2 asin(r / 2); nothing outside the image disc r < 2.
inline std::optional<Vec3> equisolid_paper_ray(const Camera& camera, const Vec2& pixel) {
    const Intrinsics& k = camera.intrinsics;
    const Long mx = (Long(pixel.x()) - k.cx) / k.fx, my = (Long(pixel.y()) - k.cy) / k.fy;
    const Long distorted = std::hypot(mx, my);
    if (!(distorted < 2)) return std::nullopt;
    if (distorted == 0) return Vec3(0, 0, 1);
    const Long theta = 2 * std::asin(distorted / 2);
    return Vec3(static_cast<double>(std::sin(theta) * mx / distorted), static_cast<double>(std::sin(theta) * my / distorted),
                static_cast<double>(std::cos(theta)));
}

// Blender's FISHEYE_LENS_POLYNOMIAL (Cycles' fisheye_lens_polynomial_to_direction):
// theta(r) = -(k0 + k1 r + ... + k4 r^4), the ray (sin(theta) m / r, cos(theta)).
inline Long lens_polynomial_theta(const Camera& camera, Long r) {
    const std::vector<double>& k = camera.lens.coefficients;
    return -(Long(k[0]) + r * (Long(k[1]) + r * (Long(k[2]) + r * (Long(k[3]) + r * Long(k[4])))));
}

// Nothing past where theta stops being monotonic, reaches pi, or has the sign opposite to
// its slope at the centre; and nothing at the centre unless k0 = 0.
inline std::optional<Vec3> lens_polynomial_paper_ray(const Camera& camera, const Vec2& pixel) {
    const Intrinsics& k = camera.intrinsics;
    const Long mx = (Long(pixel.x()) - k.cx) / k.fx, my = (Long(pixel.y()) - k.cy) / k.fy;
    const Long r = std::hypot(mx, my);
    const Long sigma = camera.lens.coefficients[1] < 0 ? 1 : -1;
    if (r == 0) {
        if (camera.lens.coefficients[0] != 0) return std::nullopt;
        return Vec3(0, 0, 1);
    }
    // One-to-one up to r: theta' keeps sigma's sign on [0, r] (checked on a fine grid).
    constexpr int kSteps = 2000;
    for (int i = 1; i <= kSteps; ++i) {
        const Long a = r * (i - 1) / kSteps, b = r * i / kSteps;
        if (!(sigma * (lens_polynomial_theta(camera, b) - lens_polynomial_theta(camera, a)) > 0)) return std::nullopt;
    }
    const Long theta = lens_polynomial_theta(camera, r);
    if (!(sigma * theta > 0) || !(std::abs(theta) < std::numbers::pi_v<Long>)) return std::nullopt;
    return Vec3(static_cast<double>(std::sin(theta) * mx / r), static_cast<double>(std::sin(theta) * my / r),
                static_cast<double>(std::cos(theta)));
}

// Projection: theta(r) = sigma times the point's angle, solved by bisection in long
// double over the radii where the ray above exists.
inline std::optional<Vec2> lens_polynomial_paper_pixel(const Camera& camera, const Vec3& point) {
    const Long x = point.x(), y = point.y(), z = point.z(), rho = std::hypot(x, y);
    if (rho == 0) {
        if (!(z > 0) || camera.lens.coefficients[0] != 0) return std::nullopt;
        return pixel_of(camera, 0, 0, 1);
    }
    const Long target = std::atan2(rho, z);
    const Long sigma = camera.lens.coefficients[1] < 0 ? 1 : -1;
    // The end of the one-to-one range: step out until theta turns or reaches pi.
    Long high = 0, step = 1e-3;
    while (true) {
        const Long next = high + step;
        if (!(sigma * (lens_polynomial_theta(camera, next) - lens_polynomial_theta(camera, high)) > 0) ||
            !(std::abs(lens_polynomial_theta(camera, next)) < std::numbers::pi_v<Long>)) {
            if (step < 1e-12) break;
            step /= 2;
            continue;
        }
        high = next;
        step *= 2;
    }
    if (!(sigma * lens_polynomial_theta(camera, high) > target) || !(sigma * lens_polynomial_theta(camera, 0) < target)) {
        return std::nullopt;
    }
    Long low = 0;
    for (int i = 0; i < 200; ++i) {
        const Long middle = (low + high) / 2;
        (sigma * lens_polynomial_theta(camera, middle) < target ? low : high) = middle;
    }
    const Long r = (low + high) / 2;
    return pixel_of(camera, sigma * x * r, sigma * y * r, rho);
}

// ---- THETA_POLYNOMIAL: WoodScape's calibration_readme.txt (rho = k1 theta + ... + k4
// theta^4, the point at rho (X, Y) / |(X, Y)|); its inverse as its projection.py does it,
// the smallest positive root of rho(theta) = r below pi, found here by bisection over the
// angles where rho still grows (checked on a fine grid).
inline Long theta_polynomial_rho(const Camera& camera, Long theta) {
    const std::vector<double>& k = camera.lens.coefficients;
    return theta * (Long(k[0]) + theta * (Long(k[1]) + theta * (Long(k[2]) + theta * Long(k[3]))));
}

inline Long theta_polynomial_slope(const Camera& camera, Long theta) {
    const std::vector<double>& k = camera.lens.coefficients;
    return Long(k[0]) + theta * (2 * Long(k[1]) + theta * (3 * Long(k[2]) + theta * 4 * Long(k[3])));
}

// The end of rho's growing range, at most pi: the first sign change of rho' on a grid,
// then bisected.
inline Long theta_polynomial_growing_end(const Camera& camera) {
    constexpr int kSteps = 20000;
    const Long pi = std::numbers::pi_v<Long>;
    for (int i = 1; i <= kSteps; ++i) {
        Long low = pi * (i - 1) / kSteps, high = pi * i / kSteps;
        if (theta_polynomial_slope(camera, high) > 0) continue;
        for (int j = 0; j < 100; ++j) {
            const Long middle = (low + high) / 2;
            (theta_polynomial_slope(camera, middle) > 0 ? low : high) = middle;
        }
        return low;
    }
    return pi;
}

inline std::optional<Vec2> theta_polynomial_paper_pixel(const Camera& camera, const Vec3& point) {
    const Long x = point.x(), y = point.y(), z = point.z(), chi = std::hypot(x, y);
    if (chi == 0) {
        if (!(z > 0)) return std::nullopt;
        return pixel_of(camera, 0, 0, 1);
    }
    const Long theta = std::atan2(chi, z);
    if (!(theta < theta_polynomial_growing_end(camera))) return std::nullopt;
    return pixel_of(camera, theta_polynomial_rho(camera, theta) * x, theta_polynomial_rho(camera, theta) * y, chi);
}

inline std::optional<Vec3> theta_polynomial_paper_ray(const Camera& camera, const Vec2& pixel) {
    const Intrinsics& k = camera.intrinsics;
    const Long mx = (Long(pixel.x()) - k.cx) / k.fx, my = (Long(pixel.y()) - k.cy) / k.fy;
    const Long r = std::hypot(mx, my);
    if (r == 0) return Vec3(0, 0, 1);
    Long low = 0, high = theta_polynomial_growing_end(camera);
    if (!(theta_polynomial_rho(camera, high) > r)) return std::nullopt;
    for (int i = 0; i < 200; ++i) {
        const Long middle = (low + high) / 2;
        (theta_polynomial_rho(camera, middle) < r ? low : high) = middle;
    }
    const Long theta = (low + high) / 2;
    return Vec3(static_cast<double>(std::sin(theta) * mx / r), static_cast<double>(std::sin(theta) * my / r),
                static_cast<double>(std::cos(theta)));
}

// ---- FTHETA: NVIDIA's F-theta as NCore, gsplat and 3DGUT publish it (the sensor point
// n = A^-1 m, A = [c d; e 1]; the angle theta(r) = k1 r + ... + k5 r^5 at r = |n|; the ray
// (sin(theta) n / r, cos(theta))), with its domain: the radii below the first where theta
// stops growing or reaches max_angle (or pi), found by a scan and bisection; the pixel of
// a point by bisection over that range, in long double.
inline Long ftheta_theta(const Camera& camera, Long r) {
    const std::vector<double>& k = camera.lens.coefficients;
    return r * (Long(k[3]) + r * (Long(k[4]) + r * (Long(k[5]) + r * (Long(k[6]) + r * Long(k[7])))));
}

inline Long ftheta_slope(const Camera& camera, Long r) {
    const std::vector<double>& k = camera.lens.coefficients;
    return Long(k[3]) + r * (2 * Long(k[4]) + r * (3 * Long(k[5]) + r * (4 * Long(k[6]) + r * 5 * Long(k[7]))));
}

// A value worked out once per lens (a domain's end, by a scan of thousands of steps), kept
// for the next call with the same coefficients: the tests ask for it once per point.
template <class Compute>
Long once_per_lens(const Camera& camera, Compute&& compute) {
    thread_local std::vector<double> last_coefficients;
    thread_local Long last_value = 0;
    if (camera.lens.coefficients != last_coefficients) {
        last_value = compute();
        last_coefficients = camera.lens.coefficients;
    }
    return last_value;
}

// Where the domain ends: the first r where theta' <= 0 or theta >= min(max_angle, pi).
inline Long ftheta_domain_end_scanned(const Camera& camera) {
    const Long limit = std::min(Long(camera.lens.coefficients[8]), std::numbers::pi_v<Long>);
    const auto outside = [&](Long r) { return ftheta_slope(camera, r) <= 0 || ftheta_theta(camera, r) >= limit; };
    constexpr int kSteps = 4000;
    const Long step = limit / Long(camera.lens.coefficients[3]) / 1000;
    for (int i = 1; i <= kSteps; ++i) {
        Long low = step * (i - 1), high = step * i;
        if (!outside(high)) continue;
        for (int j = 0; j < 100; ++j) {
            const Long middle = (low + high) / 2;
            (outside(middle) ? high : low) = middle;
        }
        return low;
    }
    return step * kSteps;
}

inline Long ftheta_domain_end(const Camera& camera) {
    return once_per_lens(camera, [&] { return ftheta_domain_end_scanned(camera); });
}

inline std::optional<Vec2> ftheta_paper_pixel(const Camera& camera, const Vec3& point) {
    const std::vector<double>& k = camera.lens.coefficients;
    const Long x = point.x(), y = point.y(), z = point.z(), rho = std::hypot(x, y);
    if (rho == 0) {
        if (!(z > 0)) return std::nullopt;
        return pixel_of(camera, 0, 0, 1);
    }
    const Long target = std::atan2(rho, z);
    Long low = 0, high = ftheta_domain_end(camera);
    if (!(target < ftheta_theta(camera, high))) return std::nullopt;
    for (int i = 0; i < 200; ++i) {
        const Long middle = (low + high) / 2;
        (ftheta_theta(camera, middle) < target ? low : high) = middle;
    }
    const Long r = (low + high) / 2, nx = r * x / rho, ny = r * y / rho;
    return pixel_of(camera, Long(k[0]) * nx + Long(k[1]) * ny, Long(k[2]) * nx + ny, 1);
}

inline std::optional<Vec3> ftheta_paper_ray(const Camera& camera, const Vec2& pixel) {
    const std::vector<double>& k = camera.lens.coefficients;
    const Intrinsics& K = camera.intrinsics;
    const Long mx = (Long(pixel.x()) - K.cx) / K.fx, my = (Long(pixel.y()) - K.cy) / K.fy;
    const Long determinant = Long(k[0]) - Long(k[1]) * Long(k[2]);
    const Long nx = (mx - Long(k[1]) * my) / determinant, ny = (Long(k[0]) * my - Long(k[2]) * mx) / determinant;
    const Long r = std::hypot(nx, ny);
    if (r == 0) return Vec3(0, 0, 1);
    if (!(r < ftheta_domain_end(camera))) return std::nullopt;
    const Long theta = ftheta_theta(camera, r);
    return Vec3(static_cast<double>(std::sin(theta) * nx / r), static_cast<double>(std::sin(theta) * ny / r),
                static_cast<double>(std::cos(theta)));
}

// ---- FTHETA_FORWARD: the same with the forward polynomial the reference (rho(theta) =
// k1 theta + ... + k5 theta^5, the sensor point q = rho (X, Y) / |(X, Y)|, m = A q); its
// inverse by bisection over the angles where rho still grows, below max_angle and pi.
inline Long ftheta_forward_rho(const Camera& camera, Long theta) {
    const std::vector<double>& k = camera.lens.coefficients;
    return theta * (Long(k[3]) + theta * (Long(k[4]) + theta * (Long(k[5]) + theta * (Long(k[6]) + theta * Long(k[7])))));
}

inline Long ftheta_forward_domain_end_scanned(const Camera& camera) {
    const std::vector<double>& k = camera.lens.coefficients;
    const Long limit = std::min(Long(k[8]), std::numbers::pi_v<Long>);
    const auto slope = [&](Long t) {
        return Long(k[3]) + t * (2 * Long(k[4]) + t * (3 * Long(k[5]) + t * (4 * Long(k[6]) + t * 5 * Long(k[7]))));
    };
    constexpr int kSteps = 4000;
    for (int i = 1; i <= kSteps; ++i) {
        Long low = limit * (i - 1) / kSteps, high = limit * i / kSteps;
        if (slope(high) > 0) continue;
        for (int j = 0; j < 100; ++j) {
            const Long middle = (low + high) / 2;
            (slope(middle) > 0 ? low : high) = middle;
        }
        return low;
    }
    return limit;
}

inline Long ftheta_forward_domain_end(const Camera& camera) {
    return once_per_lens(camera, [&] { return ftheta_forward_domain_end_scanned(camera); });
}

inline std::optional<Vec2> ftheta_forward_paper_pixel(const Camera& camera, const Vec3& point) {
    const std::vector<double>& k = camera.lens.coefficients;
    const Long x = point.x(), y = point.y(), z = point.z(), chi = std::hypot(x, y);
    if (chi == 0) {
        if (!(z > 0)) return std::nullopt;
        return pixel_of(camera, 0, 0, 1);
    }
    const Long theta = std::atan2(chi, z);
    if (!(theta < ftheta_forward_domain_end(camera))) return std::nullopt;
    const Long rho = ftheta_forward_rho(camera, theta), qx = rho * x / chi, qy = rho * y / chi;
    return pixel_of(camera, Long(k[0]) * qx + Long(k[1]) * qy, Long(k[2]) * qx + qy, 1);
}

inline std::optional<Vec3> ftheta_forward_paper_ray(const Camera& camera, const Vec2& pixel) {
    const std::vector<double>& k = camera.lens.coefficients;
    const Intrinsics& K = camera.intrinsics;
    const Long mx = (Long(pixel.x()) - K.cx) / K.fx, my = (Long(pixel.y()) - K.cy) / K.fy;
    const Long determinant = Long(k[0]) - Long(k[1]) * Long(k[2]);
    const Long qx = (mx - Long(k[1]) * my) / determinant, qy = (Long(k[0]) * my - Long(k[2]) * mx) / determinant;
    const Long r = std::hypot(qx, qy);
    if (r == 0) return Vec3(0, 0, 1);
    Long low = 0, high = ftheta_forward_domain_end(camera);
    if (!(ftheta_forward_rho(camera, high) > r)) return std::nullopt;
    for (int i = 0; i < 200; ++i) {
        const Long middle = (low + high) / 2;
        (ftheta_forward_rho(camera, middle) < r ? low : high) = middle;
    }
    const Long theta = (low + high) / 2;
    return Vec3(static_cast<double>(std::sin(theta) * qx / r), static_cast<double>(std::sin(theta) * qy / r),
                static_cast<double>(std::cos(theta)));
}

// The papers' formulas for any model of the family; nullopt for a model outside it
// (the outer optional), nothing for a point or pixel outside the domain (the inner).
// CYLINDRICAL: the longitude and the height on the unit cylinder about the Y axis;
// nothing on that axis.
inline std::optional<Vec2> cylindrical_paper_pixel(const Camera& camera, const Vec3& point) {
    const Long x = point.x(), y = point.y(), z = point.z(), across = std::hypot(x, z);
    if (!(across > 0)) return std::nullopt;
    const Long height = y / across;
    if (!std::isfinite(static_cast<double>(height))) return std::nullopt;
    return pixel_of(camera, std::atan2(x, z), height, 1);
}

// The unit ray (sin(lon), height, cos(lon)) / |.|; nothing past |lon| = pi.
inline std::optional<Vec3> cylindrical_paper_ray(const Camera& camera, const Vec2& pixel) {
    const Intrinsics& k = camera.intrinsics;
    const Long lon = (Long(pixel.x()) - k.cx) / k.fx, height = (Long(pixel.y()) - k.cy) / k.fy;
    if (!(std::abs(lon) <= std::numbers::pi_v<Long>)) return std::nullopt;
    const Long norm = std::hypot(Long(1), height);
    return Vec3(static_cast<double>(std::sin(lon) / norm), static_cast<double>(height / norm),
                static_cast<double>(std::cos(lon) / norm));
}

inline bool has_paper_formulas(LensType type) {
    return type == LensType::DoubleSphere || type == LensType::Ucm || type == LensType::Eucm || type == LensType::Fov ||
           type == LensType::Equisolid || type == LensType::LensPolynomial || type == LensType::Cylindrical ||
           type == LensType::ThetaPolynomial || type == LensType::FTheta ||
           type == LensType::FThetaForward;
}

inline std::optional<Vec2> paper_pixel(const Camera& camera, const Vec3& point) {
    switch (camera.lens.type) {
        case LensType::DoubleSphere: return double_sphere_paper_pixel(camera, point);
        case LensType::Ucm: return ucm_paper_pixel(camera, point);
        case LensType::Eucm: return eucm_paper_pixel(camera, point);
        case LensType::Fov: return fov_paper_pixel(camera, point);
        case LensType::Equisolid: return equisolid_paper_pixel(camera, point);
        case LensType::LensPolynomial: return lens_polynomial_paper_pixel(camera, point);
        case LensType::Cylindrical: return cylindrical_paper_pixel(camera, point);
        case LensType::ThetaPolynomial: return theta_polynomial_paper_pixel(camera, point);
        case LensType::FTheta: return ftheta_paper_pixel(camera, point);
        case LensType::FThetaForward: return ftheta_forward_paper_pixel(camera, point);
        default: throw std::logic_error("paper_pixel: not a model with a paper's formulas here");
    }
}

inline std::optional<Vec3> paper_ray(const Camera& camera, const Vec2& pixel) {
    switch (camera.lens.type) {
        case LensType::DoubleSphere: return double_sphere_paper_ray(camera, pixel);
        case LensType::Ucm: return ucm_paper_ray(camera, pixel);
        case LensType::Eucm: return eucm_paper_ray(camera, pixel);
        case LensType::Fov: return fov_paper_ray(camera, pixel);
        case LensType::Equisolid: return equisolid_paper_ray(camera, pixel);
        case LensType::LensPolynomial: return lens_polynomial_paper_ray(camera, pixel);
        case LensType::Cylindrical: return cylindrical_paper_ray(camera, pixel);
        case LensType::ThetaPolynomial: return theta_polynomial_paper_ray(camera, pixel);
        case LensType::FTheta: return ftheta_paper_ray(camera, pixel);
        case LensType::FThetaForward: return ftheta_forward_paper_ray(camera, pixel);
        default: throw std::logic_error("paper_ray: not a model with a paper's formulas here");
    }
}

}  // namespace libcam::test
