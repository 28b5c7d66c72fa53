#pragma once
// The bridge to OpenCV: libcam cameras as the cv::Mat arguments of calib3d. (OpenCV's
// camera files are read and written without OpenCV: io/opencv_storage.hpp.)

#include <opencv2/core.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/camera/camera.hpp"

namespace libcam {

cv::Mat opencv_camera_matrix(const Intrinsics& intrinsics);  // 3x3 CV_64F
// 1xN CV_64F in OpenCV's order (N = 0 for PINHOLE), for cv::projectPoints (OpenCV's
// models), cv::fisheye (FISHEYE) or cv::omnidir (UCM and MEI: k1 k2 p1 p2, zero for UCM;
// xi apart); NotRepresentable for a model OpenCV lacks.
cv::Mat opencv_distortion(const Lens& lens);
double opencv_xi(const Lens& lens);  // cv::omnidir's xi (UCM, MEI); NotRepresentable otherwise
cv::Mat opencv_vector(const Vec3& v);                        // 3x1 CV_64F (rvec, tvec)

// Camera-frame points projected by OpenCV itself: cv::projectPoints,
// cv::fisheye::projectPoints for FISHEYE, or cv::omnidir::projectPoints for UCM and MEI,
// with R = I and t = 0. OpenCV does not flag
// points behind the camera (it mirrors them); the caller decides what to compare.
std::vector<Vec2> opencv_project_points(const Camera& camera, const std::vector<Vec3>& camera_points);

}  // namespace libcam
