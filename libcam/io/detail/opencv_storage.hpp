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
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

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

// Every camera of such a file, and of the other layouts cv::FileStorage files come in:
//   - OpenCV's stereo_calib sample (M1 D1 M2 D2, or K1 D1 K2 D2, with R and T: camera 2
//     from camera 1, X2 = R X1 + T): "camera1", "camera2", in camera 1's frame. The
//     sample writes no image size: image_width/image_height, else ReadOptions::size.
//   - ORB-SLAM's settings (Camera.fx ... of ORB-SLAM2, Camera1.fx ... of ORB-SLAM3 1.0;
//     Camera.type PinHole (k1 k2 p1 p2 [k3]), KannalaBrandt8 (k1..k4: FISHEYE) or
//     Rectified; Camera.width, Camera.height): "Camera1", and "Camera2" placed by
//     Stereo.T_c1_c2 (Tlr before 1.0: camera 2 in camera 1's frame, inverted), or for a
//     Rectified pair by the baseline Stereo.b along x.
// A camera the file does not size takes ReadOptions::size; without it, refused.
std::vector<NamedCamera> parse_opencv_storage_set(std::string_view text, const std::string& source,
                                                  const ReadOptions& options);

// ---- the pieces the calibration sample's observations are read with (opencv_observations.cpp) ----

// The file's tree: XML when its first character is '<', YAML otherwise; a map, else FileError.
DocumentNode parse_opencv_storage_tree(std::string_view text, const std::string& source);

// The calibration sample's camera from the file's tree (image size, camera_matrix,
// distortion_coefficients; cv::fisheye's with fisheye_model 1), as parse_opencv_storage.
Camera read_opencv_storage_camera(const Field& file, const std::string& source);

// A matrix as cv::FileStorage writes it: rows x cols elements of `channels` numbers each
// (dt "2f" is CV_32FC2), row-major; or a plain list of numbers, read as a column.
struct OpenCvMatrix {
    long long rows = 0, cols = 0;
    std::vector<double> values;  // rows * cols * channels
    int channels = 1;
    char depth = 'd';  // dt's type letter: 'f' for float, 'd' for double...
};
// The matrix as cv::FileStorage writes it in YAML under `key` (dt d, or "2d" for two
// channels), every number read back to the same double.
std::string yaml_matrix(const std::string& key, const OpenCvMatrix& m);
// Refuses more than `max_elements` numbers (before reading them) and more than
// `max_channels` channels, naming the field.
OpenCvMatrix read_opencv_matrix(const Field& field, long long max_elements, int max_channels);

// ROS's camera_info YAML (camera_calibration_parsers): image_width, image_height,
// camera_name, camera_matrix, distortion_model (plumb_bob, rational_polynomial,
// equidistant), distortion_coefficients, rectification_matrix R, projection_matrix P.
// Gives the raw camera (K, D), named camera_name, and, where P is given, the rectified
// camera (P's K', no distortion) named "<camera_name>/rectified". The world is the
// stereo pair's rectified frame, the first camera's, where P projects: the rectified
// camera is at t = (Tx / fx', Ty / fy', 0) (0 for the first camera), the raw camera at
// the same centre turned by R^T.
std::vector<NamedCamera> parse_ros_camera_info(std::string_view text, const std::string& source);

// A camera_info of `camera`: R = I, P = [K | 0]. ROS keeps poses in tf, not here: a
// camera whose pose is not the identity is refused unless WriteOptions::drop_pose.
std::string format_ros_camera_info(const Camera& camera, const WriteOptions& options);

}  // namespace libcam
