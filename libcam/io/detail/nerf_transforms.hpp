#pragma once
// NeRF's transforms.json, as NeRF's synthetic scenes, instant-ngp and nerfstudio write it.
//
// Intrinsics, at the top level and overridden per frame:
//   w, h                 the image size (NeRF's synthetic scenes leave it out: then
//                        ReadOptions::size, or the first frame's image, or a refusal)
//   fl_x, fl_y, cx, cy   the focal lengths and principal point, in pixels whose (0, 0) is
//                        the image's top-left corner (as COLMAP's): libcam's cx is cx - 0.5
//   camera_angle_x/_y    the field of view from image edge to image edge, used where
//                        fl_x/fl_y are not given: fx = w / (2 tan(angle / 2)); without
//                        cx, cy the principal point is the image centre ((w - 1) / 2 in
//                        libcam's pixels, where Blender rendered NeRF's synthetic scenes),
//                        or on request (NerfPrincipalPoint::HalfSize) w / 2, where NeRF's own
//                        ray code puts it
//   camera_model         per frame or at the top level (nerfstudio reads it at the top only):
//                        OPENCV (the default), PINHOLE, SIMPLE_PINHOLE, SIMPLE_RADIAL and
//                        RADIAL (nerfstudio's perspective camera under COLMAP's names, all
//                        read alike): k1 k2 p1 p2 and k3, or nerfstudio's distortion_params
//                        [k1, k2, k3, k4, p1, p2]; nerfstudio's k4 multiplies r^8 (its
//                        radial factor 1 + k1 r^2 + ... + k4 r^8): BROWN_K4, or OPENCV5,
//                        OPENCV4, PINHOLE when k4, then k3, then all are 0.
//                        OPENCV_FISHEYE (k1..k4: FISHEYE, as COLMAP's; instant-ngp's
//                        "is_fisheye": true says the same).
//                        EQUIRECTANGULAR (nerfstudio's: LONLAT with libcam's fx = fl_x / pi).
//                        FISHEYE624 (Project Aria's, with distortion_params k0..k5 p0 p1
//                        s0..s3: nerfstudio's fisheye624_project is COLMAP's
//                        RAD_TAN_THIN_PRISM_FISHEYE term for term, in the same order).
//   latlong              instant-ngp's equirectangular image (any value: instant-ngp asks
//                        only whether the key is there): longitude spans the width's 2 pi
//                        and latitude the height's pi about the image centre, whatever the
//                        focal lengths say: LONLAT with fx = w / (2 pi), fy = h / pi.
//   ftheta_p0..p4        instant-ngp's f-theta lens: the angle from the axis
//                        alpha = p0 + p1 r + ... + p4 r^4 of the distance r in pixels from
//                        (cx, cy), whatever the focal lengths say: FISHEYE_LENS_POLYNOMIAL
//                        (Blender's theta = -(k0 + k1 r + ...)) with k = -p and fx = fy = 1.
//                        Read only (written, such a lens is refused).
//   equirectangular, orthographic: instant-ngp's other lenses (the height linear in
//                        sin(latitude); parallel rays), which libcam has no model for: refused.
//                        instant-ngp's order holds: latlong, then these, then f-theta, then
//                        the OpenCV models.
//
// Poses: each frame's transform_matrix is camera-to-world with OpenGL's camera axes (x
// right, y up, z backwards); libcam's pose is its inverse with OpenCV's axes. Rotations
// printed in float32 are read as the nearest rotation (geometry/pose.hpp).
//
// The world: nerfstudio moves the source's world (its COLMAP model's) before it writes
// the frames and the sparse points of ply_file_path, and records how as
// "applied_transform" (3x4 [A | b]) and "applied_scale" s: x_frames = s (A x_source + b).
// Its trainer records the whole move to its training world the same way in
// dataparser_transforms.json ("transform", "scale"), in its output folder, beside the poses
// it exports. libcam reports every pose in the SOURCE world (the one to compare with the
// COLMAP model the frames came from): x_source = A^T (x_frames / s - b); A must be a
// rotation. A dataparser_transforms.json beside the transforms.json read says its frames
// are in the training world; a file with both is refused (which move came first is not
// recorded). NerfWorld keeps the move as read, so that writing the frames back
// (write_nerf_scene) gives the same numbers.
//
// Reading gives one camera per frame, named by its file_path; a file without frames
// gives one camera without a pose. Writing one camera (write_nerf_transforms) gives one
// frame (WriteOptions::image_name) with fl_x, fl_y, cx, cy, w, h, the camera_angle_x/_y
// NeRF's own code reads, and the coefficients: PINHOLE, the OPENCV models up to k3 (higher
// ones when their extra coefficients are 0), FISHEYE, LONLAT and RAD_TAN_THIN_PRISM_FISHEYE
// (FISHEYE624); skew is refused.

#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> read_nerf_transforms(std::string_view text, const ReadContext& context);
std::string write_nerf_transforms(const Camera& camera, const WriteOptions& options);

// How the frames' world was moved from the source world: x_frames = scale (A x_source + b),
// transform = [A | b] (above).
struct NerfWorld {
    enum class Source {
        None,                  // the frames are in the source world
        AppliedTransform,      // the file's own applied_transform and/or applied_scale
        DataparserTransforms,  // dataparser_transforms.json beside the file
    };
    Source source = Source::None;
    Eigen::Matrix<double, 3, 4> transform = Eigen::Matrix<double, 3, 4>::Identity();
    double scale = 1.0;
    bool has_transform = false;  // applied_transform given (applied_scale alone is allowed)
    bool has_scale = false;      // applied_scale given
};

// The name nerfstudio's trainer gives its record of the world's move.
inline constexpr const char* kDataparserTransformsName = "dataparser_transforms.json";

// A frame's pose in the source world from the one in the frames' world, and back.
Pose nerf_pose_to_source(const Pose& frames_pose, const NerfWorld& world);
Pose nerf_pose_to_frames(const Pose& source_pose, const NerfWorld& world);

// Every frame (as read_nerf_transforms gives them, poses in the source world) and the
// world they were moved from.
struct NerfScene {
    std::vector<NamedCamera> cameras;
    std::vector<bool> posed;  // whether each frame has a transform_matrix (else its pose is the identity)
    NerfWorld world;
};
NerfScene read_nerf_scene(std::string_view text, const ReadContext& context);

// A transforms.json of every camera (named by its file_path), each frame with its own
// intrinsics, the poses moved into `world`'s frames world, and the move written back the
// way it was read: applied_transform / applied_scale, or (Source::DataparserTransforms) a
// second file, dataparser_transforms.json, to write beside it. Throws NotRepresentable for
// a lens transforms.json cannot hold (as write_nerf_transforms). A ply_file_path that is not
// empty is written as nerfstudio's key of that name (the frames' world's points). Each
// frame's mask_path (nerfstudio's: 0 where a pixel is ignored) is mask_paths' entry of
// the same index, when mask_paths is not empty.
std::vector<CameraFileText> write_nerf_scene(const std::vector<NamedCamera>& cameras, const NerfWorld& world,
                                             const std::string& ply_file_path = {},
                                             const std::vector<std::string>& mask_paths = {});

// Whether a parsed JSON file is a transforms.json: an object with "frames", "camera_angle_x" or
// "fl_x" and without libcam's "K".
bool claims_nerf_transforms(const DocumentNode& root);

}  // namespace libcam
