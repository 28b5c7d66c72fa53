#include "libcam/camera/camera.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "libcam/camera/detail/batch_kernels.hpp"
#include "libcam/camera/detail/point_scale.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/lens/lens_models.hpp"
#include "libcam/lens/undistort.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

// ---- what a camera must image --------------------------------------------------------------
//
// Finite, positive numbers are not enough: a focal length of 5e-324, or k1 = -1e30 (the
// lens folds over 1e-12 pixels from the principal point), or k1 = 1e30 (the whole image
// squeezed into 1e-8 degrees, from which a derived pinhole gets a focal length of 4e12
// pixels) pass every such check. COLMAP flags odd cameras after a reconstruction
// (Camera::HasBogusParams: a focal length outside 0.1 to 10 times the image's longer side,
// an extra parameter above 1), bounds that refuse real lenses (OpenCV's rational
// coefficients exceed 1) and telephoto or wide cameras. The rule here refuses only a
// camera whose numbers contradict each other, whatever its model:
//   - K (Intrinsics::validate): fx and fy are normal numbers (not subnormal), so that a
//     pixel's offset from the principal point can be divided by them;
//   - every corner of the image has finite normalised coordinates (K's inverse does not
//     overflow over the image);
//   - the four pixels next to the principal point along the image's axes have rays (a
//     lens that folds over, or whose domain ends, within a pixel of the principal point
//     has none there);
//   - a lens with a distortion on top of its projection (the models libcam unprojects by
//     solving it: OpenCV's, Kannala-Brandt's, ...) keeps its scale within that pixel: the
//     undistorted point moves, per pixel, within a factor of 2 as far over the whole
//     pixel as over its first 1/1024. A distortion starts at second order, so the focal
//     length is the lens's scale at its centre; a real lens's changes it by less than a
//     millionth within the first pixel. The scale is the undistorted coordinate's, not
//     the ray's angle, so that a pinhole whose one pixel spans 89 degrees (a 179-degree
//     field of view on a 3-pixel image) stays a camera.
// The message names the coefficient that does it (the one whose removal alone mends it),
// else the focal lengths.
// Any field of view from a millionth of a degree up stays a camera, and so does every
// real lens.

constexpr double kFinePixel = 1.0 / 1024.0;
constexpr double kNearPixel = 1.0 / (1024.0 * 1024.0);
constexpr double kMostScaleChange = 2.0;

// The lens's valid radius (a root search: worked out once per camera).
double valid_radius_of(const Lens& lens) {
    return visit_lens_model<double>(
        lens.type, [&]<class Model>() { return double(Model::parameters(lens.coefficients).valid_radius); });
}

// Whether the lens keeps its scale within a pixel of the principal point (above); the
// reason when it does not. `valid_radius`: valid_radius_of(lens).
std::optional<std::string> scale_fault(const Intrinsics& k, const Lens& lens, double valid_radius) {
    return visit_lens_model<double>(lens.type, [&]<class Model>() -> std::optional<std::string> {
        const typename Model::Parameters parameters = batch::model_parameters<Model>(lens, valid_radius);
        const auto normalized = [&](const Vec2& offset) { return k.normalized_from_pixel(Vec2(Vec2(k.cx, k.cy) + offset)); };
        for (const Vec2& step : {Vec2(1, 0), Vec2(-1, 0), Vec2(0, 1), Vec2(0, -1)}) {
            const auto pixel = [&] {
                return "the pixel (" + format_number(step.x()) + ", " + format_number(step.y()) +
                       ") off the principal point";
            };
            Vec3 ray;
            if (!Model::unproject(parameters, normalized(step), ray) || !ray.allFinite() || !(ray.norm() > 0.0)) {
                return pixel() + " has no ray";
            }
            if constexpr (SolvedLensModel<Model>) {
                // The undistorted point (the model's coordinate before its distortion) at
                // the next pixel, against the point 1/1024 of a pixel off, both from a
                // point 2^-20 of a pixel off (the principal point itself may have no ray:
                // a blind centre).
                Vec2 origin, fine, whole;
                if (!solve_undistorted<Model>(parameters, normalized(kNearPixel * step), origin) ||
                    !solve_undistorted<Model>(parameters, normalized(kFinePixel * step), fine) ||
                    !solve_undistorted<Model>(parameters, normalized(step), whole)) {
                    return pixel() + " has no ray";
                }
                const double across_whole = (whole - origin).norm() / (1.0 - kNearPixel);
                const double across_fine = (fine - origin).norm() / (kFinePixel - kNearPixel);
                if (!(across_whole <= kMostScaleChange * across_fine && across_fine <= kMostScaleChange * across_whole)) {
                    const double factor = std::max(across_whole / across_fine, across_fine / across_whole);
                    return "the lens's scale changes by a factor of " + format_short(factor) + " within " + pixel() +
                           " (by at most " + format_number(kMostScaleChange) +
                           " in a camera: its focal length is the lens's scale there)";
                }
            }
        }
        return std::nullopt;
    });
}

