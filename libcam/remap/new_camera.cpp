#include "libcam/remap/new_camera.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <cmath>
#include <mutex>
#include <numbers>
#include <vector>

#include "libcam/camera/field_of_view.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/camera/projector.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/error.hpp"
#include "libcam/remap/derived_camera.hpp"
#include "libcam/remap/detail/batches.hpp"
#include "libcam/remap/remap_map.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// The target of scale f (pixels per unit of the model's normalised coordinate: per unit
// of tangent for PINHOLE, per radian for LONLAT, per radian across and per unit of
// tangent down for CYLINDRICAL), square pixels, centred.
Camera centred_camera(LensType model, double f, const ImageSize& size, const Pose& pose) {
    Camera camera;
    camera.size = size;
    camera.intrinsics = {f, f, size.centre_x(), size.centre_y(), 0.0};
    camera.lens = {model, {}};
    camera.pose = pose;
    return camera;
}

// The target's pose: the source's centre, its axes turned by `rotation`.
Pose target_pose(const Camera& source, const Mat3& rotation) {
    return {rotation * source.pose.R, rotation * source.pose.t};
}

// The models a target can be.
constexpr LensType kTargetModels[] = {LensType::Pinhole, LensType::Lonlat, LensType::Cylindrical};
constexpr std::size_t kTargetCount = std::size(kTargetModels);

std::size_t target_index(LensType model) {
    return static_cast<std::size_t>(std::find(std::begin(kTargetModels), std::end(kTargetModels), model) -
                                    std::begin(kTargetModels));
}

