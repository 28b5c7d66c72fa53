// The table of camera-file formats: one row each (detail/format_row.hpp says what a row
// holds). Adding a format: docs/adding-a-file-format.md.

#include <array>
#include <optional>

#include "libcam/error.hpp"
#include "libcam/io/detail/alicevision_format.hpp"
#include "libcam/io/detail/blender_format.hpp"
#include "libcam/io/detail/cahvor_format.hpp"
#include "libcam/io/detail/colmap_format.hpp"
#include "libcam/io/detail/colmap_model.hpp"
#include "libcam/io/detail/colmap_observations.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/io/detail/gs_cameras.hpp"
#include "libcam/io/detail/gyroflow_format.hpp"
#include "libcam/io/detail/hugin_format.hpp"
#include "libcam/io/detail/json_format.hpp"
#include "libcam/io/detail/lensfun_format.hpp"
#include "libcam/io/detail/llff_format.hpp"
#include "libcam/io/detail/metashape_format.hpp"
#include "libcam/io/detail/nvm_bundler_formats.hpp"
#include "libcam/io/detail/ocamcalib_format.hpp"
#include "libcam/io/detail/mrcal_observations.hpp"
#include "libcam/io/detail/nerf_transforms.hpp"
#include "libcam/io/detail/open3d_format.hpp"
#include "libcam/io/detail/opencv_observations.hpp"
#include "libcam/io/detail/opencv_storage.hpp"
#include "libcam/io/detail/openmvg_format.hpp"
#include "libcam/io/detail/opensfm_format.hpp"
#include "libcam/io/detail/openicc_format.hpp"
#include "libcam/io/detail/realitycapture_csv.hpp"
#include "libcam/io/detail/realitycapture_format.hpp"
#include "libcam/io/detail/rig_formats.hpp"
#include "libcam/io/detail/woodscape_format.hpp"
#include "libcam/io/detail/driveworks_rig.hpp"