// The coefficient whose removal alone mends the lens, if any.
std::optional<std::size_t> faulty_coefficient(const Intrinsics& k, const Lens& lens) {
    for (std::size_t i = 0; i < lens.coefficients.size(); ++i) {
        if (lens.coefficients[i] == 0.0) continue;
        Lens without = lens;
        without.coefficients[i] = 0.0;
        try {
            without.validate("dist");
        } catch (const InvalidArgument&) {
            continue;  // the model needs it non-zero
        }
        if (!scale_fault(k, without, valid_radius_of(without))) return i;
    }
    return std::nullopt;
}

void require_scale(const Intrinsics& k, const Lens& lens, double valid_radius) {
    const std::optional<std::string> fault = scale_fault(k, lens, valid_radius);
    if (!fault) return;
    if (const std::optional<std::size_t> i = faulty_coefficient(k, lens)) {
        const std::span<const std::string_view> names = lens_info(lens.type).coefficients.view();
        const std::string named = *i < names.size() ? " (" + std::string(names[*i]) + ")" : std::string();
        throw InvalidArgument("dist[" + std::to_string(*i) + "]" + named + ": " + format_number(lens.coefficients[*i]) +
                              ": " + *fault);
    }
    throw InvalidArgument("K: fx " + format_number(k.fx) + ", fy " + format_number(k.fy) + ": " + *fault);
}

// K's inverse over the image: finite at every corner.
void require_finite_image(const ImageSize& size, const Intrinsics& k) {
    const double right = static_cast<double>(size.width) - 0.5, bottom = static_cast<double>(size.height) - 0.5;
    for (const Vec2& corner : {Vec2(-0.5, -0.5), Vec2(right, -0.5), Vec2(-0.5, bottom), Vec2(right, bottom)}) {
        if (k.normalized_from_pixel(corner).allFinite()) continue;
        throw InvalidArgument("K: the image's corner (" + format_number(corner.x()) + ", " + format_number(corner.y()) +
                              ") has no finite direction (fx " + format_number(k.fx) + ", fy " + format_number(k.fy) +
                              ", cx " + format_number(k.cx) + ", cy " + format_number(k.cy) + ", skew " +
                              format_number(k.skew) + ")");
    }
}

// Every check of Camera::validate but the lens's scale, which needs its valid radius.
void validate_values(const Camera& camera) {
    camera.size.validate("image_size");
    camera.intrinsics.validate("K");
    camera.lens.validate("dist");
    camera.pose.validate("R");
    require_finite_image(camera.size, camera.intrinsics);
}

}  // namespace

void Camera::validate() const {
    validate_values(*this);
    require_scale(intrinsics, lens, valid_radius_of(lens));
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
    // Camera::validate, with the valid radius worked out once.
    validate_values(camera);
    state_->valid_radius = valid_radius_of(camera.lens);
    require_scale(camera.intrinsics, camera.lens, state_->valid_radius);
    state_->camera = camera;
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
