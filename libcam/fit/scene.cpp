#include "libcam/fit/scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include "libcam/error.hpp"

namespace libcam {

namespace {

// Boundary points sit on the boundary up to rounding; membership forgives that much.
constexpr double kBoundarySlack = 1e-9;

// Fewest points on a closed curve, so that a tiny circle is still a polygon.
constexpr int kMinCurvePoints = 16;
// Directions used to find how long the field-angle curve is before sampling it.
constexpr int kConeProbeCount = 64;
// Most points on a curve: a cone near 90 degrees through a perspective lens projects
// to a curve far larger than the image, nearly all of it outside.
constexpr double kMaxCurvePoints = 65536.0;
// Margin around the probes' box, as a fraction of its size.
constexpr double kConeBoxMargin = 0.05;
// A default lattice puts at least this many samples across the scene's narrow side.
constexpr double kMinSamplesAcross = 8.0;
// Finest default lattice spacing: finer adds nothing for a smooth error.
constexpr double kMinSpacingPx = 0.1;

PixelBox image_box(const ImageSize& size) {
    return {Vec2::Zero(), Vec2(static_cast<double>(size.width - 1), static_cast<double>(size.height - 1))};
}

bool inside(const PixelBox& box, const Vec2& p) {
    return p.x() >= box.min.x() - kBoundarySlack && p.x() <= box.max.x() + kBoundarySlack &&
           p.y() >= box.min.y() - kBoundarySlack && p.y() <= box.max.y() + kBoundarySlack;
}

std::string point_text(const Vec2& p) { return "(" + format_number(p.x()) + ", " + format_number(p.y()) + ")"; }

std::string image_text(const ImageSize& size) {
    return "the image's pixel centres [0, " + std::to_string(size.width - 1) + "] x [0, " +
           std::to_string(size.height - 1) + "]";
}

// Points from a to b (both included), at most `spacing` apart.
void append_segment(const Vec2& a, const Vec2& b, double spacing, std::vector<Vec2>& out) {
    const long steps = std::max(1L, static_cast<long>(std::ceil((b - a).norm() / spacing)));
    for (long i = 0; i <= steps; ++i) out.push_back(a + (b - a) * (static_cast<double>(i) / static_cast<double>(steps)));
}

// The corners of a box, counter-clockwise from min.
std::vector<Vec2> box_corners(const PixelBox& box) {
    return {box.min, Vec2(box.max.x(), box.min.y()), box.max, Vec2(box.min.x(), box.max.y())};
}

std::vector<Vec2> polygon_points(const std::vector<Vec2>& corners, double spacing) {
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < corners.size(); ++i) append_segment(corners[i], corners[(i + 1) % corners.size()], spacing, out);
    return out;
}

std::vector<Vec2> circle_points(const Vec2& center, double radius, int count) {
    std::vector<Vec2> out;
    for (int i = 0; i < count; ++i) {
        const double angle = 2.0 * std::numbers::pi * i / count;
        out.push_back(center + radius * Vec2(std::cos(angle), std::sin(angle)));
    }
    return out;
}

double polyline_length(const std::vector<Vec2>& points) {
    double length = 0.0;
    for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
    return length;
}

// Unit directions of the pixels (zero where the source has no ray) and their validity.
std::vector<Unprojection> unit_rays(const PreparedCamera& source, const std::vector<Vec2>& pixels) {
    std::vector<Unprojection> rays = source.unproject(pixels);
    for (Unprojection& ray : rays) {
        if (ray.valid) ray.direction.normalize();
    }
    return rays;
}

// The lattice's points inside `box`.
std::vector<Vec2> lattice_points(const ImageSize& size, const Lattice& lattice, const PixelBox& box) {
    return lattice.pixels_in(size, box.min, box.max, kBoundarySlack);
}

// A lattice whose spacing puts about kDefaultFitSamples in the box, and at least
// kMinSamplesAcross across its narrow side.
Lattice default_lattice(const ImageSize& size, const PixelBox& box) {
    const Vec2 extent = (box.max - box.min).cwiseMax(1.0);
    const double spacing = std::max(kMinSpacingPx, std::min(std::sqrt(extent.prod() / kDefaultFitSamples),
                                                            extent.minCoeff() / kMinSamplesAcross));
    const auto count = [&](long side) {
        return std::max(2L, static_cast<long>(std::ceil(static_cast<double>(side - 1) / spacing)) + 1);
    };
    return {count(size.width), count(size.height)};
}

Lattice denser(const Lattice& lattice, int factor) {
    return {(lattice.columns - 1) * factor + 1, (lattice.rows - 1) * factor + 1};
}

// The lattice spacing along the finer axis, which the boundary follows.
double lattice_spacing(const ImageSize& size, const Lattice& lattice) {
    // A side of one pixel has a step of 0 and does not count.
    double step = std::numeric_limits<double>::infinity();
    for (const double axis_step : {lattice.step_x(size), lattice.step_y(size)}) {
        if (axis_step > 0.0) step = std::min(step, axis_step);
    }
    return std::isfinite(step) ? step : 1.0;
}

bool pixel_less(const Vec2& a, const Vec2& b) { return std::tie(a.x(), a.y()) < std::tie(b.x(), b.y()); }

// Sorts and removes exact duplicates (a corner shared by two edges, a lattice point on
// the image border), which would otherwise weigh twice in the fit.
void sort_unique(std::vector<Vec2>& points) {
    std::sort(points.begin(), points.end(), pixel_less);
    points.erase(std::unique(points.begin(), points.end()), points.end());
}

// The scene's pixels among `lattice` and the boundary at `spacing`, with their rays.
ScenePixels scene_pixels(const PreparedCamera& source, const Scene& scene, const Lattice& lattice, double spacing) {
    std::vector<Vec2> boundary = scene.boundary(source, spacing);
    sort_unique(boundary);
    std::vector<Vec2> interior = lattice_points(source.camera().size, lattice, scene.bounds(source));
    std::erase_if(interior, [&](const Vec2& p) { return std::binary_search(boundary.begin(), boundary.end(), p, pixel_less); });

    std::vector<Vec2> pixels = boundary;
    pixels.insert(pixels.end(), interior.begin(), interior.end());
    const std::vector<Unprojection> rays = unit_rays(source, pixels);
    ScenePixels out;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        const bool is_boundary = i < boundary.size();
        if (!is_boundary && !scene.contains(pixels[i], rays[i])) continue;
        if (!rays[i].valid) {
            ++out.skipped;
            continue;
        }
        out.pixels.push_back(pixels[i]);
        out.directions.push_back(rays[i].direction);
        if (is_boundary) ++out.boundary_count;
    }
    return out;
}

}  // namespace

