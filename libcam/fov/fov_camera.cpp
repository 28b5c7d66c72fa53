#include "libcam/fov/fov_camera.hpp"

#include <string>

#include "libcam/error.hpp"

namespace libcam {

std::string_view to_string(FovAxis axis) {
    switch (axis) {
        case FovAxis::Horizontal: return "horizontal";
        case FovAxis::Vertical: return "vertical";
        case FovAxis::Diagonal: return "diagonal";
        case FovAxis::Both: return "both";
    }
    return "?";
}

std::string_view to_string(PixelOrigin origin) {
    return origin == PixelOrigin::BottomLeft ? "bottom-left" : "top-left";
}

FovAxis fov_axis_from_string(std::string_view text) {
    for (FovAxis axis : {FovAxis::Horizontal, FovAxis::Vertical, FovAxis::Diagonal, FovAxis::Both}) {
        if (text == to_string(axis)) return axis;
    }
    throw InvalidArgument("fov_axis: must be horizontal, vertical, diagonal or both, got '" +
                          std::string(text) + "'");
}

PixelOrigin pixel_origin_from_string(std::string_view text) {
    if (text == "bottom-left") return PixelOrigin::BottomLeft;
    if (text == "top-left") return PixelOrigin::TopLeft;
    throw InvalidArgument("pixel_origin: must be bottom-left or top-left, got '" + std::string(text) + "'");
}

Vec2 opencv_pixel(const Vec2& pixel, PixelOrigin origin, const ImageSize& size) {
    return origin == PixelOrigin::TopLeft ? pixel : Vec2(pixel.x(), flip_row(pixel.y(), size));
}

Vec2 user_pixel(const Vec2& opencv, PixelOrigin origin, const ImageSize& size) {
    return opencv_pixel(opencv, origin, size);  // the flip is its own inverse
}

FovCamera FovCamera::look_at(const Vec3& eye, const Vec3& target, const Vec3& up, double fov_deg,
                             FovAxis fov_axis, ImageSize size) {
    require_finite_all("eye", eye);
    require_finite_all("target", target);
    if (target == eye) {
        throw InvalidArgument("target: equals eye (" + format_number(eye.x()) + ", " + format_number(eye.y()) +
                              ", " + format_number(eye.z()) + "), so there is no gaze direction");
    }
    // When eye and target are close, target - eye is exact (Sterbenz), so no digits are lost here.
    const Vec3 gaze = target - eye;
    if (!gaze.allFinite()) {
        throw InvalidArgument("target: target - eye overflows (eye and target more than ~1.8e308 apart)");
    }
    return FovCamera{eye, gaze, up, fov_deg, fov_axis, size};
}

void FovCamera::validate() const {
    require_finite_all("eye", eye);
    require_finite_all("gaze", gaze);
    require_finite_all("up", up);
    require_finite("fov", fov_deg);
    if (!(fov_deg > 0.0 && fov_deg < 180.0)) {
        throw InvalidArgument("fov: must be in (0, 180) degrees, got " + format_number(fov_deg));
    }
    size.validate("size");
    if (gaze.isZero(0.0)) throw InvalidArgument("gaze: must not be the zero vector");
    if (up.isZero(0.0)) throw InvalidArgument("up: must not be the zero vector");
    const double angle = angle_between(gaze, up);
    if (angle < kMinUpGazeAngleRad || angle > std::numbers::pi - kMinUpGazeAngleRad) {
        throw InvalidArgument("up: parallel to the gaze (angle " + format_number(angle) +
                              " rad from the gaze line, minimum " + format_number(kMinUpGazeAngleRad) +
                              " rad), so the camera's roll is undefined");
    }
}

Basis FovCamera::basis(Handedness handedness) const {
    // u = gaze x up for both handednesses (the seed's w x up with w along the gaze,
    // or up x w with w against it). The accurate cross product of the raw inputs keeps
    // u right to a few ulps even when up is within a small angle of the gaze.
    const Vec3 gaze_scaled = scaled_to_unit_range(gaze);
    const Vec3 u = accurate_cross(gaze_scaled, scaled_to_unit_range(up)).normalized();
    const Vec3 along_gaze = gaze_scaled.normalized();
    const Vec3 v = accurate_cross(u, along_gaze);
    return {u, v, handedness == Handedness::Left ? along_gaze : Vec3(-along_gaze), handedness};
}

// Both conversions work in long double (64-bit significand) and round once at the
// end, so exact cases stay exact (tan 45 deg = 1) and the degree-to-radian factor adds
// no error of its own.
namespace {
constexpr long double kRadiansPerDegree = 3.141592653589793238462643383279502884L / 180.0L;
}

double tan_half_angle_deg(double angle_deg) {
    const long double half = 0.5L * static_cast<long double>(angle_deg);
    // Near 180 degrees, tan(angle/2) = 1 / tan(90 - angle/2), and 90 - angle/2 is exact,
    // so the small complement keeps its digits.
    if (half > 45.0L) return static_cast<double>(1.0L / std::tan((90.0L - half) * kRadiansPerDegree));
    return static_cast<double>(std::tan(half * kRadiansPerDegree));
}

double angle_deg_from_half_tangent(double tangent) {
    const long double t = tangent;
    if (t > 1.0L) return static_cast<double>(180.0L - 2.0L * std::atan(1.0L / t) / kRadiansPerDegree);
    return static_cast<double>(2.0L * std::atan(t) / kRadiansPerDegree);
}

Vec2 FovCamera::half_tangents() const {
    const double tangent = tan_half_angle_deg(fov_deg);
    const double width = static_cast<double>(size.width);
    const double height = static_cast<double>(size.height);
    switch (fov_axis) {
        case FovAxis::Both: return {tangent, tangent};
        case FovAxis::Horizontal: return {tangent, tangent * height / width};
        case FovAxis::Vertical: return {tangent * width / height, tangent};
        case FovAxis::Diagonal: {
            const double diagonal = std::hypot(width, height);
            return {tangent * (width / diagonal), tangent * (height / diagonal)};
        }
    }
    return {tangent, tangent};
}

}  // namespace libcam
