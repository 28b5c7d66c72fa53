#pragma once
// The camera to turn a lens's images into, chosen for the user: a pinhole (square
// pixels, principal point at the image centre, so also a field-of-view camera a renderer
// takes) or, for a lens that sees more than a pinhole can hold, an equirectangular
// LONLAT camera (mrcal's: longitude along x, latitude along y, square pixels per radian)
// or a CYLINDRICAL one (longitude along x, tan(latitude) along y: straight verticals).
//
//   const NewCamera chosen = choose_new_camera(PreparedCamera(fisheye), NewCameraRequest{});
//   chosen.camera  // the pinhole;  chosen.why  // what was chosen and why, in a sentence
//
// What it keeps:
//   Keep::Valid  every target pixel has a source pixel, at least half a pixel inside the
//                source image ("no black borders"): the widest such view (for a pinhole,
//                no wider than kWidestPinholeDeg across its diagonal);
//   Keep::All    every source pixel that has a ray lands on the target image
//                ("everything the lens saw"): the narrowest such view;
//   a field of view on an axis (horizontal, vertical or diagonal, edge to edge).
// It works from the lens's real valid region (the rays the batch engine gives each pixel
// and the source lens's domain), so the result is never NaN nor degenerate: where a
// request cannot be met it throws InvalidArgument saying why. The target keeps the
// source's centre and, turned by `rotation`, its axes.

#include <functional>
#include <optional>
#include <string>

#include "libcam/camera/camera.hpp"
#include "libcam/graphics/look_at_camera.hpp"

namespace libcam {

enum class Keep { Valid, All };

struct NewCameraRequest {
    // PINHOLE, LONLAT or CYLINDRICAL. A pinhole asked to keep everything of a lens that
    // sees more than kWidestPinholeDeg across, or a cylinder asked to keep everything of
    // one that sees more than half of it above or below the horizon, becomes LONLAT
    // (NewCamera::why says so).
    LensType model = LensType::Pinhole;
    std::optional<Keep> keep = Keep::Valid;  // nullopt: fov_deg says the view
    double fov_deg = 0;                      // with keep = nullopt: the view on fov_axis
    FovAxis fov_axis = FovAxis::Horizontal;  // Horizontal, Vertical or (pinhole) Diagonal
    std::optional<ImageSize> size;           // default: the source's size
    Mat3 rotation = Mat3::Identity();        // the target's axes relative to the source's (remap_map.hpp)
    int threads = 1;
};

// The widest pinhole target chosen: a pinhole's edges stretch without bound towards 180
// degrees. Keep::Valid stops at this angle across the diagonal (and a cylinder at it
// from top to bottom); Keep::All of a lens that sees past half of it off the axis (for a
// cylinder, above or below the horizon) becomes LONLAT.
inline constexpr double kWidestPinholeDeg = 150.0;

struct NewCamera {
    Camera camera;
    std::string why;
};

NewCamera choose_new_camera(const PreparedCamera& source, const NewCameraRequest& request);

// The smallest scale f >= `widest` (the widest view: the smallest f) for which passes(f)
// holds, to 1e-12 relative, by bisection on log f: a larger f sees a narrower view, inside a
// wider one that passed, where the region that passes is star-shaped about the view's centre
// (a lens's valid region is). The search starts from `start` (doubling it until it passes);
// throws InvalidArgument(`nothing_passes`) when sixty doublings never pass.
double smallest_passing_scale(double widest, double start, const std::function<bool(double)>& passes,
                              const std::string& nothing_passes);

// The largest angle (radians) between the optical axis and the ray of any pixel of the
// lens (exact unprojection of every pixel). Throws InvalidArgument when no pixel has one.
double widest_ray_angle(const PreparedCamera& lens, int threads = 1);

// The margins, in whole pixels, to render around `render` (a camera of a renderer, whose
// axes are the lens's turned by `rotation`: d_render = rotation d_lens) so that the
// render, distorted to the lens (the map from the lens to the render with the margins),
// gives every pixel of the lens that has a ray a source on the span of the render's pixel
// centres: compositing's overscan. Zero on a side the render already covers. The render
// with them is padded(render, left, top, right, bottom) (derived_camera.hpp). Throws
// InvalidArgument when no margin can do it: a lens pixel's ray behind the render's
// camera or past its lens's domain, or further out than twice the render's size beyond
// an edge (give the render a wider view).
struct Overscan {
    long left = 0, top = 0, right = 0, bottom = 0;
};
Overscan overscan_for(const PreparedCamera& lens, const Camera& render, const Mat3& rotation = Mat3::Identity(),
                      int threads = 1);

}  // namespace libcam
