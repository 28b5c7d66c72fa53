#pragma once
// Images through a RemapMap (remap/remap_map.hpp), with OpenCV: the maps as cv::remap
// takes them, the resampled image, and the map as a file of source coordinates.
//
//   const RemapMap map = build_remap_map(PreparedCamera(pinhole), PreparedCamera(lens));
//   cv::Mat undistorted = remap_image(cv::imread("photo.jpg"), map, Interpolation::Lanczos);

#include <filesystem>
#include <string_view>
#include <utility>

#include <opencv2/core.hpp>

#include "libcam/remap/remap_map.hpp"

namespace libcam {

enum class Interpolation { Nearest, Linear, Cubic, Lanczos };
// "nearest", "linear", "cubic", "lanczos"; throws InvalidArgument naming the others.
Interpolation interpolation_from_string(std::string_view name);

// Where a target pixel without a source points in the maps for cv::remap: far outside any
// image, so that every interpolation reads only the border (BORDER_CONSTANT).
inline constexpr float kNoSourceCoordinate = -1.0e4f;

// The map as cv::remap and cv::initUndistortRectifyMap give it: CV_32FC2 (x, y), each
// coordinate rounded to float.
cv::Mat opencv_map(const RemapMap& map);
// The same in OpenCV's fixed point (cv::convertMaps: CV_16SC2 and CV_16UC1), which
// cv::remap reads fastest, to 1/32 pixel.
std::pair<cv::Mat, cv::Mat> opencv_fixed_point_map(const RemapMap& map);

// The target image: each pixel sampled from `source_image` (of the map's source size)
// by cv::remap, black where the map has no source. A source coordinate in the outer
// half pixel of the image is read from the edge pixel (the pixel's own area is on the
// image), so the edges do not fade into black. Throws InvalidArgument for an image of
// another size.
cv::Mat remap_image(const cv::Mat& source_image, const RemapMap& map, Interpolation interpolation);

// The map as a file of source coordinates, NaN where there is no source, in double's
// precision rounded to float32: an OpenEXR image with channels R (x) and G (y), or a
// NumPy .npy array of shape (height, width, 2). Chosen by the extension (.exr, .npy);
// written atomically. Throws FileError naming the file.
void write_map_file(const std::filesystem::path& path, const RemapMap& map);

}  // namespace libcam
