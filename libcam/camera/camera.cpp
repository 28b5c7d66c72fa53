#include "libcam/camera/camera.hpp"

#include <mutex>

#include "libcam/camera/detail/batch_kernels.hpp"
#include "libcam/camera/detail/point_scale.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/lens/lens_models.hpp"

namespace libcam {

void Camera::validate() const {
    size.validate("image_size");
    intrinsics.validate("K");
    lens.validate("dist");
    pose.validate("R");
}

namespace detail {

// What a PreparedCamera holds: worked out once, read by every call; shared (never
// changed after construction, but for the batch engine built once on first use).
struct PreparedState {
    Camera camera;
    double valid_radius = 0;
    double valid_angle = 0;
    double blind_angle = 0;
    std::once_flag unprojector_built;
    std::unique_ptr<const Unprojector<double>> unprojector;
};

// The model's parameters from the prepared valid radius: a copy, no root search, no
// allocation.
template <class Model>
typename Model::Parameters prepared_parameters(const PreparedState& state) {
    return batch::model_parameters<Model>(state.camera.lens, state.valid_radius);
}

}  // namespace detail

PreparedCamera::PreparedCamera(const Camera& camera) : state_(std::make_shared<detail::PreparedState>()) {
    camera.validate();
    state_->camera = camera;
    state_->valid_radius = visit_lens_model<double>(
        camera.lens.type, [&]<class Model>() { return double(Model::parameters(camera.lens.coefficients).valid_radius); });
    state_->valid_angle = visit_lens_model<double>(camera.lens.type, [&]<class Model>() {
        return libcam::valid_angle<Model>(camera.lens.coefficients, state_->valid_radius);
    });
    state_->blind_angle = visit_lens_model<double>(
        camera.lens.type, [&]<class Model>() { return libcam::blind_angle<Model>(camera.lens.coefficients); });
}

const Camera& PreparedCamera::camera() const { return state_->camera; }

double PreparedCamera::valid_radius() const { return state_->valid_radius; }

double PreparedCamera::valid_angle() const { return state_->valid_angle; }

double PreparedCamera::blind_angle() const { return state_->blind_angle; }

std::vector<Projection> PreparedCamera::project_camera_points(std::span<const Vec3> camera_points) const {
    std::vector<Projection> projections(camera_points.size());
    const Intrinsics& intrinsics = state_->camera.intrinsics;
    visit_lens_model<double>(state_->camera.lens.type, [&]<class Model>() {
        const typename Model::Parameters parameters = detail::prepared_parameters<Model>(*state_);
        for (std::size_t i = 0; i < camera_points.size(); ++i) {
            // A power-of-two scaling (exact) where the model needs it, for points at
            // 1e-300 or 1e300 (camera/detail/point_scale.hpp).
            const Vec3& point = camera_points[i];
            const bool scale = detail::needs_scaling<Model>(point.x(), point.y(), point.z());
            Vec2 normalized;
            Projection& out = projections[i];
            out.valid = Model::project(parameters, scale ? scaled_to_unit_range(point) : point, normalized);
            if (out.valid) out.pixel = intrinsics.pixel_from_normalized(normalized);
            out.valid = out.valid && out.pixel.allFinite();  // K m can overflow too
            if (!out.valid) out.pixel = Vec2::Zero();
        }
    });
    return projections;
}

Projection PreparedCamera::project_camera_point(const Vec3& camera_point) const {
    Projection out;
    const Intrinsics& intrinsics = state_->camera.intrinsics;
    visit_lens_model<double>(state_->camera.lens.type, [&]<class Model>() {
        const bool scale = detail::needs_scaling<Model>(camera_point.x(), camera_point.y(), camera_point.z());
        Vec2 normalized;
        out.valid = Model::project(detail::prepared_parameters<Model>(*state_),
                                   scale ? scaled_to_unit_range(camera_point) : camera_point, normalized);
        if (out.valid) out.pixel = intrinsics.pixel_from_normalized(normalized);
        out.valid = out.valid && out.pixel.allFinite();
        if (!out.valid) out.pixel = Vec2::Zero();
    });
    return out;
}

Projection PreparedCamera::project(const Vec3& world_point) const {
    return project_camera_point(state_->camera.pose.camera_from_world(world_point));
}

std::vector<Projection> PreparedCamera::project(std::span<const Vec3> world_points) const {
    std::vector<Vec3> camera_points(world_points.size());
    for (std::size_t i = 0; i < world_points.size(); ++i) camera_points[i] = state_->camera.pose.camera_from_world(world_points[i]);
    return project_camera_points(camera_points);
}

const Unprojector<double>& PreparedCamera::unprojector() const {
    std::call_once(state_->unprojector_built,
                   [this] { state_->unprojector = std::make_unique<const Unprojector<double>>(*this); });
    return *state_->unprojector;
}

Unprojection PreparedCamera::unproject(const Vec2& pixel) const {
    Unprojection out;
    out.valid = unprojector().unproject(pixel, UnprojectMethod::Exact, out.direction);
    return out;
}

std::vector<Unprojection> PreparedCamera::unproject(std::span<const Vec2> pixels, int threads) const {
    std::vector<Unprojection> out(pixels.size());
    unproject(pixels, out, threads);
    return out;
}

void PreparedCamera::unproject(std::span<const Vec2> pixels, std::span<Unprojection> out, int threads) const {
    unprojector().unproject(pixels, UnprojectMethod::Exact, out, threads);
}

namespace {
Ray world_ray(const Pose& pose, const Unprojection& unprojection) {
    Ray ray;
    ray.origin = pose.centre();
    ray.valid = unprojection.valid;
    if (ray.valid) ray.direction = pose.world_direction_from_camera(unprojection.direction).normalized();
    return ray;
}
}  // namespace

Ray PreparedCamera::ray(const Vec2& pixel) const { return world_ray(state_->camera.pose, unproject(pixel)); }

std::vector<Ray> PreparedCamera::rays(std::span<const Vec2> pixels, int threads) const {
    const std::vector<Unprojection> directions = unproject(pixels, threads);
    std::vector<Ray> out(directions.size());
    for (std::size_t i = 0; i < directions.size(); ++i) out[i] = world_ray(state_->camera.pose, directions[i]);
    return out;
}

}  // namespace libcam
