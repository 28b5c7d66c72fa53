#pragma once
// Checks a camera against OpenCV and mrcal, as `libcam verify` does: libcam's projection
// and unprojection against cv::projectPoints / cv::fisheye, mrcal_project and
// mrcal_unproject, and cv::undistortPoints, over a grid of pixels covering the whole
// image (corners included) and points at several depths along each pixel's ray.
//
// Everything happens in the camera frame: the pose plays no part in the lens.
//
// Each check measures an error in pixels for every grid pixel it can, and has a
// tolerance, or none when it is informational (another library's approximation, shown
// for comparison; it never fails the report). A check whose library lacks the model is
// skipped with the reason.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/stats/error_stats.hpp"

namespace libcam {

// The checks, by name (the name `libcam verify --check` takes).
namespace verify_check {
inline constexpr std::string_view project_opencv = "project-opencv";      // libcam vs cv::projectPoints
inline constexpr std::string_view project_mrcal = "project-mrcal";        // libcam vs mrcal_project
inline constexpr std::string_view unproject_libcam = "unproject-libcam";  // |project(unproject(q)) - q|, libcam both ways
inline constexpr std::string_view unproject_libcam_opencv = "unproject-libcam-opencv";  // ... reprojected by OpenCV
inline constexpr std::string_view unproject_libcam_mrcal = "unproject-libcam-mrcal";    // ... reprojected by mrcal
inline constexpr std::string_view unproject_mrcal = "unproject-mrcal";    // mrcal_unproject's own residual
inline constexpr std::string_view mrcal_vs_libcam = "unproject-mrcal-vs-libcam";  // where the two rays land
inline constexpr std::string_view undistort_opencv_default = "undistort-opencv-default";  // its residual
inline constexpr std::string_view undistort_opencv_100 = "undistort-opencv-100";  // 100 iterations
inline constexpr std::string_view round_trip = "round-trip";  // unproject(project(P)) vs P, angle x fx
}  // namespace verify_check

// Every check name, in the order of the report.
std::span<const std::string_view> verify_check_names();

inline constexpr long kMaxVerifyGridSide = 2000;

struct VerifyOptions {
    // Grid of pixel centres (geometry/pixel_grid.hpp): columns evenly from x = 0 to W-1
    // and rows from y = 0 to H-1, so the four corner pixels are always on it. Each side
    // in [2, kMaxVerifyGridSide].
    long grid_columns = 200;
    long grid_rows = 150;
    // Distances along each pixel's (unit) ray at which points are projected.
    std::vector<double> depths{0.5, 2.0, 10.0, 1000.0};
    // Threads each library's calls are split over (the results do not depend on it);
    // 0: as many as the machine has.
    int threads = 0;

    // Throws InvalidArgument naming the field.
    void validate() const;
};

struct VerifyCheck {
    std::string name;     // one of verify_check_names()
    std::string library;  // whose result is measured, and how
    std::optional<double> tolerance_px;      // none: informational
    std::optional<std::string> skipped_because;  // the library lacks the model
    std::string note;                        // what was left out, and why
    ErrorStats stats;  // over every point (pixel) measured; nearest-rank quantiles
    // Per grid pixel (row-major, as VerifyReport::pixels): the worst error over its
    // points, NaN where nothing was measured.
    std::vector<double> pixel_error_px;

    bool informational() const { return !tolerance_px.has_value(); }
    bool skipped() const { return skipped_because.has_value(); }
    // Informational and skipped checks always pass; the others when max <= tolerance.
    bool pass() const;
};

// Where OpenCV's default undistortPoints (5 iterations; cv::fisheye's 10) goes wrong,
// over the pixels libcam unprojects.
struct OpenCvDefaultSummary {
    std::string function;
    double median_px = 0.0;
    double max_px = 0.0;
    Vec2 worst_pixel = Vec2::Zero();
    double fraction_over_0_1px = 0.0;
    double fraction_over_1px = 0.0;
};

struct VerifyReport {
    ImageSize image_size;
    LensType lens_type = LensType::Pinhole;
    VerifyOptions options;
    std::vector<Vec2> pixels;        // the grid, row by row
    std::vector<bool> pixel_valid;   // libcam has a ray through it
    double invalid_fraction = 0.0;   // of grid pixels
    std::vector<VerifyCheck> checks;
    std::optional<OpenCvDefaultSummary> opencv_default;  // none when OpenCV lacks the model

    bool pass() const;
    // The check of that name; nullptr when there is none.
    const VerifyCheck* find(std::string_view name) const;
};

// Runs every check. Throws InvalidArgument for a bad camera or options.
VerifyReport verify_camera(const Camera& camera, const VerifyOptions& options = {});

// The picture of one check's error over the image: libcam/report/verify_heatmap.hpp.

}  // namespace libcam
