#pragma once
// The seed's two worked examples (a FOV camera each, and pixels on it) converted to
// calibrated cameras, and every ray checked against OpenCV (projectPoints,
// undistortPoints, Rodrigues) and mrcal (mrcal_project): what `libcam demo` shows.

#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/fov/fov_camera.hpp"

namespace libcam {

struct SeedPixel {
    Vec2 seed_pixel;      // as the seed counts it: rows from the bottom
    Vec3 seed_direction;  // the seed's formula alpha u + beta v + w, not normalised
    Vec2 opencv_pixel;    // the same pixel counted from the top
};

struct SeedCheck {
    std::string name;
    double max_error = 0.0;  // over the example's pixels (and points along their rays)
    double tolerance = 0.0;
    std::string unit;  // "rad", "px", or empty for a plain number
    bool pass() const { return max_error <= tolerance; }
};

struct SeedExample {
    std::string title;
    FovCamera fov_camera;
    Camera camera;  // to_camera(fov_camera)
    std::vector<SeedPixel> pixels;
    std::vector<SeedCheck> checks;
};

// Both examples, each with its checks: the seed formula against R^T K^-1 (angle),
// cv::projectPoints and mrcal_project of points at several depths on each ray,
// cv::undistortPoints against K^-1 [x, y, 1], cv::Rodrigues(rvec) against R.
std::vector<SeedExample> check_seed_examples();

}  // namespace libcam