Scene Scene::whole_image() { return Scene(); }

Scene Scene::circle(double radius, const Vec2& center) {
    Scene scene;
    scene.shape_ = Shape::Circle;
    scene.radius_ = radius;
    scene.center_ = center;
    return scene;
}

Scene Scene::rectangle(const Vec2& corner0, const Vec2& corner1) {
    Scene scene;
    scene.shape_ = Shape::Rectangle;
    scene.corner0_ = corner0;
    scene.corner1_ = corner1;
    return scene;
}

Scene Scene::field_angle(double max_angle_deg) {
    Scene scene;
    scene.shape_ = Shape::FieldAngle;
    scene.max_angle_deg_ = max_angle_deg;
    return scene;
}

void Scene::validate(const ImageSize& size) const {
    size.validate();
    const PixelBox image = image_box(size);
    switch (shape_) {
        case Shape::WholeImage: return;
        case Shape::Circle: {
            require_finite("scene radius", radius_);
            if (!(radius_ > 0.0)) throw InvalidArgument("scene radius: must be > 0 px (a circle with area), got " + format_number(radius_));
            require_finite_all("scene center", center_);
            if (!inside(image, center_)) {
                throw InvalidArgument("scene center " + point_text(center_) + ": outside " + image_text(size));
            }
            return;
        }
        case Shape::Rectangle: {
            require_finite_all("scene rectangle corner", corner0_);
            require_finite_all("scene rectangle corner", corner1_);
            if (!(corner0_.x() < corner1_.x() && corner0_.y() < corner1_.y())) {
                throw InvalidArgument("scene rectangle " + point_text(corner0_) + " to " + point_text(corner1_) +
                                      ": empty (x0 < x1 and y0 < y1 are required)");
            }
            if (!inside(image, corner0_) || !inside(image, corner1_)) {
                throw InvalidArgument("scene rectangle " + point_text(corner0_) + " to " + point_text(corner1_) +
                                      ": outside " + image_text(size));
            }
            return;
        }
        case Shape::FieldAngle:
            require_finite("scene max angle", max_angle_deg_);
            if (!(max_angle_deg_ > 0.0 && max_angle_deg_ < 180.0)) {
                throw InvalidArgument("scene max angle: must be in (0, 180) degrees, got " + format_number(max_angle_deg_));
            }
            return;
    }
}

