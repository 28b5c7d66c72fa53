#include "libcam/dataset/detail/dataset_views.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
#include <mutex>
#include <optional>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>

#include "libcam/camera/parallel.hpp"
#include "libcam/convert/colmap_models.hpp"
#include "libcam/error.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// A view's turn: its axes relative to the source's (d_view = Q d_source), looking along
// (sin yaw cos pitch, sin pitch, cos yaw cos pitch) with its x axis kept level.
Mat3 turn_of(double yaw_deg, double pitch_deg) {
    const Mat3 axes = (Eigen::AngleAxisd(yaw_deg * kDegree, Vec3::UnitY()) *
                       Eigen::AngleAxisd(-pitch_deg * kDegree, Vec3::UnitX()))
                          .toRotationMatrix();
    return axes.transpose();
}

struct Direction {
    double yaw_deg, pitch_deg;
};

struct Layout {
    std::string name;
    std::vector<Direction> axes;
};

// The layouts tried, fewest views first: one view; two or three side by side or one above
// another; four around the axis; a front view with four around it; rings of views about
// the vertical, with and without views straight up and down (for panoramas).
std::vector<Layout> candidate_layouts() {
    std::vector<Layout> layouts;
    layouts.push_back({"one view along the axis", {{0, 0}}});
    for (const double turn : {20.0, 30.0, 40.0, 50.0, 60.0}) {
        const std::string by = format_short(turn, 3) + " deg";
        layouts.push_back({"two views turned left and right by " + by, {{-turn, 0}, {turn, 0}}});
        layouts.push_back({"two views turned up and down by " + by, {{0, -turn}, {0, turn}}});
    }
    for (const double turn : {40.0, 50.0, 60.0, 70.0, 80.0, 90.0}) {
        const std::string by = format_short(turn, 3) + " deg";
        layouts.push_back({"a front view and two turned left and right by " + by, {{-turn, 0}, {0, 0}, {turn, 0}}});
        layouts.push_back({"a front view and two turned up and down by " + by, {{0, -turn}, {0, 0}, {0, turn}}});
    }
    for (const double turn : {30.0, 35.0, 40.0, 45.0, 50.0, 55.0, 60.0}) {
        layouts.push_back({"four views turned left, right, up and down by " + format_short(turn, 3) + " deg",
                           {{-turn, 0}, {turn, 0}, {0, -turn}, {0, turn}}});
    }
    for (const double turn : {45.0, 55.0, 65.0, 75.0, 90.0}) {
        layouts.push_back({"a front view and four turned left, right, up and down by " + format_short(turn, 3) + " deg",
                           {{0, 0}, {-turn, 0}, {turn, 0}, {0, -turn}, {0, turn}}});
    }
    for (const int ring : {3, 4, 5, 6}) {
        for (const bool poles : {false, true}) {
            Layout layout{std::to_string(ring) + " views around the vertical" + (poles ? ", one up and one down" : ""), {}};
            for (int k = 0; k < ring; ++k) layout.axes.push_back({360.0 * k / ring - (k * 2 >= ring ? 360.0 : 0.0), 0});
            if (poles) layout.axes.insert(layout.axes.end(), {{0, -90}, {0, 90}});
            layouts.push_back(std::move(layout));
        }
    }
    std::stable_sort(layouts.begin(), layouts.end(),
                     [](const Layout& a, const Layout& b) { return a.axes.size() < b.axes.size(); });
    return layouts;
}

// What a layout makes of rays: each view's box of tangents, the rays given to the view
// whose axis is nearest.
struct Boxes {
    std::vector<Eigen::AlignedBox2d> tangents;
    std::vector<Mat3> turns;
};

Boxes empty_boxes(const Layout& layout) {
    Boxes boxes;
    for (const Direction& axis : layout.axes) boxes.turns.push_back(turn_of(axis.yaw_deg, axis.pitch_deg));
    boxes.tangents.assign(boxes.turns.size(), Eigen::AlignedBox2d());
    return boxes;
}

