#pragma once
// 3D Gaussian Splatting's cameras.json (graphdeco-inria/gaussian-splatting writes it with
// camera_to_JSON in utils/camera_utils.py): a JSON list, one item per training camera,
//
//   id, img_name, width, height, fx, fy   the camera's number, image, size and focal lengths
//   position   the camera's centre in the world
//   rotation   3 rows of 3: the camera-to-world rotation, row by row, with OpenCV's (and
//              COLMAP's) camera axes
//
// camera_to_JSON builds the world-to-camera [R^T | T] from its Camera's R (which 3DGS keeps
// transposed: the camera-to-world rotation) and T (COLMAP's tvec), inverts it, and stores
// the inverse's rotation (R, the camera-to-world) and translation (the centre). So
// libcam's pose is x_cam = rotation^T (X - position).
//
// No principal point is stored: 3DGS projects with a symmetric frustum (getProjectionMatrix)
// and its rasterizer turns NDC into pixels with ndc2Pix(v, S) = ((v + 1) S - 1) / 2, its
// pixel i being at coordinate i (forward.cu's pixf), so the optical axis (v = 0) falls at
// ((W - 1) / 2, (H - 1) / 2) in OpenCV's pixels, and a pixel per NDC unit is W / 2, which
// makes fx = W / (2 tan(FoVx / 2)) the focal length, as fov2focal stores it. There is no
// distortion: every camera is a pinhole.
//
// Reading gives one camera per item, named by its img_name.

#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> read_gs_cameras(std::string_view text, const ReadContext& context);

// Whether a parsed JSON file is 3DGS's cameras.json: a list whose first item has
// "img_name" and "fx".
bool claims_gs_cameras(const DocumentNode& root);

}  // namespace libcam