// What the source's rays span in the target's frame, for every target model at once: the
// largest |m| on each axis of each model's normalised coordinates, and the largest angle
// off the target's axis.
struct Span {
    std::array<Vec2, kTargetCount> extent{Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
    double off_axis = 0;  // radians
    std::size_t rays = 0;

    const Vec2& of(LensType model) const { return extent[target_index(model)]; }
    void merge(const Span& other) {
        for (std::size_t i = 0; i < kTargetCount; ++i) extent[i] = extent[i].cwiseMax(other.extent[i]);
        off_axis = std::max(off_axis, other.off_axis);
        rays += other.rays;
    }
};

// The largest |m| of the rays that have one and project.
void widen(Vec2& extent, const Points2<double>& m, const ValidFlags& has_ray, const ValidFlags& projected) {
    for (std::size_t j = 0; j < m.size(); ++j) {
        if (has_ray[j] == 0 || projected[j] == 0) continue;
        extent = extent.cwiseMax(Vec2(std::abs(m.x[j]), std::abs(m.y[j])));
    }
}

// Every source pixel's ray (the exact method), in the target's frame.
Span span_of_source(const PreparedCamera& source, const Mat3& rotation, int threads) {
    const Camera& camera = source.camera();
    const std::size_t width = static_cast<std::size_t>(camera.size.width);
    const std::size_t n = width * static_cast<std::size_t>(camera.size.height);
    const Unprojector<double>& unprojector = source.unprojector();
    std::vector<Projector<double>> unit_targets;  // f = 1, centred on (0, 0)
    for (const LensType model : kTargetModels) {
        unit_targets.emplace_back(PreparedCamera(centred_camera(model, 1.0, {1, 1}, {})));
    }
    constexpr std::size_t kStep = 8192;
    Span all;
    std::mutex merging;
    parallel_chunks(n, threads, kStep, [&](std::size_t begin, std::size_t end) {
        Span span;
        Points2<double> m;
        Points3<double> rays;
        ValidFlags has_ray, projected;
        for (std::size_t first = begin; first < end; first += kStep) {
            unprojector.unproject_image_part(UnprojectMethod::Exact, first, std::min(kStep, end - first), rays, has_ray);
            detail::turn(rays, rotation);
            for (std::size_t j = 0; j < rays.size(); ++j) {
                if (has_ray[j] == 0) continue;
                span.off_axis = std::max(span.off_axis, std::atan2(std::hypot(rays.x[j], rays.y[j]), rays.z[j]));
                ++span.rays;
            }
            for (std::size_t t = 0; t < kTargetCount; ++t) {
                unit_targets[t].project(rays, m, projected);
                widen(span.extent[t], m, has_ray, projected);
            }
        }
        const std::lock_guard<std::mutex> lock(merging);
        all.merge(span);
    });
    return all;
}

// Whether every pixel of the target (on its border, and on a lattice every 16 pixels
// inside) has a source pixel at least half a pixel inside the source image.
bool sees_only_source(const Camera& target, const PreparedCamera& source, const Projector<double>& projector,
                      const Mat3& to_source) {
    Points2<double> pixels;
    const long w = target.size.width, h = target.size.height;
    const auto add = [&](long x, long y) {
        pixels.x.push_back(static_cast<double>(x));
        pixels.y.push_back(static_cast<double>(y));
    };
    for (long x = 0; x < w; ++x) {
        add(x, 0);
        add(x, h - 1);
    }
    for (long y = 0; y < h; ++y) {
        add(0, y);
        add(w - 1, y);
    }
    for (long y = 8; y < h; y += 16)
        for (long x = 8; x < w; x += 16) add(x, y);
    Points3<double> rays;
    ValidFlags has_ray, projected;
    Unprojector<double>(target).unproject(pixels, UnprojectMethod::Exact, rays, has_ray);
    detail::turn(rays, to_source);
    Points2<double> source_pixels;
    projector.project(rays, source_pixels, projected);
    for (std::size_t j = 0; j < rays.size(); ++j) {
        if (has_ray[j] == 0 || projected[j] == 0 ||
            !on_image(source_pixels.x[j], source_pixels.y[j], source.camera().size, -0.5)) {
            return false;
        }
    }
    return true;
}

// The widest target with no pixel lacking a source: the smallest f that passes
// sees_only_source.
double widest_valid_scale(LensType model, const ImageSize& size, const PreparedCamera& source, const Pose& pose,
                          const Mat3& to_source) {
    const Projector<double> projector(source);
    const auto passes = [&](double f) {
        return sees_only_source(centred_camera(model, f, size, pose), source, projector, to_source);
    };
    const double half_w = 0.5 * static_cast<double>(size.width), half_h = 0.5 * static_cast<double>(size.height);
    // The widest view the model holds usefully: a pinhole's corners kWidestPinholeDeg / 2
    // off the axis, the whole sphere for LONLAT, a full turn across and kWidestPinholeDeg
    // down for CYLINDRICAL (its height stretches as a pinhole's does).
    const double widest_tangent = std::tan(0.5 * kWidestPinholeDeg * kDegree);
    const double widest = model == LensType::Pinhole ? std::hypot(half_w, half_h) / widest_tangent
                          : model == LensType::Lonlat
                              ? std::max(half_w / std::numbers::pi, half_h / (0.5 * std::numbers::pi))
                              : std::max(half_w / std::numbers::pi, half_h / widest_tangent);
    return smallest_passing_scale(widest, source.camera().intrinsics.fx, passes,
                                  "new camera: the source camera sees nothing along the target's axis (no view, "
                                  "however narrow, has a source for every pixel)");
}

// f for a field of view across the image on an axis, edge to edge.
double scale_for_fov(LensType model, double fov_deg, FovAxis axis, const ImageSize& size) {
    if (axis == FovAxis::Both) {
        throw InvalidArgument("new camera: fov_axis both gives each axis its own focal length; the new camera has "
                              "square pixels: use horizontal, vertical or diagonal");
    }
    const double width = static_cast<double>(size.width), height = static_cast<double>(size.height);
    if (model == LensType::Cylindrical && axis == FovAxis::Vertical) {  // a pinhole's, down
        if (!(fov_deg > 0 && fov_deg < 180)) {
            throw InvalidArgument("new camera: a CYLINDRICAL camera's vertical fov must be in (0, 180) degrees, got " +
                                  format_number(fov_deg));
        }
        return 0.5 * height / std::tan(0.5 * fov_deg * kDegree);
    }
    if (model == LensType::Pinhole) {
        if (!(fov_deg > 0 && fov_deg < 180)) {
            throw InvalidArgument("new camera: a pinhole's fov must be in (0, 180) degrees, got " + format_number(fov_deg));
        }
        const Vec2 tangents = half_tangents_of_fov<double>(fov_deg, axis, size);
        return width / (2.0 * tangents.x());
    }
    const std::string name(lens_info(model).name);
    if (axis == FovAxis::Diagonal) throw InvalidArgument("new camera: " + name + " takes its fov across or down, not diagonally");
    const double limit = axis == FovAxis::Horizontal ? 360.0 : 180.0;
    if (!(fov_deg > 0 && fov_deg <= limit)) {
        throw InvalidArgument("new camera: a " + name + " camera's " + std::string(to_string(axis)) +
                              " fov must be in (0, " + format_number(limit) + "] degrees, got " + format_number(fov_deg));
    }
    return (axis == FovAxis::Horizontal ? width : height) / (fov_deg * kDegree);
}

// "101.2 x 97.5 deg": the target's view, edge to edge.
std::string view_of(const Camera& camera) {
    const double f = camera.intrinsics.fx;
    const double w = static_cast<double>(camera.size.width), h = static_cast<double>(camera.size.height);
    const auto angle = [&](double side, bool in_radians) {
        return (in_radians ? side / f : 2.0 * std::atan(0.5 * side / f)) / kDegree;
    };
    const LensType model = camera.lens.type;
    return format_short(angle(w, model != LensType::Pinhole), 4) + " x " +
           format_short(angle(h, model == LensType::Lonlat), 4) + " deg";
}

std::string size_text(const ImageSize& size) { return std::to_string(size.width) + "x" + std::to_string(size.height); }

}  // namespace

