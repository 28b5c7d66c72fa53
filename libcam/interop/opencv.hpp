#pragma once
// The bridge to OpenCV: libcam cameras as the cv::Mat arguments of calib3d. (OpenCV's
// camera files are read and written without OpenCV: io/detail/opencv_storage.hpp.)

#include <opencv2/core.hpp>
#include <optional>
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

// A camera as the arguments of the OpenCV functions that have its lens model (built once,
// so that a timed call builds nothing): cv::projectPoints and cv::undistortPoints for
// OpenCV's models, cv::fisheye's for FISHEYE, cv::omnidir's for UCM and MEI.
// NotRepresentable for a model OpenCV lacks.
struct OpenCvCamera {
    explicit OpenCvCamera(const Camera& camera);
    OpenCvFunction function;
    cv::Mat K, dist;
    double xi = 0;  // cv::omnidir only
};

// Camera-frame points (CV_64FC3) projected by OpenCV itself, with R = I and t = 0, into
// `pixels` (CV_64FC2). OpenCV does not flag points behind the camera (cv::projectPoints
// mirrors them, cv::fisheye folds them forward); the caller decides what to compare.
void opencv_project(const OpenCvCamera& camera, cv::InputArray points, cv::OutputArray pixels);

// Pixels (CV_64FC2) undistorted by OpenCV itself into (x, y) of the ray (x, y, 1), at the
// function's default stopping rule when `criteria` is empty. cv::omnidir's has one fixed
// rule (20 iterations): InvalidArgument if a rule is given for it.
void opencv_undistort(const OpenCvCamera& camera, cv::InputArray pixels, cv::OutputArray normalized,
                      const std::optional<cv::TermCriteria>& criteria = std::nullopt);

// opencv_project on libcam's types.
std::vector<Vec2> opencv_project_points(const Camera& camera, const std::vector<Vec3>& camera_points);

}  // namespace libcam
