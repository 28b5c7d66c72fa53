#pragma once
// Camera files: one entry point to read and write every format libcam speaks: libcam's
// JSON, OpenCV's YAML and XML, mrcal's .cameramodel, COLMAP's model, NeRF's
// transforms.json, Kalibr's, basalt's, ROS's, Open3D's, Blender's and more.
// `libcam formats` (or camera_formats() in io/camera_formats.hpp) lists every format with
// what it reads and writes and the lens models it holds; docs/file-formats.md says each
// format's conventions.
//
// A file may hold several cameras (a stereo pair, a rig): read_camera_set gives every
// one with the file's name for it; read_camera_file gives one, the first by default.
//
// Every reader validates what it reads and throws FileError (unreadable, malformed)
// or InvalidArgument (a value out of range) with the file, the key and the value.
//
// libcam::io itself links neither OpenCV nor libmrcal. cameramodel is read and written by
// libcam::interop once the program has called libcam::register_interop_formats()
// (interop/formats.hpp); before that, it throws FileError saying so.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/camera_types.hpp"

namespace libcam {

std::string_view to_string(CameraFormat format);
CameraFormat camera_format_from_string(std::string_view text);  // throws InvalidArgument
// The format a file's extension names alone or by default (.json: libcam's JSON, .yaml:
// OpenCV's YAML, .cameramodel, .bin: COLMAP's...); nullopt when no format has it.
std::optional<CameraFormat> camera_format_from_path(const std::filesystem::path& path);
// Every format's name, comma-separated (for messages and help).
std::string camera_format_names();

// The file's text in `format`. Throws NotRepresentable when the format cannot hold the
// camera (skew in .cameramodel, distortion in gl), or is written as several files.
std::string format_camera(const Camera& camera, CameraFormat format, const WriteOptions& options = {});

// Every file of `format` holding the camera: one unnamed file, or the named files of a
// format written into a folder (COLMAP: cameras.txt and images.txt).
std::vector<CameraFileText> format_camera_files(const Camera& camera, CameraFormat format,
                                                const WriteOptions& options = {});

// Whether the format is written as several files into a folder.
bool camera_format_writes_folder(CameraFormat format);

// Parses `text` as `format`; `source` names the file in error messages.
CameraFile parse_camera(std::string_view text, CameraFormat format, const std::string& source,
                        const ReadOptions& options = {});

// Every camera of `text` as `format`. Files beside it (COLMAP's images.txt, NeRF's
// images) are not looked at: read_camera_set does that.
CameraSet parse_camera_set(std::string_view text, CameraFormat format, const std::string& source,
                           const ReadOptions& options = {});

// OpenCV's stereo_calib sample writes a calibrated pair in two files: intrinsics.yml (M1 D1
// M2 D2, and the image size where it was given one) and extrinsics.yml (R T, and its
// rectification). Whether `text` is the second kind (R and T, no camera matrix).
bool is_opencv_stereo_extrinsics(std::string_view text);
// The pair's two cameras from the two files' texts, read as one OpenCV YAML document; an
// error about a line names the file that line is in and its line there.
CameraSet parse_opencv_stereo_files(std::string_view intrinsics, const std::string& intrinsics_source,
                                    std::string_view extrinsics, const std::string& extrinsics_source,
                                    const ReadOptions& options = {});

// Reads every camera of a file, in `format` or else the format its extension and
// contents say: .json is libcam's, gl, basalt's or NeRF's by its keys; .yaml/.yml
// OpenCV's, Kalibr's or camodocal's; .txt and .bin COLMAP's; without a known extension,
// the contents alone. A folder holding cameras.txt or cameras.bin is a COLMAP model.
CameraSet read_camera_set(const std::filesystem::path& path, std::optional<CameraFormat> format = std::nullopt,
                          const ReadOptions& options = {});

// The camera `selector` names: a camera's name in the file; the file name of the image
// it names, where its name is a path ("20250614_204908.jpg" for a view named
// "D:/photos/20250614_204908.jpg"), when no other camera's image has that file name; the
// first view of the intrinsics it names (a COLMAP camera id, "id:2"); or its position
// counting from 0; the first camera when empty. Throws InvalidArgument listing the
// cameras, or the cameras whose images share the file name.
const NamedCamera& select_camera(const CameraSet& set, std::string_view selector, const std::string& source);

// Reads one camera of a file (read_camera_set, then select_camera).
CameraFile read_camera_file(const std::filesystem::path& path, std::string_view camera = {},
                            std::optional<CameraFormat> format = std::nullopt, const ReadOptions& options = {});

// Writes atomically (io/atomic_write.hpp). A format written into a folder
// (camera_format_writes_folder) takes the folder, created when missing, or the path of
// one of its files (".../cameras.txt"); every file's text is made before any is written.
void write_camera_file(const std::filesystem::path& path, const Camera& camera, CameraFormat format,
                       const WriteOptions& options = {});

}  // namespace libcam
