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
std::string_view to_string(Interpolation interpolation);

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

// The same map made ready once for many images of one camera, for one interpolation:
// OpenCV's fixed point (cv::convertMaps), which cv::remap otherwise computes from float
// maps again for every image, block by block, the same way (1/32 pixel; nearest
// rounds to the nearest pixel): the same pixels, in about half the time.
struct PreparedRemap {
    cv::Mat xy;        // CV_16SC2: whole source pixels
    cv::Mat fraction;  // CV_16UC1: the 1/32-pixel fractions; empty for nearest
    ImageSize source_size;
    Interpolation interpolation = Interpolation::Cubic;
};
PreparedRemap prepare_remap(const RemapMap& map, Interpolation interpolation);
cv::Mat remap_image(const cv::Mat& source_image, const PreparedRemap& map);

// An image file read whole, its bit depth and channels as they are (IMREAD_UNCHANGED);
// FileError naming the file when it is missing or not an image OpenCV reads.
cv::Mat read_image(const std::filesystem::path& path);
// The image encoded by its file's extension and written atomically (io/atomic_write.hpp);
// FileError naming the file when OpenCV cannot write this image as that type. A JPEG's
// quality, 1 to 100 (OpenCV's default 95), is `jpeg_quality`.
inline constexpr int kDefaultJpegQuality = 95;
void write_image(const std::filesystem::path& path, const cv::Mat& image, int jpeg_quality = kDefaultJpegQuality);

// The map as a file of source coordinates, NaN where there is no source, in double's
// precision rounded to float32: an OpenEXR image with channels R (x) and G (y), or a
// NumPy .npy array of shape (height, width, 2). Chosen by the extension (.exr, .npy);
// written atomically. Throws FileError naming the file.
void write_map_file(const std::filesystem::path& path, const RemapMap& map);
// The bytes write_map_file writes, for a caller that writes several files only once all are
// made; FileError naming the file.
std::string encoded_map(const std::filesystem::path& path, const RemapMap& map);
// The same checks of the file's name alone, for a caller that checks before it works:
// FileError unless it ends in .exr or .npy (map) or .exr (STMap).
void check_map_file_name(const std::filesystem::path& path);
void check_stmap_file_name(const std::filesystem::path& path);

// The map as a compositor's STMap (Nuke's STMap node, and the UV maps of other
// compositors): an OpenEXR image, for each target pixel where to sample the source as a
// fraction of the source's format, with Nuke's pixel centres (+0.5) and its y pointing up:
//   R = u = (x + 0.5 - left) / width,   G = v = 1 - (y + 0.5 - top) / height,
// (x, y) the source pixel (libcam's, y down) and the format the width x height rectangle
// whose top-left pixel is (left, top) of the source image: the source itself when it has
// no overscan, the image inside the margins when it does (overscan pixels then get u or v
// outside [0, 1], as Nuke places them outside the format). B = 0; A = 1 where the target
// pixel has a source, and 0 with u = v = -1 where it has none. Written atomically; throws
// FileError naming the file (which must end in .exr), InvalidArgument for an empty format.
struct StmapFormat {
    ImageSize size;         // the format: the source image without its overscan
    long left = 0, top = 0;  // the format's top-left pixel in the source image
};
void write_stmap_file(const std::filesystem::path& path, const RemapMap& map, const StmapFormat& format);

}  // namespace libcam
