#include "libcam/remap/render_plan.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "libcam/convert/blender_camera.hpp"
#include "libcam/error.hpp"
#include "libcam/remap/derived_camera.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Pixels beyond the lens's widest ray inside the fisheye render's image circle: Blender
// renders black past the circle, and an interpolating warp reads a pixel's neighbours.
constexpr double kFisheyeMarginPx = 3.0;

std::size_t pixel_count(const ImageSize& size) {
    return static_cast<std::size_t>(size.width) * static_cast<std::size_t>(size.height);
}

std::string size_text(const ImageSize& size) { return std::to_string(size.width) + "x" + std::to_string(size.height); }

bool blender_draws(const Camera& camera) {
    try {
        blender_from_camera(camera);
        return true;
    } catch (const InvalidArgument&) {
        return false;
    }
}

// The pinhole with the lens's focal lengths and principal point, with its margins; or
// nothing (and why) when no margin holds the lens.
struct PinholeRender {
    Camera camera;
    Overscan margins;
};
std::optional<PinholeRender> pinhole_render(const PreparedCamera& lens, int threads, std::string& why_not) {
    const Camera& source = lens.camera();
    Camera pinhole;
    pinhole.size = source.size;
    pinhole.intrinsics = {source.intrinsics.fx, source.intrinsics.fy, source.intrinsics.cx, source.intrinsics.cy, 0.0};
    pinhole.lens = {LensType::Pinhole, {}};
    pinhole.pose = source.pose;
    try {
        const Overscan margins = overscan_for(lens, pinhole, Mat3::Identity(), threads);
        return PinholeRender{padded(pinhole, margins.left, margins.top, margins.right, margins.bottom), margins};
    } catch (const InvalidArgument&) {
        why_not = "a pinhole cannot hold its rays with any margin";
        return std::nullopt;
    }
}

// Blender's equidistant fisheye whose image circle holds every ray of the lens.
Camera fisheye_render(const Camera& source, double widest_angle) {
    double f = std::max(source.intrinsics.fx, source.intrinsics.fy);  // pixels per radian
    const double half_view = std::min(widest_angle + kFisheyeMarginPx / f, std::numbers::pi);
    const double side_px = std::ceil(2.0 * half_view * f);
    f = std::max(f, side_px / (2.0 * std::numbers::pi));  // its field of view is at most 360 degrees
    Camera fisheye;
    fisheye.size = {static_cast<long>(side_px), static_cast<long>(side_px)};
    fisheye.intrinsics = {f, f, fisheye.size.centre_x(), fisheye.size.centre_y(), 0.0};
    fisheye.lens = {LensType::Fisheye, {0.0, 0.0, 0.0, 0.0}};
    fisheye.pose = source.pose;
    return fisheye;
}

}  // namespace

RenderPlan plan_render(const PreparedCamera& lens, int threads) {
    const Camera& source = lens.camera();
    const std::string model(lens_info(source.lens.type).name);
    if (blender_draws(source)) {
        return {source, false, {}, "Blender draws " + model + " as it is: render with the lens's own camera"};
    }
    const double widest = widest_ray_angle(lens, threads);

    std::string pinhole_why_not;
    const std::optional<PinholeRender> pinhole = pinhole_render(lens, threads, pinhole_why_not);
    const Camera fisheye = fisheye_render(source, widest);
    const std::string sees = "the lens (" + model + ") sees rays up to " + format_short(widest / kDegree, 4) +
                             " degrees off its axis";
    if (pinhole && pixel_count(pinhole->camera.size) <= pixel_count(fisheye.size)) {
        const Overscan& m = pinhole->margins;
        return {pinhole->camera, true, m,
                sees + ": a pinhole with its focal lengths and principal point, " + size_text(pinhole->camera.size) +
                    " (margins left " + std::to_string(m.left) + ", top " + std::to_string(m.top) + ", right " +
                    std::to_string(m.right) + ", bottom " + std::to_string(m.bottom) +
                    " px around its image), gives every pixel of the lens a source"};
    }
    const std::string instead = pinhole ? "a pinhole would need " + size_text(pinhole->camera.size) + " pixels"
                                        : pinhole_why_not;
    return {fisheye, true, {},
            sees + " and " + instead + ": Blender's equidistant fisheye, " + size_text(fisheye.size) + " at " +
                format_short(fisheye.intrinsics.fx, 6) + " px per radian, " +
                format_short(fisheye.size.width / fisheye.intrinsics.fx / kDegree, 4) +
                " degrees across its image circle, gives every pixel of the lens a source"};
}

}  // namespace libcam