NewCamera choose_new_camera(const PreparedCamera& source, const NewCameraRequest& request) {
    if (target_index(request.model) == kTargetCount) {
        throw InvalidArgument("new camera: the model must be PINHOLE, LONLAT or CYLINDRICAL, got " +
                              std::string(lens_info(request.model).name));
    }
    Pose{request.rotation, Vec3::Zero()}.validate("rotation");
    const ImageSize size = request.size.value_or(source.camera().size);
    size.validate("size");
    const Pose pose = target_pose(source.camera(), request.rotation);
    const Mat3 to_source = request.rotation.transpose();
    LensType model = request.model;
    std::string why;
    double f = 0;
    if (!request.keep) {
        f = scale_for_fov(model, request.fov_deg, request.fov_axis, size);
        why = "the " + std::string(to_string(request.fov_axis)) + " field of view asked for";
    } else if (*request.keep == Keep::Valid) {
        f = widest_valid_scale(model, size, source, pose, to_source);
        why = "the widest view with a source pixel for every pixel (no black borders)";
        const double half_diagonal = 0.5 * std::hypot(static_cast<double>(size.width), static_cast<double>(size.height));
        if (model == LensType::Pinhole && std::atan(half_diagonal / f) >= 0.5 * kWidestPinholeDeg * kDegree * (1 - 1e-12)) {
            why += ", up to " + format_short(kWidestPinholeDeg, 3) +
                   " deg across the diagonal (a wider pinhole stretches its edges beyond use; --to-lonlat keeps more)";
        }
        const double half_height = 0.5 * static_cast<double>(size.height);
        if (model == LensType::Cylindrical &&
            std::atan(half_height / f) >= 0.5 * kWidestPinholeDeg * kDegree * (1 - 1e-12)) {
            why += ", up to " + format_short(kWidestPinholeDeg, 3) +
                   " deg from top to bottom (a taller cylinder stretches its top and bottom beyond use; --to-lonlat "
                   "keeps more)";
        }
    } else {
        const Span span = span_of_source(source, request.rotation, request.threads);
        if (span.rays == 0) throw InvalidArgument("new camera: no pixel of the source camera has a ray");
        const double widest_off_axis = 0.5 * kWidestPinholeDeg * kDegree;
        if (model == LensType::Pinhole && span.off_axis > widest_off_axis) {
            why = "the lens sees " + format_short(span.off_axis / kDegree, 4) +
                  " deg off the axis, more than a pinhole holds without stretching its edges beyond use (" +
                  format_short(0.5 * kWidestPinholeDeg, 3) + " deg), so LONLAT; ";
            model = LensType::Lonlat;
        }
        const double latitude = std::atan(span.of(LensType::Cylindrical).y());  // the farthest up or down
        if (model == LensType::Cylindrical && latitude > widest_off_axis) {
            why = "the lens sees " + format_short(latitude / kDegree, 4) +
                  " deg above or below the horizon, more than a cylinder holds without stretching its top and "
                  "bottom beyond use (" + format_short(0.5 * kWidestPinholeDeg, 3) + " deg), so LONLAT; ";
            model = LensType::Lonlat;
        }
        // The source pixels farthest out land on the target's outermost pixel centres.
        const double half_w = std::max(0.5 * static_cast<double>(size.width - 1), 0.5);
        const double half_h = std::max(0.5 * static_cast<double>(size.height - 1), 0.5);
        const double tiny = 1e-300;
        const Vec2& extent = span.of(model);
        f = std::min(half_w / std::max(extent.x(), tiny), half_h / std::max(extent.y(), tiny));
        why += "the narrowest view that keeps every source pixel with a ray";
    }
    NewCamera chosen{centred_camera(model, f, size, pose), ""};
    chosen.why = std::string(lens_info(model).name) + " " + size_text(size) + ", " + view_of(chosen.camera) +
                 ", f " + format_short(f, 6) + " px, principal point at the centre: " + why;
    return chosen;
}

