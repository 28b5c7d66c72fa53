#pragma once
// COLMAP's sparse model: cameras.txt or cameras.bin (the intrinsics, one line or record
// per camera id), with images.txt or images.bin beside it (each image's pose and the id
// of the camera that took it).
//
//   cameras.txt   CAMERA_ID MODEL WIDTH HEIGHT PARAMS...      (# comments)
//   images.txt    IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME, then a line of 2-D points
//
// Conventions: COLMAP's pixel (0, 0) is the top-left corner of the image, so its cx, cy
// are libcam's plus 0.5 (libcam's pixel centres are at integers). The pose is
// world-to-camera (X_cam = R(q) X + t), libcam's own direction, with the quaternion
// written w first. Models: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV,
// FULL_OPENCV, OPENCV_FISHEYE, SIMPLE_RADIAL_FISHEYE, RADIAL_FISHEYE, FOV,
// THIN_PRISM_FISHEYE and RAD_TAN_THIN_PRISM_FISHEYE, each read as the libcam model that
// holds it exactly (SIMPLE_RADIAL is OPENCV4 with k2 = p1 = p2 = 0, RADIAL_FISHEYE is
// FISHEYE with k3 = k4 = 0, ...).
//
// Reading gives one camera per image, named by the image's name, with its camera's
// intrinsics (intrinsics_name "id:N") and its pose; cameras no image uses, and every
// camera when there is no images file, are named "id:N" and have no pose.
//
// Writing gives cameras.txt and images.txt: camera 1 and image 1 (named by
// WriteOptions::image_name) holding the camera and its pose, and an empty points3D.txt
// (COLMAP's programs load a model only with one). PINHOLE, OPENCV4, OPENCV5
// and OPENCV8 (as FULL_OPENCV with the missing coefficients 0), OPENCV12 and OPENCV14
// when their extra coefficients are 0, FISHEYE, FOV, THIN_PRISM_FISHEYE and
// RAD_TAN_THIN_PRISM_FISHEYE (COLMAP 3.10 and later); skew and any other model are
// refused.

#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/format_table.hpp"

namespace libcam {

// The files of a model, parsed as COLMAP stores them (ids, COLMAP's pixels), for the
// readers of the model's cameras (below) and of its observations (colmap_observations.hpp).

// One line or record of cameras.txt or cameras.bin.
struct ColmapCameraRecord {
    std::uint64_t id;
    Camera camera;  // at the origin
    std::string_view model = {};  // COLMAP's name of the file's model (colmap_models()'s table)
};

// POINT3D_ID of a 2-D point that is no 3-D point's: -1 in text, its 64-bit pattern in binary.
inline constexpr std::uint64_t kColmapNoPoint3D = std::numeric_limits<std::uint64_t>::max();

// One of an image's POINTS2D: COLMAP's pixel (top-left pixel's centre at (0.5, 0.5)).
struct ColmapPoint2D {
    double x;
    double y;
    std::uint64_t point3d_id;  // kColmapNoPoint3D for none
};

// One image of images.txt or images.bin.
struct ColmapImage {
    std::uint64_t id;
    std::uint64_t camera_id;
    std::string name;
    Pose pose;                          // world to camera
    std::vector<ColmapPoint2D> points;  // read only when asked for
    std::string where;                  // "<file>: line 5: image 3", for messages
};

// points3D.txt or points3D.bin, one entry per point, tracks flattened.
struct ColmapPoints3D {
    struct TrackElement {
        std::uint32_t image_id;
        std::uint32_t point2d_index;
    };
    std::vector<std::uint64_t> ids;
    std::vector<Vec3> xyz;
    std::vector<double> errors;  // COLMAP's ERROR: -1 where it has none
    std::vector<std::array<std::uint8_t, 3>> colours;  // R, G, B
    // Point i's track is track[track_begin[i] .. track_begin[i + 1]).
    std::vector<std::size_t> track_begin{0};
    std::vector<TrackElement> track;
};

// Each file's records, `binary` saying which form (.bin or .txt); a text file is checked to
// be text first. Throws FileError naming the file, the line or byte, the field and the value.
std::vector<ColmapCameraRecord> read_colmap_cameras(std::string_view bytes, const std::string& source, bool binary);
// `with_points`: keep each image's POINTS2D (the camera reader needs only the poses).
std::vector<ColmapImage> read_colmap_images(std::string_view bytes, const std::string& source, bool binary,
                                            bool with_points);
ColmapPoints3D read_colmap_points3d(std::string_view bytes, const std::string& source, bool binary);

// cameras.txt, images.txt and points3D.txt holding the camera. Throws NotRepresentable for what
// COLMAP cannot hold.
std::vector<CameraFileText> write_colmap_model(const Camera& camera, const WriteOptions& options);

// A whole model's three files (cameras, images, points3D), text or binary, as COLMAP
// writes them: each camera by the COLMAP model that holds its lens exactly
// (colmap_from_camera), pixels in COLMAP's convention as the records hold them, every
// image with its POINTS2D. Throws NotRepresentable for a camera COLMAP cannot hold.
struct ColmapModelBytes {
    std::string cameras, images, points3d;
};
ColmapModelBytes write_colmap_files(const std::vector<ColmapCameraRecord>& cameras, const std::vector<ColmapImage>& images,
                                    const ColmapPoints3D& points, bool binary);

// The cameras file of a COLMAP model folder (cameras.bin, else cameras.txt), or empty.
std::filesystem::path colmap_cameras_file_in(const std::filesystem::path& folder);

// The COLMAP model a folder names: the folder itself when it holds a cameras file, else
// the one model folder inside it (a workspace's sparse/, holding 0/). Empty when it holds
// none; throws FileError naming them when it holds several ("sparse holds 2 COLMAP models
// (0, 1): name one, e.g. sparse/0"). Every command that takes a model folder asks here.
std::filesystem::path colmap_model_folder(const std::filesystem::path& folder);
// What a folder holding neither is told, after its name.
inline constexpr std::string_view kNoColmapModel =
    "not a COLMAP model folder (it has no cameras.bin or cameras.txt, nor a folder inside that has)";
// The cameras file of colmap_model_folder(folder), or empty.
std::filesystem::path colmap_cameras_file_named(const std::filesystem::path& folder);

// For another file of a COLMAP model (images, points3D, frames or rigs, .txt or .bin):
// the cameras file beside it (the same form first), or empty.
std::filesystem::path colmap_cameras_file_for(const std::filesystem::path& part);

}  // namespace libcam
