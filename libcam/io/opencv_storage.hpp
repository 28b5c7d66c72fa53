#pragma once
// OpenCV's camera files, as cv::FileStorage writes and reads them (YAML and XML),
// read and written by libcam itself: no OpenCV needed.
//
//   %YAML:1.0
//   ---
//   image_width: 640
//   image_height: 480
//   camera_matrix: !!opencv-matrix
//      rows: 3
//      cols: 3
//      dt: d
//      data: [ 500., 0., 319.5, 0., 500., 239.5, 0., 0., 1. ]
//   distortion_coefficients: !!opencv-matrix      4, 5, 8, 12 or 14 numbers
//      ...
//   rvec: ..., tvec: ...                         3 numbers each, world -> camera; optional
//
// These are the names OpenCV's calibration sample writes; its older spellings
// (Camera_Matrix, Distortion_Coefficients, image_Width, image_Height) are read too.
// The coefficients are cv::projectPoints' (OPENCV4..14) unless the file says they are
// cv::fisheye's (FISHEYE): the sample's `fisheye_model: 1`, or a `distortion_model` of
// equidistant, fisheye or kannala_brandt (plumb_bob, rational_polynomial and radtan
// name cv::projectPoints' model; any other name is refused).
// A matrix may also be a plain list of numbers. The file may start with or without the
// "%YAML:1.0" line and the "---" line, with CRLF line ends.

#include <string>
#include <string_view>

#include "libcam/camera/camera.hpp"

namespace libcam {

enum class OpenCvStorage { Yaml, Xml };

// The text of such a file for `camera`, every number written so that it reads back to
// the same double. A PINHOLE lens is written as five zero coefficients, as
// cv::calibrateCamera does; OPENCV4..14 as their coefficients; FISHEYE as its four with
// `fisheye_model: 1` and `distortion_model: equidistant` (without them they would read
// back as OPENCV4). Other models throw NotRepresentable.
std::string format_opencv_storage(const Camera& camera, OpenCvStorage storage);

// Reads such a file (XML when its first character is '<', YAML otherwise). rvec and
// tvec may be absent (identity pose). 4, 5, 8, 12 or 14 distortion coefficients are
// OPENCV4..OPENCV14; coefficients that are all zero, or none, are read as PINHOLE,
// which they equal exactly. cv::fisheye's are FISHEYE (4, even when all zero: that is
// the equidistant lens). Throws FileError naming the file, line, key and value.
Camera parse_opencv_storage(std::string_view text, const std::string& source);

}  // namespace libcam
