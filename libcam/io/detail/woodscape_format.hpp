#pragma once
// Valeo's WoodScape calibration JSON (the dataset's calibration/*.json, read by its
// scripts/calibration/projection.py, read_cam_from_json):
//
//   {"extrinsic": {"quaternion": [qx, qy, qz, qw], "translation": [x, y, z]},
//    "intrinsic": {"aspect_ratio": a, "cx_offset": ox, "cy_offset": oy, "height": H,
//                  "k1": k1, "k2": k2, "k3": k3, "k4": k4, "model": "radial_poly",
//                  "poly_order": 4, "width": W},
//    "name": "FV"}
//
// The lens: rho(theta) = k1 theta + k2 theta^2 + k3 theta^3 + k4 theta^4 pixels from the
// principal point, theta the angle from the optical axis, every power (not FISHEYE's odd
// ones): libcam's THETA_POLYNOMIAL with fx = 1 and fy = a (WoodScape multiplies the
// vertical offset alone by the aspect ratio: v = v' a + cy), so the coefficients are the
// file's numbers to the bit.
//
// Pixels: the principal point is the image centre plus the offset, with the top-left pixel
// centre at (0, 0), as OpenCV's: cx = W / 2 + ox - 0.5, cy = H / 2 + oy - 0.5.
//
// Pose: WoodScape's translation and quaternion take camera coordinates to vehicle
// coordinates (X_vehicle = R X_camera + t, its Camera class inverts it to project); the
// quaternion is scipy's Rotation.from_quat order, scalar LAST (x, y, z, w). The vehicle
// frame is ISO 8855's (x forward, y left, z up, on the ground below the middle of the rear
// axle, metres); the camera frame OpenCV's (x right, y down, z forward). libcam's pose is
// the inverse, vehicle to camera, with the vehicle frame as the world.
//
// Written the same way, from a THETA_POLYNOMIAL camera without skew: the coefficients
// times fx (the file's pixels: exact when fx = 1, as read) and aspect_ratio = fy / fx.

#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> parse_woodscape_camera(std::string_view text, const std::string& source);
std::string format_woodscape_camera(const Camera& camera, const WriteOptions& options);

// Whether a parsed JSON file is WoodScape's: an "intrinsic" map with "cx_offset".
bool claims_woodscape_camera(const DocumentNode& root);

}  // namespace libcam
