#pragma once
// The types every part of libcam::io shares: the formats, what a file holds, and the
// options of reading and writing. The entry points that use them are in camera_file.hpp.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/convert/opengl.hpp"
#include "libcam/graphics/look_at_camera.hpp"

namespace libcam {

enum class CameraFormat {
    Json, OpenCvYaml, OpenCvXml, Cameramodel, Gl, Kalibr, Basalt, Camodocal, Colmap, Nerf, Cahvor, Ros, Open3d, Euroc,
    Openicc, Blender, BlenderJson, OpenSfm, OpenMvg, GsCameras, Llff, Metashape,
    // Photogrammetry files: AliceVision's cameras.sfm, VisualSfM's .nvm, Bundler's .out.
    AliceVision, Nvm, Bundler,
    // Lens databases: lensfun's XML, Hugin's .pto, Gyroflow's lens profiles.
    Lensfun, HuginPto, Gyroflow,
    // OCamCalib: the MATLAB toolbox's calib_results.txt, py-OCamCalib's JSON
    OcamCalib, PyOcamCalib,
    RealityCapture,     // RealityCapture's XMP sidecars
    RealityCaptureCsv,  // RealityCapture's CSV of internal/external camera parameters
    Woodscape,       // Valeo's WoodScape calibration JSON
    DriveworksRig,   // NVIDIA DriveWorks' rig.json (F-theta cameras)
};
// How many formats there are (the table of formats checks that each has its row).
inline constexpr std::size_t kCameraFormatCount = static_cast<std::size_t>(CameraFormat::DriveworksRig) + 1;

// What a file holds: the calibrated camera, and the look-at camera it was made from when
// the file says so (libcam JSON records the fov axis).
struct CameraFile {
    Camera camera;
    std::optional<LookAtCamera> look_at_camera;
};

// One camera of a file: the file's name for it (cam0, a camodocal camera_name, a COLMAP
// image's name), or empty where the file names none.
struct NamedCamera {
    std::string name;
    CameraFile file;
    // Where the file holds several views taken with one set of intrinsics (COLMAP's
    // images of one camera), the name of those intrinsics ("id:2"); else empty.
    std::string intrinsics_name = {};
    // A view the file lists with its calibration but without a pose (a photo Metashape
    // has not aligned, a view of OpenMVG's or AliceVision's file before or left out of the
    // reconstruction, a NeRF frame without transform_matrix): its pose here is the
    // identity, which says nothing of where it was.
    bool unposed = false;
};

// Every camera a file holds, in the file's order (at least one).
struct CameraSet {
    CameraFormat format = CameraFormat::Json;
    std::vector<NamedCamera> cameras;
};

struct WriteOptions {
    std::optional<LookAtCamera> look_at_camera;  // JSON: record the look-at camera's own axis and up
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

    // Lens databases (lensfun's XML), which describe lenses, not images: which lens (one
    // of its model names, or a part of one that names no other lens), at which focal
    // length in millimetres (a prime lens's own by default), on a sensor of which crop
    // factor (the calibration's by default); the image size above is required.
    std::string lens;
    std::optional<double> focal_mm;
    std::optional<double> crop_factor;
    // The lens's projection alone, its distortion left out (what lensfun's projection
    // transform without distortion correction maps).
    bool lens_projection_only = false;
};

// One file of a format's output: its name in the output folder (COLMAP's "cameras.txt"),
// empty for a format written as one file, and its text.
struct CameraFileText {
    std::string name;
    std::string text;
};

}  // namespace libcam
