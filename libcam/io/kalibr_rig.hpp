#pragma once
// A rig's cameras as one Kalibr camchain file (the single camera is a row of the format
// table: camera_file.hpp's format_camera with CameraFormat::Kalibr).

#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"

namespace libcam {

// Cameras of one rig as one Kalibr camchain (cam0, cam1, ...): each but the first placed
// from the one before it (T_cn_cnm1, from their poses), the first's pose not written (the
// rig's frame). Throws NotRepresentable, naming the model, for a camera Kalibr has no model
// for (it holds pinhole cameras with radtan (OPENCV4), equidistant (FISHEYE) or no
// distortion, and omni, ds and eucm).
std::string format_kalibr_rig(const std::vector<Camera>& cameras);

}  // namespace libcam
