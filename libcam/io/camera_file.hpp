#pragma once
// Camera files: one entry point to read and write every format libcam speaks.
//
//   json         libcam's JSON (io/json_format.hpp): K, dist, R, t, rvec, P, fov...
//   opencv-yaml  what cv::FileStorage writes and reads, with the key names of
//   opencv-xml   OpenCV's calibration sample (camera_matrix, distortion_coefficients,
//                image_width, image_height) plus rvec and tvec (io/opencv_storage.hpp)
//   cameramodel  mrcal's .cameramodel, checked by libmrcal's own parser
//   gl           JSON holding an OpenGL projection, view matrix and viewport
//
// Every reader validates what it reads and throws FileError (unreadable, malformed)
// or InvalidArgument (a value out of range) with the file, the key and the value.
//
// libcam::io itself reads and writes json, gl, opencv-yaml and opencv-xml, and links
// neither OpenCV nor libmrcal. cameramodel is read and written by libcam::interop once
// the program has called libcam::register_interop_formats() (interop/formats.hpp);
// before that, it throws FileError saying so (io/format_table.hpp).

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "libcam/camera/camera.hpp"
#include "libcam/convert/opengl.hpp"
#include "libcam/fov/fov_camera.hpp"

namespace libcam {

enum class CameraFormat { Json, OpenCvYaml, OpenCvXml, Cameramodel, Gl };

std::string_view to_string(CameraFormat format);
CameraFormat camera_format_from_string(std::string_view text);  // throws InvalidArgument
// By extension (.json, .yaml/.yml, .xml, .cameramodel); nullopt when unknown.
std::optional<CameraFormat> camera_format_from_path(const std::filesystem::path& path);

// What a file holds: the calibrated camera, and the FOV camera it was made from when
// the file says so (libcam JSON records the fov axis).
struct CameraFile {
    Camera camera;
    std::optional<FovCamera> fov_camera;
};

struct WriteOptions {
    std::optional<FovCamera> fov_camera;  // JSON: record the FOV camera's own axis and up
    double gl_near = 0.1;
    double gl_far = 1000.0;
    DepthRange gl_depth_range = DepthRange::MinusOneToOne;
};

// The file's text in `format`. Throws NotRepresentable when the format cannot hold the
// camera (skew in .cameramodel, distortion in gl).
std::string format_camera(const Camera& camera, CameraFormat format, const WriteOptions& options = {});

// Parses `text` as `format`; `source` names the file in error messages.
CameraFile parse_camera(std::string_view text, CameraFormat format, const std::string& source);

// Reads a file, choosing the format from its extension or, failing that, its contents.
CameraFile read_camera_file(const std::filesystem::path& path);

// Writes atomically (io/atomic_write.hpp).
void write_camera_file(const std::filesystem::path& path, const Camera& camera, CameraFormat format,
                       const WriteOptions& options = {});

}  // namespace libcam
