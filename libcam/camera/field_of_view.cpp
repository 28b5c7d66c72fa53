#include "libcam/camera/field_of_view.hpp"

#include <algorithm>
#include <cmath>

#include "libcam/geometry/pixel_grid.hpp"
#include "libcam/geometry/vector_math.hpp"

namespace libcam {

namespace {

// Steps along a line from an edge towards the other when the edge has no ray.
constexpr int kEdgeSteps = 1024;

struct EdgeRay {
    Vec3 direction = Vec3::UnitZ();
    bool at_edge = false;
    bool found = false;
};

// The ray through `from`, or through the first point on the way to `to` that has one.
EdgeRay edge_ray(const PreparedCamera& camera, const Vec2& from, const Vec2& to) {
    for (int i = 0; i <= kEdgeSteps; ++i) {
        const Vec2 pixel = from + (to - from) * (static_cast<double>(i) / kEdgeSteps);
        const Unprojection ray = camera.unproject(pixel);
        if (ray.valid) return {ray.direction.normalized(), i == 0, true};
    }
    return {};
}

// The angle between the rays through a line's two ends, through the optical axis: the
// sum of their angles from the axis when they lie on its two sides (the signed
// coordinate `side` along the line tells), the difference otherwise.
AxisFieldOfView across(const PreparedCamera& camera, const Vec2& low, const Vec2& high, int axis) {
    const EdgeRay a = edge_ray(camera, low, high), b = edge_ray(camera, high, low);
    if (!a.found || !b.found) return {0.0, false};
    const double angle_a = angle_between(a.direction, Vec3::UnitZ());
    const double angle_b = angle_between(b.direction, Vec3::UnitZ());
    const bool opposite = (a.direction(axis) <= 0.0) != (b.direction(axis) <= 0.0);
    const double angle = opposite ? angle_a + angle_b : std::abs(angle_a - angle_b);
    return {degrees_from_radians(angle), a.at_edge && b.at_edge};
}

}  // namespace

FieldOfView field_of_view(const PreparedCamera& camera) {
    const Camera& c = camera.camera();
    const double width = c.size.width, height = c.size.height;
    const double row = std::clamp(c.intrinsics.cy, -0.5, height - 0.5);
    const double column = std::clamp(c.intrinsics.cx, -0.5, width - 0.5);
    FieldOfView fov;
    fov.horizontal = across(camera, {-0.5, row}, {width - 0.5, row}, 0);
    fov.vertical = across(camera, {column, -0.5}, {column, height - 0.5}, 1);
    fov.valid_angle_deg = degrees_from_radians(camera.valid_angle());
    const std::vector<Vec2> lattice = PixelGrid{64, 64}.pixels(c.size);
    const std::vector<Unprojection> rays = camera.unproject(lattice);
    const auto rayless = std::count_if(rays.begin(), rays.end(), [](const Unprojection& u) { return !u.valid; });
    fov.rayless_fraction = static_cast<double>(rayless) / static_cast<double>(rays.size());
    return fov;
}

}  // namespace libcam
