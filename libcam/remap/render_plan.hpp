#pragma once
// Rendering through a real lens that the renderer cannot draw: the camera to render with,
// and the map that turns its render into the lens's image.
//
//   const PreparedCamera lens(calibration);
//   const RenderPlan plan = plan_render(lens);
//   // render with plan.render (format_blender_script), then
//   const RemapMap warp = build_remap_map(lens, PreparedCamera(plan.render));
//   cv::Mat photo_like = remap_image(render, warp, Interpolation::Cubic);  // interop/image_remap.hpp
//
// The render camera, in this order:
//   1. the lens itself, when Blender draws it as it is (blender_from_camera: PINHOLE,
//      FISHEYE with zero coefficients, EQUISOLID, FISHEYE_LENS_POLYNOMIAL, LONLAT):
//      nothing to warp;
//   2. a pinhole with the lens's focal lengths and principal point (its distortion and
//      skew left to the warp) and the least overscan margins around it that give every
//      lens pixel with a ray a source (overscan_for): the render is as sharp as the lens
//      at its centre and a perspective render, which every Blender engine draws;
//   3. Blender's equidistant fisheye (FISHEYE with zero coefficients, square pixels, a
//      square image centred on the axis) at the larger of the lens's fx and fy pixels per
//      radian, its image circle just wider than the lens's widest ray: when a pinhole
//      cannot hold the lens (rays at or past 90 degrees, margins past twice its size) or
//      would need more pixels than this fisheye.
// The render has the lens's pose: the scene renders from where the lens stands.

#include <string>

#include "libcam/camera/camera.hpp"
#include "libcam/remap/new_camera.hpp"

namespace libcam {

struct RenderPlan {
    Camera render;
    bool needs_warp = true;  // false: the lens itself is the render camera
    Overscan margins;        // of a pinhole render (step 2), around the lens's own image
    std::string why;         // what was chosen and why, in a sentence
};

// Throws InvalidArgument when no pixel of the lens has a ray.
RenderPlan plan_render(const PreparedCamera& lens, int threads = 1);

}  // namespace libcam
