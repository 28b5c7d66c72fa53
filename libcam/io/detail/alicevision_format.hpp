#pragma once
// AliceVision's (Meshroom's) SfMData JSON: cameras.sfm, and the .json ConvertSfMFormat
// writes. boost's property tree writes it, so every value is a JSON string ("4000",
// "0.0826"), an empty list is "" and booleans are "true"/"false" (older files "0"/"1").
//
//   version      ["1", "2", "6"]: decides how the intrinsics read (below)
//   views        [{viewId, poseId, intrinsicId, path, width, height, [rigId, subPoseId,
//                isPoseIndependant], metadata}]
//   intrinsics   [{intrinsicId, width, height, sensorWidth, sensorHeight (mm, default 36
//                and 24), type, focalLength (mm), pixelRatio, principalPoint,
//                distortionParams, [distortionType, undistortionType]}]
//   poses        [{poseId, pose: {transform: {rotation: 9 numbers, center: 3}}}]
//   rigs         [{rigId, subPoses: [{status, pose: {rotation, center}}]}]
//   structure    [{landmarkId, X, observations: [{observationId (the view's id),
//                featureId, x: [x, y], scale}]}]
//
// Poses (geometry/Pose3.hpp): `rotation` is c_R_w, world to camera, written by Eigen's
// linear index, so column by column (R(i, j) is number i + 3 j; AliceVision's own sample
// scene, an angle-axis rotation, shows it), and `center` is the camera's centre in the
// world: x_cam = R (X - C). The camera looks down +z with x right and y down (Pinhole's
// project: x / z), OpenCV's axes. A view of a rig (isPoseIndependant "false") is its
// sub-pose after the rig's pose.
//
// Intrinsics, by version (sfmDataIO/jsonIO.cpp, loadIntrinsic):
//   before 1.2.0   pxFocalLength: one number, fx = fy
//   1.2.0, 1.2.1   pxFocalLength: [fx, fy]
//   1.2.2 - 1.2.4  focalLength in mm: fx = focalLength w / sensorWidth, fy = fx / pixelRatio
//   1.2.5 - 1.2.10 fx = focalLength w / sensorWidth, fy = fx pixelRatio
//   1.2.11         fx = focalLength / pixelRatio w / sensorWidth, fy = focalLength w / sensorWidth
//   newer          refused, as AliceVision refuses a file newer than itself
// principalPoint is the offset from (w / 2, h / 2) from 1.2.1 on, the pixel itself before.
// AliceVision's pixels are OpenMVG's, the top-left pixel's centre at (0, 0) (its images are
// sampled at integer pixels): read as they are.
//
// Models: "type" names them before 1.2.8 (pinhole, radial1, radial3, brown, fisheye4,
// fisheye1, equidistant, equidistant_r3, 3de...), then "type" (pinhole or equidistant) with
// "distortionType" (none, radialk1, radialk3, radialk3pt, brown, fisheye, fisheye1) and
// "undistortionType". On a pinhole, with p = (x / z, y / z):
//   radialk1 (k1)             p (1 + k1 r^2): OPENCV4
//   radialk3 (k1 k2 k3)       p (1 + k1 r^2 + k2 r^4 + k3 r^6): OPENCV5, p1 = p2 = 0
//   brown (k1 k2 k3 t1 t2)    OpenCV's radial and tangential terms, t1 = p1, t2 = p2: OPENCV5
//   fisheye (k1..k4)          theta (1 + k1 theta^2 + ...) / r: FISHEYE
//   fisheye1 (w)              atan(2 r tan(w / 2)) / (w r): FOV
//   radialk3pt (k1 k2 k3)     radialk3 divided by 1 + k1 + k2 + k3: OPENCV5 with fx, fy divided by it
// The equidistant camera maps a point at angle theta from the axis to the radius
// rho = theta / (fov / 2), fov = min(sensorWidth, sensorHeight) / fmm, fmm = fx
// sensorWidth / max(w, h), then distorts rho and scales by (fx, fy): with c = 2 fmm /
// min(sensorWidth, sensorHeight) it is FISHEYE with focal lengths (fx, fy) c, and with
// radialk1, radialk3 or radialk3pt (divide the focal lengths by 1 + k1 + k2 + k3) the
// coefficients k1 c^2, k2 c^4, k3 c^6. The 3DE models (undistortion maps, or older
// distortions) and other pairs have no libcam lens and are refused.
//
// Reading gives one camera per view with an intrinsic and a pose, named by its path, its
// intrinsics named "id:N"; then one per view with an intrinsic but no pose, said to be
// unposed; a file without views, one camera per intrinsic. A view is found by its path or
// by its image's file name alone (select_camera).
// Observations: every observation of the structure in a view with a pose.
//
// Written as version 1.2.6 (Meshroom 2023's, which every later AliceVision reads): one
// view, its intrinsic (a 36 mm wide sensor of the image's aspect) and its pose.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/io/observations.hpp"

namespace libcam {

std::vector<NamedCamera> read_alicevision(std::string_view text, const ReadContext& context);

ObservationSet read_alicevision_observations(const std::filesystem::path& file, std::string_view text,
                                             const ObservationReadOptions& options);

std::string format_alicevision(const Camera& camera, const WriteOptions& options);

// Whether a parsed JSON file is AliceVision's: a "version" list beside "views" or
// "intrinsics" (OpenMVG's has "sfm_data_version").
bool claims_alicevision(const DocumentNode& root);

}  // namespace libcam