namespace libcam::detail {

namespace {

using L = LensType;

// ---- readers and writers in the table's form ----------------------------------------------

std::string write_json(const Camera& camera, const WriteOptions& options) {
    return format_json(camera, options.look_at_camera);
}

std::string write_gl_json(const Camera& camera, const WriteOptions& options) {
    // A projection matrix is linear: it holds a pinhole, nothing more.
    if (camera.lens.type != LensType::Pinhole) {
        throw NotRepresentable("gl holds a pinhole camera only (an OpenGL projection matrix has no distortion); this "
                               "camera's lens is " + std::string(lens_info(camera.lens.type).name));
    }
    return format_gl_json(to_opengl(camera, options.gl_near, options.gl_far, options.gl_depth_range), camera.size);
}

// OpenCV's files (one camera, a stereo pair, ORB-SLAM's settings) record no look-at camera.
std::vector<NamedCamera> read_opencv_storage(std::string_view text, const ReadContext& context) {
    return parse_opencv_storage_set(text, context.source, context.options);
}

std::string write_opencv_yaml(const Camera& camera, const WriteOptions&) {
    return format_opencv_storage(camera, OpenCvStorage::Yaml);
}

std::string write_opencv_xml(const Camera& camera, const WriteOptions&) {
    return format_opencv_storage(camera, OpenCvStorage::Xml);
}

// A Blender script is Python, which libcam does not run: the JSON of the same settings
// (--from-format blender names it too) is what it reads.
std::vector<NamedCamera> read_blender_script(std::string_view text, const ReadContext& context) {
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    if (first != std::string_view::npos && text[first] == '{') return parse_blender_cameras(text, context.source);
    throw FileError(context.source + ": a Blender script is not read back; read the same settings as JSON (convert "
                    "--to blender-json), or export a .blend's cameras with tools/blender/export_cameras.py");
}

// ROS's camera_info: the keys of its rectified camera tell it from OpenCV's own YAML.
bool claims_ros_camera_info(const DocumentNode& root) {
    return root.find("projection_matrix") != nullptr || root.find("rectification_matrix") != nullptr;
}

// ---- the lens models each format holds ------------------------------------------------

constexpr L kEveryLens[] = {
#define LIBCAM_LENS_ROW(id, model) L::id,
    LIBCAM_LENS_MODEL_LIST(LIBCAM_LENS_ROW)
#undef LIBCAM_LENS_ROW
};
constexpr L kPinhole[] = {L::Pinhole};
constexpr L kOpenCvFiles[] = {L::Pinhole, L::OpenCv4, L::OpenCv5, L::OpenCv8, L::OpenCv12, L::OpenCv14, L::Fisheye};
constexpr L kCameramodel[] = {L::Pinhole,       L::OpenCv4, L::OpenCv5, L::OpenCv8, L::OpenCv12,
                              L::Stereographic, L::Lonlat,  L::Latlon,  L::Cahvor,  L::Cahvore,
                              L::SplinedStereographic};
constexpr L kKalibr[] = {L::Pinhole, L::OpenCv4, L::Fisheye, L::Fov, L::Ucm, L::Mei, L::DoubleSphere, L::Eucm};
constexpr L kBasalt[] = {L::Pinhole, L::OpenCv4, L::OpenCv5, L::OpenCv8, L::Fisheye,
                         L::DoubleSphere, L::Eucm, L::Ucm, L::Fov};
constexpr L kCamodocal[] = {L::OpenCv4, L::Mei, L::Fisheye, L::OcamCalib};
constexpr L kColmap[] = {L::Pinhole, L::OpenCv4, L::OpenCv5, L::OpenCv8, L::Fisheye, L::Fov,
                         L::ThinPrismFisheye, L::RadTanThinPrismFisheye, L::Eucm,
                         L::Division};  // SIMPLE_DIVISION, DIVISION
constexpr L kNerf[] = {L::Pinhole, L::OpenCv4, L::OpenCv5, L::BrownK4, L::Fisheye, L::Lonlat, L::RadTanThinPrismFisheye};
constexpr L kCahvor[] = {L::Pinhole, L::Cahvor, L::Cahvore, L::OpenCv4, L::OpenCv5, L::OpenCv8, L::OpenCv12};
constexpr L kRos[] = {L::Pinhole, L::OpenCv4, L::OpenCv5, L::OpenCv8, L::Fisheye};
constexpr L kEuroc[] = {L::OpenCv4, L::Fisheye};
constexpr L kOpenicc[] = {L::Pinhole, L::OpenCv4, L::OpenCv5, L::OpenCv8, L::OpenCv12, L::OpenCv14, L::Fisheye, L::DoubleSphere, L::Eucm,
                          L::Division};  // DIVISION_UNDISTORTION
constexpr L kBlender[] = {L::Pinhole, L::Equisolid, L::LensPolynomial, L::Lonlat};
constexpr L kOpenSfm[] = {L::Pinhole, L::OpenCv4, L::OpenCv5, L::Fisheye, L::Lonlat};
constexpr L kOpenMvg[] = {L::Pinhole, L::OpenCv4, L::OpenCv5, L::Fisheye, L::Lonlat};
// Metashape's spherical sensor is LONLAT with fx = fy only: not every LONLAT camera.
constexpr L kMetashape[] = {L::Pinhole, L::OpenCv4, L::OpenCv5, L::BrownK4, L::Fisheye, L::Lonlat};
// ---- photogrammetry files (AliceVision, VisualSfM, Bundler) ----
constexpr L kAliceVision[] = {L::Pinhole, L::OpenCv4, L::OpenCv5, L::Fisheye, L::Fov};
constexpr L kBundler[] = {L::Pinhole, L::OpenCv4};
// Lens databases.
constexpr L kLensfun[] = {L::Pinhole,       L::OpenCv4, L::Ptlens,      L::Fisheye,
                          L::Equisolid, L::Stereographic, L::Lonlat, L::Cylindrical,
                          L::EquidistantRadial, L::EquisolidRadial, L::StereographicRadial};
constexpr L kGyroflow[] = {L::OpenCv4, L::OpenCv5, L::OpenCv8, L::OpenCv12, L::Fisheye, L::Ptlens};
constexpr L kHuginPto[] = {L::Pinhole,   L::OpenCv4,       L::Ptlens, L::Fisheye,
                           L::Equisolid, L::Stereographic, L::Lonlat, L::Cylindrical,
                           L::EquidistantRadial, L::EquisolidRadial, L::StereographicRadial};
constexpr L kOcamCalib[] = {L::OcamCalib};
constexpr L kOcamCalibWritten[] = {L::OcamCalib, L::Pinhole};  // a pinhole: zero polynomial, identity affine
constexpr L kRealityCapture[] = {L::Pinhole, L::OpenCv4, L::OpenCv5, L::BrownK4};  // RealityCapture's XMP and CSV
constexpr L kWoodscape[] = {L::ThetaPolynomial};  // WoodScape's calibration JSON
constexpr L kDriveworksRig[] = {L::FTheta, L::FThetaForward};  // DriveWorks' ftheta cameras

using C = Content;

// ---- the most libcam reads of each format's files, and of the files read beside them ----

// mrcal's .cameramodel with its optimization_inputs (a calibration's every observation,
// base85): the largest real ones are about 1 MB.
constexpr std::uint64_t kCameramodelLargest = 256 * kMiB;
constexpr FileBeside kColmapBeside[] = {{"images and points3D (.bin or .txt)", kColmapModelPartLimit}};
constexpr FileBeside kNerfBeside[] = {{"dataparser_transforms.json", kCameraFileLimit}};
constexpr FileBeside kOpenSfmBeside[] = {{"tracks.csv", kReconstructionLimit}};
constexpr FileBeside kBundlerBeside[] = {{"list.txt", kCameraFileLimit}};

// Every format, in CameraFormat's order. Where several formats share a file ending, the
// first row whose `claims` accepts the file's keys is its format, else the row without
// `claims` (libcam's JSON for .json, OpenCV's YAML for .yaml).
constexpr FormatRow kRows[] = {
    {.format = CameraFormat::Json, .name = "json", .title = "libcam JSON",
     .description = "libcam's own JSON: K, distortion, R, t, rvec, P, fov, frustum, eye/gaze/up",
     .extensions = {".json"}, .content = static_cast<unsigned>(C::Json), .read = one_camera<parse_json_camera>,
     .write = one_file<write_json>, .lenses = kEveryLens, .lens_names = "every model libcam has",
     .camera_names = "one camera"},
    {.format = CameraFormat::OpenCvYaml, .name = "opencv-yaml", .title = "OpenCV YAML",
     .description = "OpenCV's cv::FileStorage YAML with the keys of its calibration sample; stereo pairs and "
                    "ORB-SLAM's settings too",
     .extensions = {".yaml", ".yml"}, .content = static_cast<unsigned>(C::Yaml), .read = read_opencv_storage,
     .write = one_file<write_opencv_yaml>, .read_observations = read_opencv_observations, .lenses = kOpenCvFiles,
     .lens_names = "4, 5, 8, 12 or 14 coefficients, or cv::fisheye's 4",
     .camera_names = "one camera; a stereo file's camera1 and camera2, ORB-SLAM's Camera1 and Camera2 (and LEFT, "
                     "RIGHT)"},
    {.format = CameraFormat::OpenCvXml, .name = "opencv-xml", .title = "OpenCV XML",
     .description = "the same in cv::FileStorage XML", .extensions = {".xml"},
     .content = static_cast<unsigned>(C::Xml), .read = read_opencv_storage, .write = one_file<write_opencv_xml>,
     .read_observations = read_opencv_observations, .lenses = kOpenCvFiles,
     .lens_names = "4, 5, 8, 12 or 14 coefficients, or cv::fisheye's 4",
     .camera_names = "one camera; a stereo file's camera1 and camera2, ORB-SLAM's Camera1 and Camera2 (and LEFT, "
                     "RIGHT)"},
    {.format = CameraFormat::Cameramodel, .name = "cameramodel", .title = "mrcal .cameramodel",
     .description = "mrcal's .cameramodel, read and written by libmrcal's own parser",
     .extensions = {".cameramodel"}, .content = static_cast<unsigned>(C::PythonDict),
     .largest_file = kCameramodelLargest, .read_observations = read_mrcal_observations, .lenses = kCameramodel,
     .lens_names = "mrcal's LENSMODEL_ names", .refuses = "skew", .library = "libcam::interop",
     .installer = "libcam::register_interop_formats()",
     .camera_names = "one camera"},
    {.format = CameraFormat::Gl, .name = "gl", .title = "gl JSON",
     .description = "JSON holding an OpenGL projection, view matrix and viewport", .extensions = {".json"},
     .content = static_cast<unsigned>(C::Json), .read = one_camera<parse_json_camera>,
     .write = one_file<write_gl_json>, .lenses = kPinhole, .refuses = "distortion",
     .camera_names = "one camera"},
    {.format = CameraFormat::Kalibr, .name = "kalibr", .title = "Kalibr camchain YAML",
     .description = "Kalibr's camchain and camchain-imucam YAML, also as OpenVINS ships it",
     .extensions = {".yaml", ".yml"}, .content = static_cast<unsigned>(C::Yaml), .claims = claims_kalibr_camchain,
     .telling_keys = {"cam0", "T_cn_cnm1", "T_cam_imu", "camera_model"}, .read = with_source<parse_kalibr_camchain>,
     .write = one_file<format_kalibr_camchain>, .lenses = kKalibr,
     .lens_names = "pinhole, omni, ds, eucm with radtan, equidistant, fov, none", .refuses = "skew",
     .camera_names = "cam0, cam1, ..."},
    {.format = CameraFormat::Basalt, .name = "basalt", .title = "basalt calibration JSON",
     .description = "basalt's calibration JSON (cereal's value0)", .extensions = {".json"},
     .content = static_cast<unsigned>(C::Json), .claims = claims_basalt_calibration,
     .read = with_source<parse_basalt_calibration>, .write = one_file<format_basalt_calibration>, .lenses = kBasalt,
     .lens_names = "pinhole, kb4, ds, eucm, ucm, fov, pinhole-radtan8", .refuses = "skew",
     .camera_names = "cam0, cam1, ..."},
    {.format = CameraFormat::Camodocal, .name = "camodocal", .title = "camodocal YAML",
     .description = "camodocal's YAML, as VINS-Mono and VINS-Fusion ship it", .extensions = {".yaml", ".yml"},
     .content = static_cast<unsigned>(C::Yaml), .claims = claims_camodocal,
     .telling_keys = {"model_type", "mirror_parameters", "projection_parameters", "distortion_parameters"},
     .read = with_source<parse_camodocal>,
     .read_only = true, .lenses = kCamodocal, .lens_names = "PINHOLE, MEI, KANNALA_BRANDT, SCARAMUZZA",
     .camera_names = "its camera_name"},
    {.format = CameraFormat::Colmap, .name = "colmap", .title = "COLMAP model",
     .description = "COLMAP's sparse model: cameras.txt or .bin with images.txt or .bin beside it; written as "
                    "cameras.txt, images.txt and points3D.txt into a folder",
     .extensions = {".bin"}, .content = C::Table | C::Binary, .read = read_colmap_model,
     .write = write_colmap_model, .writes_folder = true, .binary = true, .files_beside = kColmapBeside,
     .file_in_folder = colmap_cameras_file_named,
     .file_for_part = colmap_cameras_file_for,
     .read_observations = read_colmap_observations, .lenses = kColmap,
     .lens_names = "SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV, FULL_OPENCV, OPENCV_FISHEYE, "
                   "SIMPLE_RADIAL_FISHEYE, RADIAL_FISHEYE, SIMPLE_FISHEYE, FISHEYE, FOV, THIN_PRISM_FISHEYE, "
                   "RAD_TAN_THIN_PRISM_FISHEYE, EUCM, SIMPLE_DIVISION, DIVISION, "
                   "EQUIRECTANGULAR",  // LONLAT over the whole sphere
     .refuses = "skew; OPENCV12 and OPENCV14 unless their coefficients past the eighth are 0; "
                "LONLAT unless it spans the whole sphere (EQUIRECTANGULAR: fx = w / (2 pi), fy = h / pi, "
                "cx = w / 2 - 0.5, cy = h / 2 - 0.5)",
     .camera_names = "each image's NAME, or its file name alone; id:N, a camera's first image (the camera alone "
                     "when no image uses it)"},
    {.format = CameraFormat::Nerf, .name = "nerf", .title = "NeRF transforms.json",
     .description = "NeRF's transforms.json (instant-ngp, nerfstudio)", .extensions = {".json"},
     .content = static_cast<unsigned>(C::Json), .claims = claims_nerf_transforms,
     .telling_keys = {"frames", "camera_angle_x", "fl_x", "aabb_scale"}, .read = read_nerf_transforms,
     .write = one_file<write_nerf_transforms>, .files_beside = kNerfBeside, .lenses = kNerf,
     .lens_names = "OPENCV, PINHOLE, SIMPLE_PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV_FISHEYE, EQUIRECTANGULAR, "
                   "FISHEYE624; instant-ngp's is_fisheye, latlong and f-theta (read as FISHEYE_LENS_POLYNOMIAL)",
     .refuses = "skew; k4 (r^8); instant-ngp's equirectangular and orthographic lenses",
     .camera_names = "each frame's file_path, or its image's file name alone"},
    {.format = CameraFormat::Cahvor, .name = "cahvor", .title = "JPL .cahvor",
     .description = "JPL's .cahvor and .cahvore text, as mrcal writes it", .extensions = {".cahvor", ".cahvore"},
     .content = static_cast<unsigned>(C::KeyValue), .read = with_source<parse_cahvor>, .read_only = true, .lenses = kCahvor, .lens_names = "CAHV, CAHVOR, CAHVORE",
     .camera_names = "one camera"},
    {.format = CameraFormat::Ros, .name = "ros", .title = "ROS camera_info YAML",
     .description = "ROS's camera_info YAML (camera_calibration_parsers)", .extensions = {".yaml", ".yml"},
     .content = static_cast<unsigned>(C::Yaml), .claims = claims_ros_camera_info,
     .telling_keys = {"projection_matrix", "rectification_matrix", "camera_name"},
     .read = with_source<parse_ros_camera_info>, .write = one_file<format_ros_camera_info>, .lenses = kRos,
     .lens_names = "plumb_bob, rational_polynomial, equidistant",
     .refuses = "a pose (camera_info holds none: --no-pose writes the intrinsics alone)",
     .camera_names = "its camera_name; <camera_name>/rectified"},
    {.format = CameraFormat::Open3d, .name = "open3d", .title = "Open3D camera JSON",
     .description = "Open3D's PinholeCameraIntrinsic, PinholeCameraParameters and PinholeCameraTrajectory JSON",
     .extensions = {".json"}, .content = static_cast<unsigned>(C::Json), .claims = claims_open3d_camera,
     .telling_keys = {"intrinsic_matrix", "class_name"}, .read = with_source<parse_open3d_camera>,
     .write = one_file<format_open3d_camera>, .lenses = kPinhole,
     .refuses = "distortion",
     .camera_names = "one camera; a trajectory's by position only"},
    {.format = CameraFormat::Euroc, .name = "euroc", .title = "EuRoC sensor.yaml",
     .description = "the EuRoC (ASL) dataset's camera sensor.yaml", .extensions = {".yaml", ".yml"},
     .content = static_cast<unsigned>(C::Yaml), .claims = claims_euroc_sensor, .telling_keys = {"T_BS", "sensor_type"},
     .read = with_source<parse_euroc_sensor>,
     .read_only = true, .lenses = kEuroc,
     .lens_names = "pinhole with radial-tangential or equidistant",
     .camera_names = "its comment"},
    {.format = CameraFormat::Openicc, .name = "openicc", .title = "OpenImuCameraCalibrator JSON",
     .description = "OpenImuCameraCalibrator's JSON, as UMI ships its GoPro calibrations", .extensions = {".json"},
     .content = static_cast<unsigned>(C::Json), .claims = claims_openicc_camera,
     .read = with_source<parse_openicc_camera>, .read_only = true, .lenses = kOpenicc,
     .lens_names = "FISHEYE, DOUBLE_SPHERE, EUCM, PINHOLE, DIVISION_UNDISTORTION (with fx = fy, as DIVISION)",
     .camera_names = "one camera"},
    {.format = CameraFormat::Blender, .name = "blender", .title = "Blender camera script",
     .description = "a Python script that sets a Blender scene's camera: blender -b scene.blend -P camera.py",
     .extensions = {".py"}, .content = static_cast<unsigned>(C::Python), .read = read_blender_script,
     .write = one_file<format_blender_script>, .write_only = true, .lenses = kBlender,
     .lens_names = "PERSP, and the panoramic FISHEYE_EQUISOLID, FISHEYE_LENS_POLYNOMIAL (fx != fy as the pixel "
                   "aspect for these three), EQUIRECTANGULAR, FISHEYE_EQUIDISTANT (FISHEYE with its coefficients 0)",
     .refuses = "skew, an equidistant fisheye with W / fx != H / fy",
     .camera_names = "each camera's name; <name>@<frame> for a frame of an animated one"},
    {.format = CameraFormat::BlenderJson, .name = "blender-json", .title = "Blender camera JSON",
     .description = "the same settings as JSON, in bpy's names (also what tools/blender/export_cameras.py writes)",
     .extensions = {".json"}, .content = static_cast<unsigned>(C::Json), .claims = claims_blender_cameras,
     .read = with_source<parse_blender_cameras>, .write = one_file<format_blender_json>, .lenses = kBlender,
     .lens_names = "as for blender", .refuses = "skew, an equidistant fisheye with W / fx != H / fy",
     .camera_names = "each camera's name; <name>@<frame> for a frame of an animated one"},
    {.format = CameraFormat::OpenSfm, .name = "opensfm", .title = "OpenSfM reconstruction.json",
     .description = "OpenSfM's reconstruction.json (tracks.csv beside it holds the observations), and the camera "
                    "dictionaries of camera_models.json and OpenDroneMap's cameras.json",
     .extensions = {".json"}, .content = static_cast<unsigned>(C::Json), .claims = claims_opensfm,
     .telling_keys = {"shots", "points", "projection_type"}, .read = read_opensfm, .read_only = true,
     .largest_file = kReconstructionLimit.max_bytes, .files_beside = kOpenSfmBeside,
     .read_observations = read_opensfm_observations, .lenses = kOpenSfm,
     .lens_names = "perspective, brown, radial, simple_radial, fisheye, fisheye_opencv, spherical",
     .refuses = "fisheye62, fisheye624, dual",
     .camera_names = "each shot's name (its image), or the image's file name alone; a camera's id (its first "
                     "shot)"},
    {.format = CameraFormat::OpenMvg, .name = "openmvg", .title = "OpenMVG sfm_data.json",
     .description = "OpenMVG's sfm_data.json: views, intrinsics, extrinsics and the structure's observations",
     .extensions = {".json"}, .content = static_cast<unsigned>(C::Json), .claims = claims_openmvg,
     .telling_keys = {"sfm_data_version", "root_path", "extrinsics"}, .read = read_openmvg, .read_only = true,
     .largest_file = kReconstructionLimit.max_bytes, .read_observations = read_openmvg_observations, .lenses = kOpenMvg,
     .lens_names = "pinhole, pinhole_radial_k1, pinhole_radial_k3, pinhole_brown_t2, fisheye, spherical",
     .refuses = "any other intrinsic type",
     .camera_names = "each view's filename, or its image's file name alone, posed or not; id:N, an intrinsic's "
                     "first view"},
    {.format = CameraFormat::GsCameras, .name = "gs-cameras", .title = "3D Gaussian Splatting cameras.json",
     .description = "the cameras.json 3D Gaussian Splatting writes beside its model: per image a size, fx, fy, "
                    "centre and rotation",
     .extensions = {".json"}, .content = static_cast<unsigned>(C::Json), .claims = claims_gs_cameras,
     .telling_keys = {"img_name"}, .read = read_gs_cameras, .read_only = true, .lenses = kPinhole,
     .lens_names = "a pinhole with its principal point at the image centre", .refuses = "distortion",
     .camera_names = "each image's img_name"},
    {.format = CameraFormat::Llff, .name = "llff", .title = "LLFF poses_bounds.npy",
     .description = "LLFF's poses_bounds.npy (imgs2poses.py), as NeRF's LLFF scenes ship it: per image a 3x5 "
                    "matrix of rotation, centre and H, W, focal, then near and far",
     .extensions = {".npy"}, .content = static_cast<unsigned>(C::Binary), .read = read_llff_poses,
     .read_only = true, .binary = true, .lenses = kPinhole,
     .lens_names = "a pinhole with one focal length, its principal point at the image centre",
     .refuses = "distortion",
     .camera_names = "each row's number (0, 1, ...)"},
    {.format = CameraFormat::Metashape, .name = "metashape", .title = "Agisoft Metashape XML",
     .description = "Agisoft Metashape's (PhotoScan's) cameras.xml from Export Cameras (PhotoScan 0.9's "
                    "<collection> too), and its Export Calibration XML",
     .extensions = {".xml"}, .content = static_cast<unsigned>(C::Xml), .claims = claims_metashape,
     .telling_keys = {"document", "calibration", "collection"}, .read = read_metashape, .write = one_file<format_metashape>,
     .largest_file = kReconstructionLimit.max_bytes, .lenses = kMetashape,
     .lens_names = "frame (f cx cy b1 b2 k1..k4 p1 p2, P1 and P2 swapped against OpenCV's; BROWN_K4 when k4 is not "
                   "0), fisheye, spherical "
                   "(LONLAT with fx = fy); PhotoScan 0.9's fx fy cx cy skew k1..k3 p1 p2 (cx, cy absolute, P1 and "
                   "P2 in OpenCV's order); written as cameras.xml, or with --no-pose as Export Calibration's file",
     .refuses = "tangential terms on a fisheye, cylindrical and RPC sensors",
     .camera_names = "each camera's label, aligned or not; a sensor's label (its first camera)"},
    // ---- photogrammetry files (AliceVision, VisualSfM, Bundler) ----
    {.format = CameraFormat::AliceVision, .name = "alicevision", .title = "AliceVision SfMData",
     .description = "AliceVision's (Meshroom's) SfMData JSON, cameras.sfm: views, intrinsics, poses and the "
                    "structure's observations; written as one view",
     .extensions = {".sfm", ".json"}, .content = static_cast<unsigned>(C::Json), .claims = claims_alicevision,
     .telling_keys = {"featuresFolders", "matchesFolders", "poses"}, .read = read_alicevision,
     .write = one_file<format_alicevision>,
     .largest_file = kReconstructionLimit.max_bytes, .read_observations = read_alicevision_observations,
     .lenses = kAliceVision,
     .lens_names = "pinhole, radial1, radial3, brown, fisheye4, fisheye1 (and radialk3pt; equidistant and "
                   "equidistant_r3 read as FISHEYE)",
     .refuses = "skew; the 3DE models and undistortion maps",
     .camera_names = "each view's path, or its image's file name alone, posed or not; id:N, an intrinsic's "
                     "first view"},
    {.format = CameraFormat::Nvm, .name = "nvm", .title = "VisualSfM NVM",
     .description = "VisualSfM's .nvm (NVM_V3): cameras, points and their measurements; the image size is given "
                    "(--image-size), the file has none",
     .extensions = {".nvm"}, .content = static_cast<unsigned>(C::Table), .read = read_nvm, .read_only = true,
     .largest_file = kReconstructionLimit.max_bytes, .read_observations = read_nvm_observations, .lenses = kPinhole,
     .lens_names = "a pinhole per image, its principal point at the image centre",
     .refuses = "a camera with VisualSfM's measurement distortion (its observations are read undistorted), FixedK",
     .camera_names = "each image's file name as the file gives it, or its file name alone"},
    {.format = CameraFormat::Bundler, .name = "bundler", .title = "Bundler bundle.out",
     .description = "Bundler's bundle.out (v0.3): f k1 k2, R, t per image, points and their views; names from "
                    "list.txt beside it; the image size is given (--image-size), the file has none",
     .extensions = {".out"}, .content = static_cast<unsigned>(C::Table), .read = read_bundler, .read_only = true,
     .largest_file = kReconstructionLimit.max_bytes, .files_beside = kBundlerBeside,
     .read_observations = read_bundler_observations, .lenses = kBundler,
     .lens_names = "f, k1, k2: OPENCV4 with p1 = p2 = 0, its principal point at the image centre",
     .camera_names = "each image's name from list.txt, or its file name alone"},
    // Lens databases.
    {.format = CameraFormat::Lensfun, .name = "lensfun", .title = "lensfun database XML",
     .description = "lensfun's lens database (data/db/*.xml): one lens at one focal length, crop factor and image "
                    "size (--lens, --focal, --crop-factor, --image-size)",
     .extensions = {".xml"}, .content = static_cast<unsigned>(C::Xml), .claims = claims_lensfun,
     .telling_keys = {"lensdatabase"}, .read = read_lensfun, .read_only = true, .lenses = kLensfun,
     .lens_names = "poly3 and poly5 (OpenCV's k1 k2 once rescaled), ptlens (PTLENS); fisheye, equisolid and "
                   "stereographic with any of them (EQUIDISTANT_RADIAL or FISHEYE, EQUISOLID_RADIAL, "
                   "STEREOGRAPHIC_RADIAL); equirectangular and panoramic without distortion",
     .refuses = "acm, orthographic and fisheye_thoby lenses, distortion on equirectangular and panoramic ones",
     .camera_names = "one lens (chosen by --lens)"},
    {.format = CameraFormat::HuginPto, .name = "hugin", .title = "Hugin project",
     .description = "Hugin's (PanoTools') .pto project: one camera per image line (w h f v a b c d e), posed in the "
                    "panorama by its y p r and TrX TrY TrZ",
     .extensions = {".pto"}, .content = static_cast<unsigned>(C::Table), .read = read_hugin_pto, .read_only = true,
     .lenses = kHuginPto,
     .lens_names = "f0 with a b c (PTLENS; OPENCV4 when a = c = 0), f2/f3 fisheye with a b c (EQUIDISTANT_RADIAL; "
                   "FISHEYE when a = c = 0), f21 and f10 with a b c (EQUISOLID_RADIAL, STEREOGRAPHIC_RADIAL), f1 "
                   "and f4 without distortion",
     .refuses = "shear (g t), other projections, a b c on f1 and f4",
     .camera_names = "each image line's n\"name\", or its file name alone"},
    {.format = CameraFormat::Gyroflow, .name = "gyroflow", .title = "Gyroflow lens profile",
     .description = "Gyroflow's lens profile JSON (calib_dimension, fisheye_params, distortion_model)",
     .extensions = {".json"}, .content = static_cast<unsigned>(C::Json), .claims = claims_gyroflow,
     .telling_keys = {"calib_dimension", "fisheye_params", "calibrator_version", "use_opencv_fisheye"},
     .read = read_gyroflow, .read_only = true, .lenses = kGyroflow,
     .lens_names = "opencv_fisheye (FISHEYE), opencv_standard (OpenCV's 12), poly3, poly5 (OPENCV4), ptlens (PTLENS)",
     .refuses = "anamorphic stretch, GoPro, Insta360, Sony and Gyroflow's other models",
     .camera_names = "one camera, named by its brand, model, lens and setting"},
    // ---- OCamCalib (Scaramuzza's omnidirectional model) ----
    {.format = CameraFormat::OcamCalib, .name = "ocamcalib", .title = "OCamCalib calib_results.txt",
     .description = "the OCamCalib MATLAB toolbox's calib_results.txt (export_data): pol, invpol, centre, affine, "
                    "size", .content = static_cast<unsigned>(C::OcamText), .read = read_ocamcalib,
     .write = one_file<write_ocamcalib>, .lenses = kOcamCalibWritten,
     .lens_names = "Scaramuzza's polynomial up to degree 5 (the toolbox's default is 4), with its affine; a "
                   "pinhole written as one (read back as OCAMCALIB)",
     .refuses = "skew, a pose (--no-pose writes the intrinsics alone); invpol is written fitted as the toolbox fits it",
     .camera_names = "one camera"},
    {.format = CameraFormat::PyOcamCalib, .name = "py-ocamcalib", .title = "py-OCamCalib JSON",
     .description = "py-OCamCalib's calibration JSON (taylor_coefficient, distortion_center, stretch_matrix); it "
                    "stores no image size: give --image-size", .extensions = {".json"},
     .content = static_cast<unsigned>(C::Json), .claims = claims_py_ocamcalib,
     .telling_keys = {"taylor_coefficient", "distortion_center", "stretch_matrix", "inverse_poly"},
     .read = read_py_ocamcalib,
     .read_only = true, .lenses = kOcamCalib, .lens_names = "Scaramuzza's polynomial up to degree 5",
     .camera_names = "one camera, named by its camera_name"},
    // RealityCapture's XMP sidecars.
    {.format = CameraFormat::RealityCapture, .name = "realitycapture", .title = "RealityCapture XMP",
     .description = "RealityCapture's (RealityScan's) XMP sidecar of an image: its pose and calibration (the image "
                    "size given with --image-size)",
     .extensions = {".xmp"}, .content = static_cast<unsigned>(C::Xml), .claims = claims_realitycapture_xmp,
     .read = read_realitycapture_xmp, .read_only = true, .lenses = kRealityCapture,
     .lens_names = "perspective, brown3, brown4 and brown3t2, brown4t2 (t1 t2 swapped against OpenCV's p1 p2; "
                   "BROWN_K4 when k4 is not 0)",
     .refuses = "skew, division with a coefficient other than 0",
     .camera_names = "one camera"},
    {.format = CameraFormat::RealityCaptureCsv, .name = "realitycapture-csv", .title = "RealityCapture CSV",
     .description = "RealityCapture's (RealityScan's) CSV of internal/external camera parameters: per image x, y, "
                    "alt, heading, pitch, roll, f, px, py, k1..k4, t1, t2 (the image size given with --image-size)",
     .extensions = {".csv"}, .content = static_cast<unsigned>(C::Table), .read = read_realitycapture_csv,
     .read_only = true, .lenses = kRealityCapture,
     .lens_names = "Brown's k1 k2 k3 k4 t1 t2 (t1 t2 swapped against OpenCV's p1 p2; BROWN_K4 when k4 is not 0), "
                   "as the XMP's",
     .refuses = "py other than 0 (its sign is not documented); longitude and latitude (a geographic export)",
     .camera_names = "each row's name, or its file name alone"},
    // ---- WoodScape's calibration JSON
    {.format = CameraFormat::Woodscape, .name = "woodscape", .title = "WoodScape calibration JSON",
     .description = "Valeo's WoodScape dataset's calibration JSON (radial_poly fisheye, camera-to-vehicle extrinsic)",
     .extensions = {".json"}, .content = static_cast<unsigned>(C::Json), .claims = claims_woodscape_camera,
     .telling_keys = {"intrinsic", "cx_offset"}, .read = with_source<parse_woodscape_camera>,
     .write = one_file<format_woodscape_camera>, .lenses = kWoodscape,
     .lens_names = "radial_poly", .refuses = "skew",
     .camera_names = "one camera, named by its name"},
    // ---- NVIDIA DriveWorks' rig.json
    {.format = CameraFormat::DriveworksRig, .name = "driveworks-rig", .title = "DriveWorks rig JSON",
     .description = "NVIDIA DriveWorks' rig.json: its F-theta camera sensors, each placed in the rig's FLU frame",
     .extensions = {".json"}, .content = static_cast<unsigned>(C::Json), .claims = claims_driveworks_rig,
     .telling_keys = {"rig"}, .read = with_source<parse_driveworks_rig>, .write = one_file<format_driveworks_rig>,
     .lenses = kDriveworksRig,
     .lens_names = "ftheta (pixeldistance-to-angle or angle-to-pixeldistance polynomial, linear-c d e)",
     .refuses = "skew, max_angle other than pi",
     .camera_names = "each camera sensor's name"},
};

// Every CameraFormat has its row, in the enum's order: a format added to the enum without
// a row, or given two, stops the build here.
constexpr bool rows_match_formats() {
    if (std::size(kRows) != kCameraFormatCount) return false;
    for (std::size_t i = 0; i < std::size(kRows); ++i) {
        if (static_cast<std::size_t>(kRows[i].format) != i) return false;
    }
    return true;
}
static_assert(rows_match_formats(), "every CameraFormat needs exactly one row, in the enum's order");


}  // namespace

std::span<const FormatRow> format_rows() { return kRows; }

void refuse_lens(CameraFormat format, LensType type) {
    const FormatRow& row = kRows[static_cast<std::size_t>(format)];
    std::string held;
    for (std::size_t i = 0; i < row.lenses.size(); ++i) {
        const bool last = i + 1 == row.lenses.size();
        held += std::string(i == 0 ? "" : last ? " and " : ", ") + std::string(lens_info(row.lenses[i]).name);
    }
    throw NotRepresentable(std::string(row.title) + " has no model for a " + std::string(lens_info(type).name) +
                           " lens (it holds " + held + ")");
}

}  // namespace libcam::detail