// Widens `boxes` by `rays` (unit length); false, leaving them part-widened, when a ray is
// further than `limit_deg` from every view's axis.
bool widen(Boxes& boxes, const std::vector<Vec3>& rays, double limit_deg, int threads) {
    const double nearest_allowed = std::cos(limit_deg * kDegree);
    const std::size_t views = boxes.turns.size();
    std::mutex lock;
    std::atomic<bool> held{true};
    parallel_chunks(rays.size(), threads, 4096, [&](std::size_t begin, std::size_t end) {
        if (!held) return;
        std::vector<Eigen::AlignedBox2d> part(views);
        for (std::size_t i = begin; i < end; ++i) {
            std::size_t best = 0;
            double best_dot = -2;
            for (std::size_t k = 0; k < views; ++k) {
                const double dot = boxes.turns[k].row(2).dot(rays[i]);
                if (dot > best_dot) best_dot = dot, best = k;
            }
            if (best_dot < nearest_allowed) {
                held = false;
                return;
            }
            const Vec3 d = boxes.turns[best] * rays[i];
            part[best].extend(Vec2(d.x() / d.z(), d.y() / d.z()));
        }
        const std::lock_guard<std::mutex> guard(lock);
        for (std::size_t k = 0; k < views; ++k) {
            if (!part[k].isEmpty()) boxes.tangents[k].extend(part[k]);
        }
    });
    return held;
}

// The smallest pinhole of `focal` pixels per unit tangent whose pixel centres span the box.
Camera pinhole_over(const Eigen::AlignedBox2d& box, double focal, const Mat3& turn, const Pose& source_pose) {
    const auto side = [&](double low, double high) {
        return static_cast<long>(std::ceil(focal * (high - low) - 1e-9)) + 1;
    };
    Camera camera;
    camera.size = {side(box.min().x(), box.max().x()), side(box.min().y(), box.max().y())};
    camera.intrinsics = {focal, focal, -focal * box.min().x(), -focal * box.min().y(), 0.0};
    camera.lens = {LensType::Pinhole, {}};
    camera.pose = {turn * source_pose.R, turn * source_pose.t};
    return camera;
}

// The rays (unit length) of the pixel centres of `rows` that have one, every `step`-th
// column and the last.
std::vector<Vec3> pixel_rays(const PreparedCamera& source, const std::vector<long>& rows, long step, int threads) {
    const long width = source.camera().size.width;
    std::vector<Vec2> pixels;
    for (const long y : rows) {
        for (long x = 0; x < width; x += step) pixels.emplace_back(static_cast<double>(x), static_cast<double>(y));
        if ((width - 1) % step != 0) pixels.emplace_back(static_cast<double>(width - 1), static_cast<double>(y));
    }
    std::vector<Vec3> rays;
    rays.reserve(pixels.size());
    for (const Unprojection& ray : source.unproject(pixels, threads)) {
        if (ray.valid) rays.push_back(ray.direction.normalized());
    }
    return rays;
}

// The choice is made on the rays of a sample of the pixels (every `step`-th row and column,
// and the last): at most about kSampledPixels of them.
constexpr double kSampledPixels = 250000;

std::vector<Vec3> sampled_rays(const PreparedCamera& source, std::span<const Vec3> extra_rays, int threads) {
    const ImageSize& size = source.camera().size;
    const double area = static_cast<double>(size.width) * static_cast<double>(size.height);
    const long step = std::max(1L, static_cast<long>(std::ceil(std::sqrt(area / kSampledPixels))));
    std::vector<long> rows;
    for (long y = 0; y < size.height; y += step) rows.push_back(y);
    if (rows.back() != size.height - 1) rows.push_back(size.height - 1);
    std::vector<Vec3> rays = pixel_rays(source, rows, step, threads);
    if (rays.empty()) {
        throw InvalidArgument("lens: no pixel of the " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                              " image has a ray");
    }
    for (const Vec3& ray : extra_rays) rays.push_back(ray.normalized());
    return rays;
}

// The chosen layout's boxes over every pixel's ray, a block of rows at a time (so that a
// large image's rays are never all in memory). A pixel between the samples may lie a little
// past kViewHalfAngleDeg from its view's axis; one a pinhole cannot hold at all (past
// kHardLimitDeg) is refused.
constexpr double kHardLimitDeg = 85.0;

void widen_by_every_pixel(Boxes& boxes, const PreparedCamera& source, int threads) {
    const long height = source.camera().size.height, block = 64;
    for (long row = 0; row < height; row += block) {
        std::vector<long> rows;
        for (long y = row; y < std::min(height, row + block); ++y) rows.push_back(y);
        if (!widen(boxes, pixel_rays(source, rows, 1, threads), kHardLimitDeg, threads)) {
            throw InvalidArgument("a pixel's ray is more than " + format_short(kHardLimitDeg, 3) +
                                  " deg from every view's axis (between the pixels the views were chosen on)");
        }
    }
}

