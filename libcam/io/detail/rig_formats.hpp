#pragma once
// Calibration files of other tools that hold a rig: several cameras, each with its pose
// in the rig's reference frame. Each reader returns every camera, in the file's order,
// with poses world-to-camera (X_cam = R X + t) where the "world" is the file's reference
// frame:
//
//   Kalibr camchain / camchain-imucam YAML (also as OpenVINS ships it, with a %YAML:1.0
//   line): keys cam0, cam1, ... each with camera_model (pinhole, omni, ds, eucm),
//   distortion_model (radtan, equidistant, fov, none), intrinsics, distortion_coeffs,
//   resolution. The world is the IMU frame: T_cam_imu as it is, T_imu_cam (OpenVINS)
//   inverted; a file without either is in cam0's frame, each later camera placed by
//   T_cn_cnm1 (camera n from camera n-1). Names: the keys (cam0, ...).
//
//   basalt calibration JSON (cereal's "value0"): T_imu_cam (camera to IMU, a quaternion
//   and a position: inverted), intrinsics with camera_type pinhole, kb4, ds, eucm, ucm,
//   fov or pinhole-radtan8, resolution. The world is the IMU frame. Names: cam0, cam1, ...
//   by position. basalt's ucm is libcam's UCM with xi = alpha / (1 - alpha) and the focal
//   lengths divided by (1 - alpha).
//
//   camodocal YAML (VINS-Mono and VINS-Fusion): model_type PINHOLE, MEI or
//   KANNALA_BRANDT with its projection_parameters, distortion_parameters and
//   mirror_parameters, image_width and image_height. One camera, no pose (identity).
//   Name: camera_name.
//
//   EuRoC (ASL) dataset sensor.yaml of a camera: sensor_type camera, camera_model
//   pinhole, distortion_model radial-tangential (OPENCV4) or equidistant (FISHEYE),
//   intrinsics fu fv cu cv, distortion_coefficients, resolution, and T_BS (the camera in
//   the body frame, inverted: the world is the body, the IMU). Name: comment.
//
// Each throws FileError naming the file, the line (YAML), the key and the value.

#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> parse_kalibr_camchain(std::string_view text, const std::string& source);
std::vector<NamedCamera> parse_basalt_calibration(std::string_view text, const std::string& source);
std::vector<NamedCamera> parse_camodocal(std::string_view text, const std::string& source);
std::vector<NamedCamera> parse_euroc_sensor(std::string_view text, const std::string& source);

// A Kalibr camchain of one camera, cam0: camera_model and distortion_model from the lens
// model's Kalibr names, intrinsics (the model's leading coefficients, then fu fv pu pv),
// distortion_coeffs, resolution, and T_cam_imu (the pose: the world is the IMU frame).
// Numbers as PyYAML (Kalibr's reader) reads floats. Throws NotRepresentable for skew
// and for a model Kalibr lacks.
std::string format_kalibr_camchain(const Camera& camera, const WriteOptions& options);

// basalt's calibration JSON of one camera, cam0, as basalt's loader (cereal) reads it:
// T_imu_cam (the inverse of the pose: the world is the IMU frame), intrinsics with the
// table's camera_type (OPENCV4 and OPENCV5 as pinhole-radtan8 with the higher terms 0, UCM
// in basalt's parametrisation), resolution, and the IMU fields basalt requires with the
// values its own camera-only calibration writes (no bias, 200 Hz, basalt's default noise).
// No rpmax for pinhole-radtan8: basalt estimates it. Throws NotRepresentable for skew and
// for a model basalt lacks.
std::string format_basalt_calibration(const Camera& camera, const WriteOptions& options);

// What a YAML or JSON file's keys say it is, for a file whose extension is shared by
// several formats: Kalibr (a camN key holding camera_model), camodocal (model_type),
// basalt (value0). nullopt: none of these (OpenCV's YAML, libcam's JSON).
bool claims_kalibr_camchain(const DocumentNode& root);
bool claims_basalt_calibration(const DocumentNode& root);
bool claims_camodocal(const DocumentNode& root);
bool claims_euroc_sensor(const DocumentNode& root);

}  // namespace libcam
