#pragma once
// Camera files: one entry point to read and write every format libcam speaks.
//
//   json         libcam's JSON (io/json_format.hpp): K, dist, R, t, rvec, P, fov...
//   opencv-yaml  what cv::FileStorage writes and reads, with the key names of
//   opencv-xml   OpenCV's calibration sample (camera_matrix, distortion_coefficients,
//                image_width, image_height) plus rvec and tvec (io/opencv_storage.hpp)
//   cameramodel  mrcal's .cameramodel, checked by libmrcal's own parser
//   gl           JSON holding an OpenGL projection, view matrix and viewport
//   kalibr       Kalibr's camchain YAML (io/rig_formats.hpp): read only
//   basalt       basalt's calibration JSON: read only
//   camodocal    camodocal's YAML (VINS-Mono, VINS-Fusion): read only
//
// A file may hold several cameras (a stereo pair, a rig): read_camera_set gives every
// one with the file's name for it; read_camera_file gives one, the first by default.
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
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/convert/opengl.hpp"
#include "libcam/fov/fov_camera.hpp"

namespace libcam {

enum class CameraFormat { Json, OpenCvYaml, OpenCvXml, Cameramodel, Gl, Kalibr, Basalt, Camodocal };

std::string_view to_string(CameraFormat format);
CameraFormat camera_format_from_string(std::string_view text);  // throws InvalidArgument
// By extension (.json, .yaml/.yml, .xml, .cameramodel); nullopt when unknown.
std::optional<CameraFormat> camera_format_from_path(const std::filesystem::path& path);
// Every format's name, comma-separated (for messages and help).
std::string camera_format_names();

// What a file holds: the calibrated camera, and the FOV camera it was made from when
// the file says so (libcam JSON records the fov axis).
struct CameraFile {
    Camera camera;
    std::optional<FovCamera> fov_camera;
};

// One camera of a file: the file's name for it (cam0, a camodocal camera_name), or empty
// where the file names none.
struct NamedCamera {
    std::string name;
    CameraFile file;
};

// Every camera a file holds, in the file's order (at least one).
struct CameraSet {
    CameraFormat format = CameraFormat::Json;
    std::vector<NamedCamera> cameras;
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

// Every camera of `text` as `format`.
CameraSet parse_camera_set(std::string_view text, CameraFormat format, const std::string& source);

// Reads every camera of a file, in `format` or else the format its extension and
// contents say: .json is libcam's, gl or basalt's by its keys; .yaml/.yml OpenCV's,
// Kalibr's or camodocal's; without a known extension, the contents alone.
CameraSet read_camera_set(const std::filesystem::path& path, std::optional<CameraFormat> format = std::nullopt);

// The camera `selector` names: a camera's name in the file, or its position counting
// from 0; the first camera when empty. Throws InvalidArgument listing the cameras.
const NamedCamera& select_camera(const CameraSet& set, std::string_view selector, const std::string& source);

// Reads one camera of a file (read_camera_set, then select_camera).
CameraFile read_camera_file(const std::filesystem::path& path, std::string_view camera = {},
                            std::optional<CameraFormat> format = std::nullopt);

// Writes atomically (io/atomic_write.hpp).
void write_camera_file(const std::filesystem::path& path, const Camera& camera, CameraFormat format,
                       const WriteOptions& options = {});

}  // namespace libcam