double widest_angle_deg(const std::vector<Vec3>& rays) {
    double smallest_z = 1;
    for (const Vec3& ray : rays) smallest_z = std::min(smallest_z, ray.z());
    return std::acos(std::clamp(smallest_z, -1.0, 1.0)) / kDegree;
}

double pixels_of(const Boxes& boxes, double focal, std::size_t& views) {
    double pixels = 0;
    views = 0;
    for (const Eigen::AlignedBox2d& box : boxes.tangents) {
        if (box.isEmpty()) continue;
        ++views;
        const Vec2 sides = focal * box.sizes();
        pixels += (std::ceil(sides.x()) + 1) * (std::ceil(sides.y()) + 1);
    }
    return pixels;
}

}  // namespace

LensViews choose_views(const PreparedCamera& source, std::span<const Vec3> extra_rays, int threads) {
    const std::vector<Vec3> rays = sampled_rays(source, extra_rays, threads);
    const Intrinsics& k = source.camera().intrinsics;
    const double focal = std::sqrt(k.fx * k.fy);
    const std::vector<Layout> layouts = candidate_layouts();
    const Layout* best = nullptr;
    std::optional<Boxes> best_boxes;
    std::size_t best_views = 0;
    double best_pixels = 0;
    for (const Layout& layout : layouts) {
        if (best && layout.axes.size() > best_views) break;  // fewer views always win
        Boxes boxes = empty_boxes(layout);
        if (!widen(boxes, rays, kViewHalfAngleDeg, threads)) continue;
        std::size_t views = 0;
        const double pixels = pixels_of(boxes, focal, views);
        if (!best || views < best_views || (views == best_views && pixels < best_pixels)) {
            best = &layout;
            best_boxes = std::move(boxes);
            best_views = views;
            best_pixels = pixels;
        }
    }
    const double widest = widest_angle_deg(rays);
    if (!best) {
        throw InvalidArgument("the lens sees " + format_short(widest, 4) +
                              " deg off its axis: no layout of pinhole views tried holds it (each view keeps within " +
                              format_short(kViewHalfAngleDeg, 3) + " deg of its axis)");
    }
    widen_by_every_pixel(*best_boxes, source, threads);
    best_pixels = pixels_of(*best_boxes, focal, best_views);
    LensViews chosen;
    for (std::size_t v = 0; v < best->axes.size(); ++v) {
        if (best_boxes->tangents[v].isEmpty()) continue;
        LensView view;
        view.turn = best_boxes->turns[v];
        view.yaw_deg = best->axes[v].yaw_deg;
        view.pitch_deg = best->axes[v].pitch_deg;
        view.camera = pinhole_over(best_boxes->tangents[v], focal, view.turn, source.camera().pose);
        chosen.views.push_back(std::move(view));
    }
    const std::string angle = "rays up to " + format_short(widest, 4) + " deg off the axis";
    if (chosen.views.size() == 1) {
        chosen.why = angle + ", within the " + format_short(kViewHalfAngleDeg, 3) +
                     " deg one pinhole holds well: one view, the smallest pinhole holding every pixel's ray";
    } else {
        chosen.why = angle + ", more than the " + format_short(kViewHalfAngleDeg, 3) + " deg one pinhole holds well: " +
                     best->name + " (" + std::to_string(chosen.views.size()) + " views, " +
                     format_short(best_pixels, 9) +
                     " pixels: the fewest views, then pixels, of the layouts tried that hold every pixel's ray and "
                     "every observation within " + format_short(kViewHalfAngleDeg, 3) + " deg of a view's axis)";
    }
    return chosen;
}

std::string view_image_name(const std::string& source_name, std::size_t view) {
    const std::filesystem::path name(source_name);
    const std::filesystem::path renamed = name.parent_path() / (name.stem().string() + "_view" + std::to_string(view) +
                                                                name.extension().string());
    return renamed.generic_string();
}

}  // namespace libcam

