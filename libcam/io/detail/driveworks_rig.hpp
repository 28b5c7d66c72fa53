#pragma once
// NVIDIA DriveWorks' rig file (rig.json), the cameras of its sensors:
//
//   {"rig": {"sensors": [
//     {"name": "camera:front:wide:120fov", "protocol": "camera.gmsl",
//      "properties": {"Model": "ftheta", "cx": "1919.420", "cy": "1078.106",
//                     "width": "3848", "height": "2168",
//                     "polynomial": "0 0.000538 2.356e-09 1.907e-12 1.204e-16",
//                     "polynomial-type": "pixeldistance-to-angle",
//                     "linear-c": "1.0", "linear-d": "0.0", "linear-e": "0.0"},
//      "nominalSensor2Rig_FLU": {"roll-pitch-yaw": [0.130, 0.468, -0.714], "t": [1.697, -0.010, 1.443]},
//      "correction_sensor_R_FLU": {"roll-pitch-yaw": [...]}, "correction_rig_T": [...]}, ...]}}
//
// DriveWorks writes the properties as strings; numbers are taken too. Older rigs give the
// backward polynomial as "bw-poly" (no "polynomial-type"). The lens: libcam's FTHETA
// (lens/ftheta.hpp) with K's fx = fy = f = 1 / b1 and k_i = b_i f^i, the polynomial
// b0 + b1 p + ... + b5 p^5 giving the angle (radians) at p pixels from (cx, cy) on the
// sensor, after the affine [c d; e 1] that takes the sensor offset to the pixel offset;
// b0 must be 0; max_angle is pi (a rig holds none: the polynomial's own reach bounds the
// domain). A forward polynomial ("angle-to-pixeldistance": a0 + a1 t + ... + a5 t^5 pixels
// at the angle t) is FTHETA_FORWARD (lens/ftheta_forward.hpp) with f = a1 and k_i = a_i / f.
// Pixel centres: the first pixel's
// centre is (0, 0), as OpenCV's (NCore's FThetaCameraModelParameters say so of the
// principal point DriveWorks calibrates).
//
// Pose: nominalSensor2Rig_FLU places the sensor in the rig's frame, FLU (x forward, y left,
// z up; the origin on the ground below the middle of the rear axle), roll-pitch-yaw in
// degrees and t in metres: X_rig = R X_sensor + t with R = Rz(yaw) Ry(pitch) Rx(roll) (scipy's
// Rotation.from_euler("xyz", [roll, pitch, yaw], degrees=True), as NVIDIA's tools read
// it). The sensor frame is FLU too: a camera's optical axis is its x, its image's right
// -y, its image's down -z, so OpenCV's camera axes (x right, y down, z forward) are
// X_sensor = S X_cam with S = [0 0 1; -1 0 0; 0 -1 0]. correction_sensor_R_FLU turns the
// sensor after the nominal rotation (R = R_nominal R_correction) and correction_rig_T adds
// to t, as NVIDIA's tools apply them. libcam's pose is rig to camera, the rig's frame the
// world: R_world_to_cam = (R S)^T, t = -(R S)^T t_rig.
//
// Every camera sensor is read (protocol "camera.*", or a sensor with a "Model" in its
// properties); other sensors (lidar, radar, IMU, CAN) are skipped. A camera whose Model
// is not ftheta is refused, naming it. Names: each sensor's "name".
//
// Written as one camera sensor (WriteOptions::camera_name, protocol camera.virtual) from an
// FTHETA or FTHETA_FORWARD camera without skew and with max_angle = pi: f = fy, c and d
// times fx / fy (the affine absorbs fx != fy, as NCore's transform does), the polynomial
// b_i = k_i / f^i (backward) or a_i = k_i f (forward).

#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> parse_driveworks_rig(std::string_view text, const std::string& source);
std::string format_driveworks_rig(const Camera& camera, const WriteOptions& options);

// Whether a parsed JSON file is a DriveWorks rig: a "rig" map with "sensors".
bool claims_driveworks_rig(const DocumentNode& root);

}  // namespace libcam
