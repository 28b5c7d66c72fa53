#pragma once
// LLFF's poses_bounds.npy (Fyusion/LLFF's imgs2poses.py writes it from a COLMAP model;
// NeRF's load_llff.py and most NeRF and Gaussian-splatting code read it): a numpy .npy
// array of N rows of 17 float64, one row per image in the order of the images' names:
//
//   15 numbers   a 3x5 matrix, row by row: [R | c | hwf], R the camera-to-world rotation
//                whose columns are the camera's [down, right, backwards] axes, c the
//                camera's centre in COLMAP's world, hwf the column (H, W, focal) in pixels
//   2 numbers    near and far: the depths of the scene's points seen (not read)
//
// Axes: LLFF's pose_utils.py reorders COLMAP's camera-to-world columns (x right, y down,
// z forward) as [y, x, -z]; libcam's camera-to-world columns are LLFF's [1, 0, -2], and
// libcam's pose is x_cam = R_cv^T (X - c). NeRF's load_llff.py then recentres and rescales
// the poses for training; the file itself is in COLMAP's world, and so is what libcam reads.
//
// Intrinsics: one focal length (COLMAP's first parameter), no principal point, no
// distortion. imgs2poses ran COLMAP with its principal point at the image centre, which
// is ((W - 1) / 2, (H - 1) / 2) in OpenCV's pixels (libcam's default); NeRF's ray code
// (get_rays_np: pixel index i at (i - W / 2) / focal) puts it at (W / 2, H / 2) instead,
// half a pixel off, read on request with NerfPrincipalPoint::HalfSize.
//
// Reading gives one pinhole camera per row, named by its row's number ("0", "1", ...).

#include <string_view>
#include <vector>

#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> read_llff_poses(std::string_view bytes, const ReadContext& context);

}  // namespace libcam
