#pragma once
// OpenMVG's sfm_data.json (cereal's JSON): views, intrinsics, extrinsics and the structure
// with its observations.
//
//   views        id -> {filename, width, height, id_view, id_intrinsic, id_pose}
//   intrinsics   id -> a polymorphic intrinsic: its polymorphic_name (written with the first
//                of each type; later ones give only the polymorphic_id) and its data:
//                width, height, focal_length, principal_point, and the distortion, either
//                flat or, as newer OpenMVG writes it, the pinhole's keys nested in "value0"
//   extrinsics   id -> {rotation (3 rows: world to camera), center}: X_cam = R (X - C)
//   structure    track id -> {X, observations: view id -> {id_feat, x: [x, y]}}
//
// Conventions: OpenMVG's pixel centres are at integers, as OpenCV's (its undistortion
// samples pixel (i, j) of the image at (i, j), and its features are measured so): libcam
// reads its pixels and principal point as they are. Distortion applies to the normalized
// point (x - pp) / f.
//
// Models: pinhole (PINHOLE), pinhole_radial_k1 (OPENCV4 with k1 alone),
// pinhole_radial_k3 (k1, k2, k3 on r^2, r^4, r^6: OPENCV5 with p1 = p2 = 0),
// pinhole_brown_t2 (k1, k2, k3, t1, t2: OPENCV5 with p1 = t1, p2 = t2: OpenCV's tangential
// terms), fisheye (k1..k4 on theta: FISHEYE) and spherical (LONLAT, with fx = fy =
// max(width, height) / (2 pi) and the principal point at (width / 2, height / 2), where
// OpenMVG's cam2ima puts it); any other type is refused.
//
// Reading cameras gives one per view with a pose, named by its filename, with its
// intrinsics (intrinsics_name "id:N") and its pose; then one per view with an intrinsic
// but without a pose (every view of a file before SfM), said to be unposed; a file
// without views, one per intrinsic, named "id:N", without a pose.
//
// Observations: every observation of the structure in a view with a pose. OpenMVG stores
// no reprojection error in the file.

#include <filesystem>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/io/observations.hpp"

namespace libcam {

std::vector<NamedCamera> read_openmvg(std::string_view text, const ReadContext& context);

ObservationSet read_openmvg_observations(const std::filesystem::path& file, std::string_view text,
                                         const ObservationReadOptions& options);

// Whether a parsed JSON file is an sfm_data.json: an object with "sfm_data_version".
bool claims_openmvg(const DocumentNode& root);

}  // namespace libcam
