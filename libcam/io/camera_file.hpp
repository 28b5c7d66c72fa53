#pragma once
// Camera files: one entry point to read and write every format libcam speaks.
//
//   json         libcam's JSON (io/json_format.hpp): K, dist, R, t, rvec, P, fov...
//   opencv-yaml  what cv::FileStorage writes and reads, with the key names of
//   opencv-xml   OpenCV's calibration sample (camera_matrix, distortion_coefficients,
//                image_width, image_height) plus rvec and tvec (io/opencv_storage.hpp)
//   cameramodel  mrcal's .cameramodel, checked by libmrcal's own parser
//   gl           JSON holding an OpenGL projection, view matrix and viewport
//   kalibr       Kalibr's camchain YAML (io/rig_formats.hpp)
//   basalt       basalt's calibration JSON: read only
//   camodocal    camodocal's YAML (VINS-Mono, VINS-Fusion): read only
//   colmap       COLMAP's cameras.txt / cameras.bin, with images.txt / images.bin beside
//                them for the poses (io/colmap_format.hpp); written as cameras.txt,
//                images.txt and points3D.txt into a folder
//   nerf         NeRF's transforms.json (instant-ngp, nerfstudio; io/nerf_transforms.hpp)
//   cahvor       JPL's .cahvor / .cahvore text, as mrcal reads and writes it: read only
//   ros          ROS's camera_info YAML (io/opencv_storage.hpp)
//   open3d       Open3D's PinholeCameraIntrinsic / PinholeCameraParameters JSON
//   euroc        the EuRoC (ASL) dataset's sensor.yaml of a camera: read only
//   openicc      OpenImuCameraCalibrator's JSON, as UMI ships it: read only
//   blender      a Python script that sets a Blender scene's camera: written only
//   blender-json Blender's camera settings as JSON (io/blender_format.hpp)
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

enum class CameraFormat {
    Json, OpenCvYaml, OpenCvXml, Cameramodel, Gl, Kalibr, Basalt, Camodocal, Colmap, Nerf, Cahvor, Ros, Open3d, Euroc,
    Openicc, Blender, BlenderJson
};

std::string_view to_string(CameraFormat format);
CameraFormat camera_format_from_string(std::string_view text);  // throws InvalidArgument
// By extension (.json, .yaml/.yml, .xml, .cameramodel, .py); nullopt when unknown.
std::optional<CameraFormat> camera_format_from_path(const std::filesystem::path& path);
// Every format's name, comma-separated (for messages and help).
std::string camera_format_names();

// What a file holds: the calibrated camera, and the FOV camera it was made from when
// the file says so (libcam JSON records the fov axis).
struct CameraFile {
    Camera camera;
    std::optional<FovCamera> fov_camera;
};

// One camera of a file: the file's name for it (cam0, a camodocal camera_name, a COLMAP
// image's name), or empty where the file names none.
struct NamedCamera {
    std::string name;
    CameraFile file;
    // Where the file holds several views taken with one set of intrinsics (COLMAP's
    // images of one camera), the name of those intrinsics ("id:2"); else empty.
    std::string intrinsics_name = {};
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
    // The image the camera's pose belongs to, in formats that list images (COLMAP's
    // images.txt NAME, transforms.json's file_path).
    std::string image_name = "image.png";
    // The camera's name in formats that name it (ROS's camera_name).
    std::string camera_name = "camera";
    // Formats that hold no pose (ROS's camera_info) refuse a camera whose pose is not the
    // identity, unless this says to write its intrinsics alone.
    bool drop_pose = false;
};

// Where NeRF's transforms.json puts the principal point when it gives none (only
// camera_angle_x, as NeRF's synthetic scenes).
enum class NerfPrincipalPoint {
    ImageCentre,  // (W - 1) / 2, (H - 1) / 2: the image's centre, where Blender rendered them (default)
    HalfSize,     // W / 2, H / 2 in libcam's pixels: where NeRF's own ray code puts it, half a pixel off
};

struct ReadOptions {
    // The image size, for a file that does not record it (NeRF's synthetic scenes);
    // a size the file records must agree with it.
    std::optional<ImageSize> size;
    NerfPrincipalPoint nerf_principal_point = NerfPrincipalPoint::ImageCentre;
};

// One file of a format's output: its name in the output folder (COLMAP's "cameras.txt"),
// empty for a format written as one file, and its text.
struct CameraFileText {
    std::string name;
    std::string text;
};

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

// Reads every camera of a file, in `format` or else the format its extension and
// contents say: .json is libcam's, gl, basalt's or NeRF's by its keys; .yaml/.yml
// OpenCV's, Kalibr's or camodocal's; .txt and .bin COLMAP's; without a known extension,
// the contents alone. A folder holding cameras.txt or cameras.bin is a COLMAP model.
CameraSet read_camera_set(const std::filesystem::path& path, std::optional<CameraFormat> format = std::nullopt,
                          const ReadOptions& options = {});

// The camera `selector` names: a camera's name in the file, the first view of the
// intrinsics it names (a COLMAP camera id, "id:2"), or its position counting from 0;
// the first camera when empty. Throws InvalidArgument listing the cameras.
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
