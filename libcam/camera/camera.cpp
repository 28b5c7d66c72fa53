#include "libcam/camera/camera.hpp"

#include "libcam/lens/pinhole.hpp"

namespace libcam {

void Camera::validate() const {
    size.validate("image_size");
    intrinsics.validate("K");
    lens.validate("dist");
    pose.validate("R");
}

Projection Camera::project_camera_point(const Vec3& camera_point) const {
    Projection result;
    Vec2 normalized;
    switch (lens.type) {
        case LensType::Pinhole: result.valid = PinholeLens<double>::project(camera_point, normalized); break;
    }
    if (result.valid) result.pixel = intrinsics.pixel_from_normalized(normalized);
    return result;
}

bool Camera::unproject(const Vec2& pixel, Vec3& camera_direction) const {
    const Vec2 normalized = intrinsics.normalized_from_pixel(pixel);
    switch (lens.type) {
        case LensType::Pinhole: return PinholeLens<double>::unproject(normalized, camera_direction);
    }
    return false;
}

Ray Camera::ray(const Vec2& pixel) const {
    Ray result;
    result.origin = pose.centre();
    Vec3 camera_direction;
    result.valid = unproject(pixel, camera_direction);
    if (result.valid) result.direction = pose.world_direction_from_camera(camera_direction).normalized();
    return result;
}

}  // namespace libcam
