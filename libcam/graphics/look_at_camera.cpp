#include "libcam/graphics/look_at_camera.hpp"

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

FovAxis fov_axis_from_string(std::string_view text) {
    for (FovAxis axis : {FovAxis::Horizontal, FovAxis::Vertical, FovAxis::Diagonal, FovAxis::Both}) {
        if (text == to_string(axis)) return axis;
    }
    throw InvalidArgument("fov_axis: must be horizontal, vertical, diagonal or both, got '" +
                          std::string(text) + "'");
}

LookAtCamera LookAtCamera::look_at(const Vec3& eye, const Vec3& target, const Vec3& up, double fov_deg,
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
    return LookAtCamera{eye, gaze, up, fov_deg, fov_axis, size};
}

void LookAtCamera::validate() const {
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

Basis LookAtCamera::basis(Handedness handedness) const {
    validate();
    return basis_from_gaze_up<double>(gaze, up, handedness);
}

Vec2 LookAtCamera::half_tangents() const {
    validate();
    return half_tangents_of_fov<double>(fov_deg, fov_axis, size);
}

}  // namespace libcam