namespace libcam {

namespace {

// The rays of the POINTS2D of each camera's images, in its frame (those that have one).
std::vector<std::vector<Vec3>> observation_rays(const std::vector<PreparedCamera>& sources,
                                                const std::vector<ColmapImage>& images,
                                                const std::vector<std::size_t>& camera_of) {
    std::vector<std::vector<Vec3>> rays(sources.size());
    for (std::size_t i = 0; i < images.size(); ++i) {
        const PreparedCamera& source = sources[camera_of[i]];
        for (const ColmapPoint2D& point : images[i].points) {
            const Unprojection ray = source.unproject(Vec2(point.x - kColmapPixelShift, point.y - kColmapPixelShift));
            if (ray.valid) rays[camera_of[i]].push_back(ray.direction);
        }
    }
    return rays;
}

DatasetCamera view_camera(const ColmapCameraRecord& record, const LensView& view, std::size_t index,
                          const LensViews& all) {
    DatasetCamera camera;
    camera.source_id = record.id;
    camera.source_model = std::string(record.model);
    camera.source = record.camera;
    camera.camera = view.camera;
    camera.camera.pose = {};
    camera.why = all.why;
    camera.view = index;
    camera.views = all.views.size();
    camera.turn = view.turn;
    camera.yaw_deg = view.yaw_deg;
    camera.pitch_deg = view.pitch_deg;
    return camera;
}

}  // namespace

ViewSplit split_into_views(const std::vector<ColmapCameraRecord>& cameras, const std::vector<ColmapImage>& images,
                           const ColmapPoints3D& points, const std::vector<std::size_t>& camera_of,
                           const std::vector<std::optional<DatasetCamera>>& kept_as_is, const std::string& where,
                           int threads) {
    std::vector<PreparedCamera> sources;
    for (const ColmapCameraRecord& record : cameras) sources.emplace_back(record.camera);
    const std::vector<std::vector<Vec3>> rays = observation_rays(sources, images, camera_of);
    ViewSplit split;
    std::vector<std::size_t> first_view(cameras.size());
    for (std::size_t c = 0; c < cameras.size(); ++c) {
        first_view[c] = split.cameras.size();
        if (kept_as_is[c]) {
            split.cameras.push_back(*kept_as_is[c]);
            split.cameras.back().source_id = cameras[c].id;
        } else {
            const std::string name = "camera " + std::to_string(cameras[c].id) + " (" + std::string(cameras[c].model) + ")";
            LensViews views;
            try {
                views = choose_views(sources[c], rays[c], threads);
            } catch (const InvalidArgument& error) {
                throw InvalidArgument(name + ": " + error.what());
            }
            for (std::size_t v = 0; v < views.views.size(); ++v) {
                split.cameras.push_back(view_camera(cameras[c], views.views[v], v, views));
            }
        }
    }
    for (std::size_t k = 0; k < split.cameras.size(); ++k) {
        split.cameras[k].id = k + 1;
        split.records.push_back({k + 1, split.cameras[k].camera, "PINHOLE"});
    }
    // Image i's view v is image first_image[i] + v of the output.
    std::vector<std::size_t> first_image(images.size());
    std::map<std::uint64_t, std::size_t> image_index;
    for (std::size_t i = 0; i < images.size(); ++i) {
        image_index.emplace(images[i].id, i);
        first_image[i] = split.images.size();
        const std::size_t c = camera_of[i];
        const std::size_t views = split.cameras[first_view[c]].views;
        for (std::size_t v = 0; v < views; ++v) {
            const DatasetCamera& camera = split.cameras[first_view[c] + v];
            ColmapImage view = images[i];
            view.id = split.images.size() + 1;
            view.camera_id = camera.id;
            if (views > 1) view.name = view_image_name(images[i].name, v);
            view.pose = {camera.turn * images[i].pose.R, camera.turn * images[i].pose.t};
            split.images.push_back(std::move(view));
            split.camera_of.push_back(first_view[c] + v);
            split.source_of.push_back(i);
        }
    }
    split.points = points;
    split.points.track.clear();
    split.points.track_begin.assign(1, 0);
    for (std::size_t p = 0; p < points.ids.size(); ++p) {
        for (std::size_t k = points.track_begin[p]; k < points.track_begin[p + 1]; ++k) {
            const auto [image_id, index] = points.track[k];
            const auto found = image_index.find(image_id);
            if (found == image_index.end()) {
                throw FileError(where + ": point " + std::to_string(points.ids[p]) + ": track element (" +
                                std::to_string(image_id) + ", " + std::to_string(index) + ") names no image");
            }
            const std::size_t views = split.cameras[first_view[camera_of[found->second]]].views;
            for (std::size_t v = 0; v < views; ++v) {
                split.points.track.push_back({static_cast<std::uint32_t>(first_image[found->second] + v + 1), index});
            }
        }
        split.points.track_begin.push_back(split.points.track.size());
    }
    return split;
}

}  // namespace libcam
