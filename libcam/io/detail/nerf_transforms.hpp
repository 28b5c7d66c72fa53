#pragma once
// NeRF's transforms.json, as NeRF's synthetic scenes, instant-ngp and nerfstudio write it.
//
// Intrinsics, at the top level and overridden per frame:
//   w, h                 the image size (NeRF's synthetic scenes leave it out: then
//                        ReadOptions::size, or the first frame's image, or a refusal)
//   fl_x, fl_y, cx, cy   the focal lengths and principal point, in pixels whose (0, 0) is
//                        the image's top-left corner (as COLMAP's): libcam's cx is cx - 0.5
//   camera_angle_x/_y    the field of view from image edge to image edge, used where
//                        fl_x/fl_y are not given: fx = w / (2 tan(angle / 2)); without
//                        cx, cy the principal point is the image centre ((w - 1) / 2 in
//                        libcam's pixels, where Blender rendered NeRF's synthetic scenes),
//                        or on request (NerfPrincipalPoint::HalfSize) w / 2, where NeRF's own
//                        ray code puts it
//   camera_model         OPENCV (the default; k1 k2 p1 p2 and k3: OPENCV4 or OPENCV5, PINHOLE
//                        when they are all 0; nerfstudio's k4 multiplies r^8, which OpenCV's
//                        models do not have, so a k4 that is not 0 is refused), PINHOLE,
//                        SIMPLE_PINHOLE, OPENCV_FISHEYE (k1..k4: FISHEYE, as COLMAP's), or
//                        EQUIRECTANGULAR (nerfstudio's: LONLAT with libcam's fx = fl_x / pi)
//
// Poses: each frame's transform_matrix is camera-to-world with OpenGL's camera axes (x
// right, y up, z backwards); libcam's pose is its inverse with OpenCV's axes. Rotations
// printed in float32 are read as the nearest rotation (geometry/pose.hpp).
//
// Reading gives one camera per frame, named by its file_path; a file without frames
// gives one camera without a pose. Writing gives one frame (WriteOptions::image_name)
// with fl_x, fl_y, cx, cy, w, h, the camera_angle_x/_y NeRF's own code reads, and the
// coefficients: PINHOLE, the OPENCV models up to k3 (higher ones when their extra
// coefficients are 0), FISHEYE and LONLAT; skew is refused.

#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> read_nerf_transforms(std::string_view text, const ReadContext& context);
std::string write_nerf_transforms(const Camera& camera, const WriteOptions& options);

// Whether a parsed JSON file is a transforms.json: an object with "frames", "camera_angle_x" or
// "fl_x" and without libcam's "K".
bool claims_nerf_transforms(const DocumentNode& root);

}  // namespace libcam
