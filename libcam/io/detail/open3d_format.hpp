#pragma once
// Open3D's camera JSON, as open3d.io.write_pinhole_camera_intrinsic,
// write_pinhole_camera_parameters and write_pinhole_camera_trajectory write it:
//
//   PinholeCameraIntrinsic    {"width", "height", "intrinsic_matrix": 9 numbers}
//   PinholeCameraParameters   {"class_name": "PinholeCameraParameters",
//                              "intrinsic": {...}, "extrinsic": 16 numbers, ...}
//   PinholeCameraTrajectory   {"class_name": "PinholeCameraTrajectory",
//                              "parameters": [PinholeCameraParameters...]}
//
// Matrices are Eigen's column-major order: intrinsic_matrix is fx 0 0  s fy 0  cx cy 1,
// the extrinsic column by column. The extrinsic is world to camera (X_cam = R X + t),
// libcam's direction, with OpenCV's axes; pixel centres are at integers (Open3D's default
// camera has cx = 319.5 in a 640-pixel image), as in libcam. A pinhole only: Open3D's
// cameras have no distortion. A trajectory's cameras are named by their position.
//
// Written as PinholeCameraParameters (which holds the pose); a distorted lens is refused.

#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> parse_open3d_camera(std::string_view text, const std::string& source);
std::string format_open3d_camera(const Camera& camera, const WriteOptions& options);

// Whether a parsed JSON file is Open3D's: intrinsic_matrix at the top, or Open3D's class_name.
bool claims_open3d_camera(const DocumentNode& root);

}  // namespace libcam
