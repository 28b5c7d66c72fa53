#pragma once
// OpenSfM's reconstruction.json (a list of reconstructions, each with its cameras, shots
// and points) with tracks.csv beside it, and the bare camera dictionaries OpenSfM and
// OpenDroneMap write (camera_models.json, ODM's cameras.json).
//
//   cameras   id -> {projection_type, width, height, and the model's parameters}
//   shots     image name -> {camera, rotation (axis-angle), translation}: world to camera,
//             X_cam = R(rotation) X + translation, OpenCV's camera axes
//   points    track id -> {coordinates, color}
//   tracks.csv  OPENSFM_TRACKS_VERSION_v1..v3, then tab-separated rows of
//             shot, track id, feature id, x, y (normalized), scale, r, g, b, ...
//
// Conventions: OpenSfM measures the image in "normalized" units, the larger side being 1
// with the origin at the image's centre; its pixel (0, 0) is the image's top-left corner
// (features.py: normalized = (pixel + 0.5 - width / 2) / max(width, height) for OpenCV's
// pixels), so libcam's pixel is x * N + (width - 1) / 2 with N = max(width, height), and
// libcam's cx = c_x * N + (width - 1) / 2.
//
// Models, each read as the libcam model that holds it exactly (the simplest one of its
// family, so zero coefficients give PINHOLE): perspective (focal, k1, k2 on r^2 and r^4:
// OPENCV4 with p1 = p2 = 0), brown (focal_x, focal_y, c_x, c_y, k1, k2, k3, p1, p2:
// OPENCV5, OpenCV's tangential terms), radial (k1, k2) and simple_radial (k1) with
// focal_x, focal_y, c_x, c_y (OPENCV4), fisheye (focal, k1, k2 on theta: FISHEYE with
// k3 = k4 = 0), fisheye_opencv (FISHEYE), spherical and equirectangular (LONLAT, with
// fx = fy = N / (2 pi)). fisheye62, fisheye624 and dual are refused: libcam has no model
// that holds them exactly.
//
// Reading cameras gives one per shot, named by the shot, with its camera's intrinsics
// (intrinsics_name: the camera's id) and its pose; a file without shots (a camera
// dictionary) gives one per camera, named by its id, without a pose. Several
// reconstructions each have their own world frame.
//
// Observations: every row of tracks.csv whose shot is in a reconstruction and whose track
// is a point of that reconstruction. OpenSfM stores no reprojection error that tracks.csv
// lets one recompute (older files' per-point reprojection_error is not read).

#include <filesystem>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/io/observations.hpp"

namespace libcam {

std::vector<NamedCamera> read_opensfm(std::string_view text, const ReadContext& context);

// The reconstructions of reconstruction.json with the rows of the tracks.csv beside it.
ObservationSet read_opensfm_observations(const std::filesystem::path& file, std::string_view text,
                                         const ObservationReadOptions& options);

// Whether a parsed JSON file is OpenSfM's: a list whose first item has "shots" or
// "cameras", or an object whose first value has "projection_type".
bool claims_opensfm(const DocumentNode& root);

}  // namespace libcam
