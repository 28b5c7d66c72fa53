#include "libcam/uncertainty/uncertainty_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "libcam/error.hpp"
#include "libcam/geometry/pixel_grid.hpp"

namespace libcam {

namespace {

// The z of (b - a) x (c - a): positive when a, b, c turn counter-clockwise (x right, y down:
// clockwise on screen).
double turn(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// The convex hull of points, by Andrew's monotone chain: its corners in order, no three in line.
std::vector<Vec2> convex_hull(std::vector<Vec2> points) {
    std::sort(points.begin(), points.end(),
              [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
    points.erase(std::unique(points.begin(), points.end()), points.end());
    if (points.size() < 3) return points;
    std::vector<Vec2> hull(2 * points.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {  // lower chain
        while (k >= 2 && turn(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
        hull[k++] = points[i];
    }
    for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
        while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
        hull[k++] = points[i];
    }
    hull.resize(k - 1);
    return hull;
}

}  // namespace

namespace {

// The camera's part of the set: its board views with their inlier observations and
// weights, each view's frame where the set's cameras share board poses.
SolvedCalibration camera_part(const ObservationSet& set, int camera) {
    if (!set.board) {
        throw FileError(set.source + ": holds no calibration board (" + std::string(to_string(set.tool)) +
                        "): the projection uncertainty needs a board's corners, known points seen from solved poses");
    }
    const auto corners = static_cast<std::size_t>(set.board->width) * static_cast<std::size_t>(set.board->height);
    SolvedCalibration solved;
    solved.camera = set.cameras.at(static_cast<std::size_t>(camera)).camera;
    solved.camera.pose = Pose{};
    if (set.board->warp_solved) {
        solved.bow = SolvedCalibration::BoardBow{(set.board->width - 1) * set.board->spacing,
                                                 (set.board->height - 1) * set.board->spacing};
    }
    std::vector<int> view_of(set.views.size(), -1);
    for (std::size_t v = 0; v < set.views.size(); ++v) {
        if (set.views[v].camera != camera) continue;
        view_of[v] = static_cast<int>(solved.views.size());
        solved.views.push_back({set.views[v].name, set.views[v].pose, {}});
        solved.weights.emplace_back();
        const int frame = set.views[v].frame;
        if (set.frames.empty()) continue;
        if (frame < 0 || static_cast<std::size_t>(frame) >= set.frames.size()) {
            throw FileError(set.source + ": view " + set.views[v].name + " has no board pose of the solve's " +
                            std::to_string(set.frames.size()));
        }
        solved.frame_of_view.push_back(frame);
        // The camera's pose from the reference: the view's pose after its board's, undone.
        solved.camera.pose = set.views[v].pose.after(set.frames[static_cast<std::size_t>(frame)].inverse());
        solved.pose_solved = set.views[v].camera_pose_solved;
    }
    std::size_t counted = 0;
    for (const Observation& o : set.observations) {
        const int v = view_of[static_cast<std::size_t>(o.view)];
        // The tool's inliers on the board (mrcal's discrete points, beyond its corners, are not).
        if (v < 0 || !o.inlier || !(o.weight > 0.0) || static_cast<std::size_t>(o.point) >= corners) continue;
        auto& view = solved.views[static_cast<std::size_t>(v)];
        view.observations.push_back({set.points[static_cast<std::size_t>(o.point)], o.pixel});
        solved.weights[static_cast<std::size_t>(v)].push_back(o.weight);
        ++counted;
    }
    if (counted == 0) {
        throw FileError(set.source + ": camera " + set.cameras[static_cast<std::size_t>(camera)].name +
                        ": no board observation counted (every one is an outlier, or there are none)");
    }
    for (std::size_t v = solved.views.size(); v-- > 0;) {
        if (!solved.views[v].observations.empty()) continue;
        solved.views.erase(solved.views.begin() + static_cast<long>(v));
        solved.weights.erase(solved.weights.begin() + static_cast<long>(v));
        if (!solved.frame_of_view.empty()) solved.frame_of_view.erase(solved.frame_of_view.begin() + static_cast<long>(v));
    }
    return solved;
}

}  // namespace

SolvedCalibration solved_calibration(const ObservationSet& set, int camera) {
    SolvedCalibration solved = camera_part(set, camera);
    if (set.frames.empty()) return solved;
    // A solve of several cameras sharing the boards' poses: the others count too.
    solved.frames = set.frames;
    for (std::size_t other = 0; other < set.cameras.size(); ++other) {
        if (static_cast<int>(other) != camera) solved.others.push_back(camera_part(set, static_cast<int>(other)));
    }
    return solved;
}

UncertaintyMap uncertainty_map(const ProjectionUncertainty& uncertainty, long columns, double distance) {
    if (columns < 2) throw InvalidArgument("grid: " + std::to_string(columns) + " columns: at least 2");
    UncertaintyMap map;
    map.image = uncertainty.camera().size;
    map.columns = columns;
    map.rows = std::max(2L, std::lround(static_cast<double>(columns) * static_cast<double>(map.image.height) /
                                        static_cast<double>(map.image.width)));
    map.distance = distance;
    map.pixels = tile_centres(map.image, map.columns, map.rows);
    map.sigma_px = uncertainty.sigma_px(map.pixels, distance);
    return map;
}

std::vector<Vec2> observed_region(const SolvedCalibration& solved) {
    std::vector<Vec2> pixels;
    for (const FitView& view : solved.views) {
        for (const FitSample& o : view.observations) pixels.push_back(o.pixel);
    }
    return convex_hull(std::move(pixels));
}

bool inside_region(const std::vector<Vec2>& region, const Vec2& pixel) {
    if (region.size() < 3) return false;
    for (std::size_t i = 0; i < region.size(); ++i) {
        if (turn(region[i], region[(i + 1) % region.size()], pixel) < 0.0) return false;
    }
    return true;
}

UncertaintySummary summarize(const UncertaintyMap& map, const std::vector<Vec2>& region) {
    UncertaintySummary out;
    std::size_t below_tenth = 0, below_one = 0;
    for (std::size_t i = 0; i < map.pixels.size(); ++i) {
        const double sigma = map.sigma_px[i];
        if (sigma < 0.1) ++below_tenth;
        if (sigma < 1.0) ++below_one;
        if (!inside_region(region, map.pixels[i])) continue;
        ++out.observed_tiles;
        // A pixel without a ray inside the observed region is as bad as it gets.
        out.worst_observed_px = std::isnan(sigma) || std::isnan(out.worst_observed_px)
                                    ? std::numeric_limits<double>::quiet_NaN()
                                    : std::max(out.worst_observed_px, sigma);
    }
    const auto total = static_cast<double>(std::max<std::size_t>(1, map.pixels.size()));
    out.share_below_0_1 = static_cast<double>(below_tenth) / total;
    out.share_below_1 = static_cast<double>(below_one) / total;
    return out;
}

}  // namespace libcam