double smallest_passing_scale(double widest, double start, const std::function<bool(double)>& passes,
                              const std::string& nothing_passes) {
    if (passes(widest)) return widest;
    double narrow = std::max(start, widest);
    for (int doubling = 0; !passes(narrow); ++doubling) {
        if (doubling == 60) throw InvalidArgument(nothing_passes);
        narrow *= 2.0;
    }
    double wide = widest;
    while (narrow / wide > 1.0 + 1e-12) {
        const double middle = std::sqrt(wide * narrow);
        (passes(middle) ? narrow : wide) = middle;
    }
    return narrow;
}

double widest_ray_angle(const PreparedCamera& lens, int threads) {
    const Span span = span_of_source(lens, Mat3::Identity(), threads);
    if (span.rays == 0) {
        const ImageSize& size = lens.camera().size;
        throw InvalidArgument("lens: no pixel of the " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                              " image has a ray");
    }
    return span.off_axis;
}

Overscan overscan_for(const PreparedCamera& lens, const Camera& render, const Mat3& rotation, int threads) {
    // The lens's pixels through a render twice its own size bigger on every side: where
    // each lands on the plain render, and which land nowhere.
    const long reach_x = 2 * render.size.width, reach_y = 2 * render.size.height;
    const PreparedCamera wide(padded(render, reach_x, reach_y, reach_x, reach_y));
    RemapOptions options;
    options.rotation = rotation.transpose();  // the lens's axes relative to the render's
    options.threads = threads;
    const RemapMap map = build_remap_map(lens, wide, options);
    double low_x = 0, low_y = 0, high_x = 0, high_y = 0;  // beyond the render's centre span
    const double last_x = static_cast<double>(render.size.width - 1), last_y = static_cast<double>(render.size.height - 1);
    const std::size_t width = static_cast<std::size_t>(map.size.width);
    std::vector<Vec2> without_source;  // lens pixels the map gives nothing: no ray, or one beyond any margin
    for (std::size_t i = 0; i < map.x.size(); ++i) {
        if (!map.has_source(i)) {
            without_source.emplace_back(static_cast<double>(i % width), static_cast<double>(i / width));
            continue;
        }
        const double x = map.x[i] - static_cast<double>(reach_x), y = map.y[i] - static_cast<double>(reach_y);
        low_x = std::max(low_x, -x);
        low_y = std::max(low_y, -y);
        high_x = std::max(high_x, x - last_x);
        high_y = std::max(high_y, y - last_y);
    }
    // Of those, the ones with a ray (the map's own exact unprojection: the same answer)
    // are the ones no margin can hold; a pixel that sees nothing needs nothing rendered.
    std::size_t beyond = 0;
    for (const Unprojection& ray : lens.unproject(without_source, threads)) beyond += ray.valid ? 1 : 0;
    if (beyond > 0) {
        throw InvalidArgument("overscan: " + std::to_string(beyond) +
                              " pixels of the lens see rays the render cannot hold with any margin (behind its camera, "
                              "past its lens's domain, or more than twice its size beyond its edges): give the render "
                              "a wider view");
    }
    // Whole pixels; a coordinate within rounding of a whole number needs no pixel more.
    const auto margin = [](double needed) { return static_cast<long>(std::ceil(needed - 1e-9)); };
    return {margin(low_x), margin(low_y), margin(high_x), margin(high_y)};
}

}  // namespace libcam
