#pragma once
// Two text files of incremental SfM: VisualSfM's .nvm and Bundler's bundle.out. Neither
// stores the image size: every image of the file has the one given (ReadOptions::size,
// `--image-size WxH`; ObservationReadOptions::size), and reading without it is refused.
// Both measure pixels from "the image centre": libcam puts that at OpenCV's centre
// ((w - 1) / 2, (h - 1) / 2), where Bundler's own key reader puts it (ImageData.cpp:
// x - 0.5 (w - 1), after flipping y), and the principal point with it; a tool that
// measured from w / 2 moves every pixel and the principal point by the same half pixel,
// which no residual sees.
//
// VisualSfM's NVM_V3 (its documentation, "NVM file format"):
//   NVM_V3 [FixedK fx cx fy cy]
//   <camera count>
//   <file name> <focal length> <quaternion w x y z> <camera centre x y z> <radial distortion r> 0
//   <point count>
//   <x y z> <r g b> <measurement count> (<image index> <feature index> <x> <y>)...
//   [further models, then the unregistered images: not read]
// The quaternion is the rotation R, world to camera, of x_cam = R (X - C), camera axes
// OpenCV's (x right, y down, z forward, as PBA projects f (x / z, y / z)); measurements are
// (x, y) from the image centre, y down. r is VisualSfM's measurement distortion: the ideal
// normalized point is the measured one m / f times 1 + r |m / f|^2 (COLMAP's export writes
// r = -k for its SIMPLE_RADIAL k, the first-order inverse). That runs the other way from
// every libcam lens, so a camera with r != 0 is refused; its observations are read as
// VisualSfM's bundle adjuster sees them, measurements undistorted by r, seen by the pinhole
// f. FixedK files are refused.
//
// Bundler's v0.3 (its README, "Output format"):
//   # Bundle file v0.3
//   <camera count> <point count>
//   per camera: <f> <k1> <k2>, R (3 rows), t: P = R X + t, p = -P / P.z, pixel = f r(p) p,
//               r(p) = 1 + k1 |p|^2 + k2 |p|^4, from the image centre, x right, y up; the
//               camera looks down -z with y up (OpenGL's axes). A camera not registered is
//               all zeros (f = 0) and gives none.
//   per point:  <x y z>, <r g b>, <view count> (<camera> <key> <x> <y>)...
// In libcam's axes R and t are diag(1, -1, -1) R and diag(1, -1, -1) t, the lens OPENCV4
// (k1, k2, 0, 0), and a measurement (x, y) the pixel (cx + x, cy - y). The images' names
// are the first word of each line of list.txt beside the file where it is there, else
// "camera N".

#include <filesystem>
#include <string_view>
#include <vector>

#include "libcam/io/format_table.hpp"
#include "libcam/io/observations.hpp"

namespace libcam {

std::vector<NamedCamera> read_nvm(std::string_view text, const ReadContext& context);
ObservationSet read_nvm_observations(const std::filesystem::path& file, std::string_view text,
                                     const ObservationReadOptions& options);

std::vector<NamedCamera> read_bundler(std::string_view text, const ReadContext& context);
ObservationSet read_bundler_observations(const std::filesystem::path& file, std::string_view text,
                                         const ObservationReadOptions& options);

}  // namespace libcam
