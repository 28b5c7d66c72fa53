#include "libcam/camera/camera.hpp"

#include "libcam/camera/point_scale.hpp"
#include "libcam/lens/lens_models.hpp"

namespace libcam {

void Camera::validate() const {
    size.validate("image_size");
    intrinsics.validate("K");
    lens.validate("dist");
    pose.validate("R");
}

// What the camera-frame functions use: K and the lens (the pose and the size not).
// Cheap when they are valid, so that every call checks them.
void Camera::validate_lens_and_k() const {
    intrinsics.validate("K");
    lens.validate("dist");
}

std::vector<Projection> Camera::project_camera_points(std::span<const Vec3> camera_points) const {
    validate_lens_and_k();
    return visit_lens_model<double>(lens.type, [&]<class Model>() {
        const typename Model::Parameters parameters = Model::parameters(lens.coefficients);
        std::vector<Projection> projections(camera_points.size());
        for (std::size_t i = 0; i < camera_points.size(); ++i) {
            // A power-of-two scaling (exact) where the model needs it, for points at
            // 1e-300 or 1e300 (camera/point_scale.hpp).
            const Vec3& point = camera_points[i];
            const bool scale = detail::needs_scaling<Model>(point.x(), point.y(), point.z());
            Vec2 normalized;
            Projection& out = projections[i];
            out.valid = Model::project(parameters, scale ? scaled_to_unit_range(point) : point, normalized);
            if (out.valid) out.pixel = intrinsics.pixel_from_normalized(normalized);
            out.valid = out.valid && out.pixel.allFinite();  // K m can overflow too
        }
        return projections;
    });
}

Projection Camera::project_camera_point(const Vec3& camera_point) const {
    return project_camera_points(std::span(&camera_point, 1)).front();
}

std::vector<Unprojection> Camera::unproject_pixels(std::span<const Vec2> pixels) const {
    validate_lens_and_k();
    return visit_lens_model<double>(lens.type, [&]<class Model>() {
        const typename Model::Parameters parameters = Model::parameters(lens.coefficients);
        std::vector<Unprojection> directions(pixels.size());
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            Unprojection& out = directions[i];
            out.valid = Model::unproject(parameters, intrinsics.normalized_from_pixel(pixels[i]), out.direction) &&
                        out.direction.allFinite();
            if (!out.valid) out.direction = Vec3::Zero();
        }
        return directions;
    });
}

bool Camera::unproject(const Vec2& pixel, Vec3& camera_direction) const {
    const Unprojection result = unproject_pixels(std::span(&pixel, 1)).front();
    if (result.valid) camera_direction = result.direction;
    return result.valid;
}

Projection Camera::project(const Vec3& world_point) const {
    pose.validate("R");
    return project_camera_point(pose.camera_from_world(world_point));
}

Ray Camera::ray(const Vec2& pixel) const {
    pose.validate("R");
    Ray result;
    result.origin = pose.centre();
    Vec3 camera_direction;
    result.valid = unproject(pixel, camera_direction);
    if (result.valid) result.direction = pose.world_direction_from_camera(camera_direction).normalized();
    return result;
}

}  // namespace libcam