std::string Scene::describe(const ImageSize& size) const {
    switch (shape_) {
        case Shape::WholeImage: return "the whole image, " + std::to_string(size.width) + "x" + std::to_string(size.height);
        case Shape::Circle:
            return "circle of radius " + format_number(radius_) + " px around " + point_text(center_);
        case Shape::Rectangle: return "rectangle " + point_text(corner0_) + " to " + point_text(corner1_);
        case Shape::FieldAngle: return "rays within " + format_number(max_angle_deg_) + " deg of the optical axis";
    }
    return "";
}

bool Scene::contains(const Vec2& pixel, const Unprojection& ray) const {
    switch (shape_) {
        case Shape::WholeImage: return true;
        case Shape::Circle: return (pixel - center_).squaredNorm() <= radius_ * radius_ * (1.0 + kBoundarySlack);
        case Shape::Rectangle: return inside({corner0_, corner1_}, pixel);
        case Shape::FieldAngle:
            return ray.valid &&
                   angle_between(ray.direction, Vec3::UnitZ()) <= radians_from_degrees(max_angle_deg_) + kBoundarySlack;
    }
    return false;
}

std::vector<Vec2> Scene::cone_pixels(const PreparedCamera& source, int count, bool* complete) const {
    const double angle = radians_from_degrees(max_angle_deg_);
    std::vector<Vec3> directions;
    for (const Vec2& azimuth : circle_points(Vec2::Zero(), 1.0, count)) {
        directions.emplace_back(std::sin(angle) * azimuth.x(), std::sin(angle) * azimuth.y(), std::cos(angle));
    }
    std::vector<Vec2> pixels;
    bool all = true;
    for (const Projection& projection : source.project_camera_points(directions)) {
        if (projection.valid) pixels.push_back(projection.pixel);
        all = all && projection.valid;
    }
    if (complete != nullptr) *complete = all;
    return pixels;
}

PixelBox Scene::bounds(const PreparedCamera& source) const {
    const PixelBox image = image_box(source.camera().size);
    const auto clamp_to_image = [&](PixelBox box) {
        return PixelBox{box.min.cwiseMax(image.min).cwiseMin(image.max), box.max.cwiseMax(image.min).cwiseMin(image.max)};
    };
    switch (shape_) {
        case Shape::WholeImage: return image;
        case Shape::Circle: return clamp_to_image({center_.array() - radius_, center_.array() + radius_});
        case Shape::Rectangle: return {corner0_, corner1_};
        case Shape::FieldAngle: {
            // Where a direction of the cone has no pixel, the scene runs on to the edge
            // of the lens's domain: only the whole image bounds it then.
            bool complete = false;
            const std::vector<Vec2> cone = cone_pixels(source, kConeProbeCount, &complete);
            if (!complete || cone.empty()) return image;
            PixelBox box{cone.front(), cone.front()};
            for (const Vec2& p : cone) {
                box.min = box.min.cwiseMin(p);
                box.max = box.max.cwiseMax(p);
            }
            // The curve bulges a little between the probes.
            const Vec2 margin = (box.max - box.min) * kConeBoxMargin;
            return clamp_to_image({box.min - margin, box.max + margin});
        }
    }
    return image;
}

