#pragma once
// The bridge to OpenCV: libcam cameras as the cv::Mat arguments of calib3d, and
// OpenCV's camera files as cv::FileStorage writes them.

#include <opencv2/core.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/camera/camera.hpp"

namespace libcam {

cv::Mat opencv_camera_matrix(const Intrinsics& intrinsics);  // 3x3 CV_64F
// 1xN CV_64F in OpenCV's order (N = 0 for PINHOLE), for cv::projectPoints (OpenCV's
// models) or cv::fisheye (FISHEYE); NotRepresentable for a model OpenCV lacks.
cv::Mat opencv_distortion(const Lens& lens);
cv::Mat opencv_vector(const Vec3& v);                        // 3x1 CV_64F (rvec, tvec)

// Camera-frame points projected by OpenCV itself: cv::projectPoints, or
// cv::fisheye::projectPoints for FISHEYE, with R = I and t = 0. OpenCV does not flag
// points behind the camera (it mirrors them); the caller decides what to compare.
std::vector<Vec2> opencv_project_points(const Camera& camera, const std::vector<Vec3>& camera_points);

enum class OpenCvStorage { Yaml, Xml };

// The text cv::FileStorage writes: image_width, image_height, camera_matrix,
// distortion_coefficients (OpenCV's calibration sample's names), rvec, tvec.
// A PINHOLE lens is written as five zero coefficients, as cv::calibrateCamera does;
// OPENCV4..14 as their coefficients. Other models throw NotRepresentable (FISHEYE's
// four coefficients would read back as OPENCV4).
std::string format_opencv_storage(const Camera& camera, OpenCvStorage storage);

// Reads such a file. rvec and tvec may be absent (identity pose). 4, 5, 8, 12 or 14
// distortion coefficients are OPENCV4..OPENCV14; coefficients that are all zero are
// read as PINHOLE, which they equal exactly.
Camera parse_opencv_storage(std::string_view text, const std::string& source);

}  // namespace libcam
