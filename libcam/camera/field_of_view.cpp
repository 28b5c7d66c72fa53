#include "libcam/camera/field_of_view.hpp"

#include <algorithm>
#include <cmath>

#include "libcam/camera/unprojector.hpp"
#include "libcam/geometry/pixel_grid.hpp"
#include "libcam/geometry/vector_math.hpp"

namespace libcam {

namespace {

// Steps along a line from an edge towards the other when the edge has no ray.
constexpr int kEdgeSteps = 1024;

// The rays here come from an engine with a coarse table of its own. The camera's own
// (PreparedCamera::unproject) tabulates 384 nodes along the image's longer side, each
// solved and checked, for batches of millions of pixels: about 0.1 s for the few thousand
// pixels asked here, and seconds for a lens whose solver fails on many nodes. The exact
// method certifies each ray to the full solver's tolerance whatever its start
// (unprojector.hpp), and which pixels have a ray is the same on every lens of the test set
// and every real file tried. Only a lens the solver cannot invert everywhere (tangential
// terms near 1) has rays found from some starts and not from others, with either table:
// there the share of pixels without one can differ by a few tenths of a percent.
constexpr UnprojectorOptions kFewPixels{.table_nodes = 32, .threads = 1};

struct EdgeRay {
    Vec3 direction = Vec3::UnitZ();
    bool at_edge = false;
    bool found = false;
};

// The ray through `from`, or through the first point on the way to `to` that has one.
EdgeRay edge_ray(const Unprojector<double>& rays, const Vec2& from, const Vec2& to) {
    for (int i = 0; i <= kEdgeSteps; ++i) {
        const Vec2 pixel = from + (to - from) * (static_cast<double>(i) / kEdgeSteps);
        Vec3 direction;
        if (rays.unproject(pixel, UnprojectMethod::Exact, direction)) return {direction.normalized(), i == 0, true};
    }
    return {};
}

// The angle between the rays through a line's two ends, through the optical axis: the
// sum of their angles from the axis when they lie on its two sides (the signed
// coordinate `side` along the line tells), the difference otherwise.
AxisFieldOfView across(const Unprojector<double>& rays, const Vec2& low, const Vec2& high, int axis) {
    const EdgeRay a = edge_ray(rays, low, high), b = edge_ray(rays, high, low);
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
    const Unprojector<double> rays(camera, kFewPixels);
    FieldOfView fov;
    fov.horizontal = across(rays, {-0.5, row}, {width - 0.5, row}, 0);
    fov.vertical = across(rays, {column, -0.5}, {column, height - 0.5}, 1);
    fov.valid_angle_deg = degrees_from_radians(camera.valid_angle());
    const std::vector<Vec2> lattice = PixelGrid{64, 64}.pixels(c.size);
    std::vector<Unprojection> lattice_rays(lattice.size());
    rays.unproject(lattice, UnprojectMethod::Exact, lattice_rays);
    const auto rayless =
        std::count_if(lattice_rays.begin(), lattice_rays.end(), [](const Unprojection& u) { return !u.valid; });
    fov.rayless_fraction = static_cast<double>(rayless) / static_cast<double>(lattice_rays.size());
    return fov;
}

}  // namespace libcam