std::vector<Vec2> Scene::boundary(const PreparedCamera& source, double spacing) const {
    const PixelBox image = image_box(source.camera().size);
    std::vector<Vec2> edge;
    switch (shape_) {
        case Shape::WholeImage: return polygon_points(box_corners(image), spacing);
        case Shape::Rectangle: return polygon_points(box_corners({corner0_, corner1_}), spacing);
        case Shape::Circle: {
            const double wanted = std::ceil(2.0 * std::numbers::pi * radius_ / spacing);
            const int count = std::max(kMinCurvePoints, static_cast<int>(std::min(wanted, kMaxCurvePoints)));
            edge = circle_points(center_, radius_, count);
            break;
        }
        case Shape::FieldAngle: {
            const std::vector<Vec2> probe = cone_pixels(source, kConeProbeCount);
            const double length = polyline_length(probe);
            const double wanted = std::ceil(length / spacing);
            edge = cone_pixels(source, std::max(kConeProbeCount, static_cast<int>(std::min(wanted, kMaxCurvePoints))));
            break;
        }
    }
    std::erase_if(edge, [&](const Vec2& p) { return !inside(image, p); });
    // The image border cuts a circle or a cone that reaches past it.
    const std::vector<Vec2> border = polygon_points(box_corners(image), spacing);
    const std::vector<Unprojection> rays = unit_rays(source, border);
    for (std::size_t i = 0; i < border.size(); ++i) {
        if (contains(border[i], rays[i])) edge.push_back(border[i]);
    }
    return edge;
}

std::vector<Vec2> Scene::outline(const PreparedCamera& source) const {
    constexpr int kOutlinePoints = 256;
    std::vector<Vec2> curve;
    switch (shape_) {
        case Shape::WholeImage: curve = box_corners(image_box(source.camera().size)); break;
        case Shape::Rectangle: curve = box_corners({corner0_, corner1_}); break;
        case Shape::Circle: curve = circle_points(center_, radius_, kOutlinePoints); break;
        case Shape::FieldAngle: curve = cone_pixels(source, kOutlinePoints); break;
    }
    if (!curve.empty()) curve.push_back(curve.front());
    return curve;
}

SceneSampling sample_scene(const PreparedCamera& source, const Scene& scene, std::optional<Lattice> lattice) {
    scene.validate(source.camera().size);
    SceneSampling sampling;
    sampling.fit_lattice = lattice.value_or(default_lattice(source.camera().size, scene.bounds(source)));
    if (sampling.fit_lattice.columns < 2 || sampling.fit_lattice.rows < 2) {
        throw InvalidArgument("sampling lattice: needs at least 2x2 points, got " +
                              std::to_string(sampling.fit_lattice.columns) + "x" + std::to_string(sampling.fit_lattice.rows));
    }
    sampling.check_lattice = denser(sampling.fit_lattice, kCheckDensity);
    const double spacing = lattice_spacing(source.camera().size, sampling.fit_lattice);
    sampling.fit = scene_pixels(source, scene, sampling.fit_lattice, spacing);
    sampling.check = scene_pixels(source, scene, sampling.check_lattice, spacing / kCheckDensity);
    if (sampling.fit.pixels.empty() || sampling.check.pixels.empty()) {
        throw InvalidArgument("scene " + scene.describe(source.camera().size) + ": no pixel of it has a ray through the source camera (" +
                              std::to_string(sampling.check.skipped) + " without one)");
    }
    return sampling;
}

}  // namespace libcam
