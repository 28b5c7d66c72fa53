#pragma once
// The two worked example cameras (3x3 pixels, 90 degrees: one at the origin looking down
// -z, one at eye (0,5,5) looking at the origin), with pixels on each, converted to
// calibrated cameras, and every ray checked against OpenCV (projectPoints,
// undistortPoints, Rodrigues) and mrcal (mrcal_project): what `libcam demo` shows.

#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/graphics/look_at_camera.hpp"

namespace libcam {

struct WorkedExamplePixel {
    Vec2 bottom_left_pixel;  // rows counted from the bottom, as the look-at formula counts them
    Vec3 look_at_direction;  // the look-at formula alpha u + beta v + w, not normalised
    Vec2 opencv_pixel;       // the same pixel counted from the top
};

struct WorkedExampleCheck {
    std::string name;
    double max_error = 0.0;  // over the example's pixels (and points along their rays)
    double tolerance = 0.0;
    std::string unit;  // "rad", "px", or empty for a plain number
    bool pass() const { return max_error <= tolerance; }
};

struct WorkedExample {
    std::string name;   // "example 1"
    std::string title;  // the name and the camera
    LookAtCamera look_at_camera;
    Camera camera;  // to_camera(look_at_camera)
    std::vector<WorkedExamplePixel> pixels;
    std::vector<WorkedExampleCheck> checks;
};

// Both example cameras, each with its checks: the look-at formula against R^T K^-1 (angle),
// cv::projectPoints and mrcal_project of points at several depths on each ray,
// cv::undistortPoints against K^-1 [x, y, 1], cv::Rodrigues(rvec) against R.
std::vector<WorkedExample> check_worked_examples();

}  // namespace libcam
