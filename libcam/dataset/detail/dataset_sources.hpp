#pragma once
// The sources and outputs of `libcam dataset` besides COLMAP's model (colmap_dataset.hpp):
// NeRF's transforms.json (io/detail/nerf_transforms.hpp), as nerfstudio and instant-ngp
// read it, taken in as COLMAP's records so that one pipeline makes the pinholes.
//
// A transforms.json source: each frame's camera (its own intrinsics, any camera_model
// libcam reads) and pose, in the source world (the move nerfstudio recorded undone);
// frames with identical intrinsics share one camera (ids 1, 2, ... in the order first
// met); images numbered 1, 2, ... in the file's order; no 3-D points, so no observations.
// Each image's name is its file_path relative to the json's folder, made plain
// ("./images/a.png" is "images/a.png"); when every frame's image is under images/ (as
// nerfstudio's and instant-ngp's tools lay a dataset out) that folder is the images'
// folder and the names are relative to it, so the output's images/ holds them as they
// were. A file_path outside the json's folder (absolute, or through "..") is refused as
// COLMAP's NAME is (dataset_paths.hpp): the output keeps each image under its name.
//
// A transforms.json output: one frame per image with the new pinhole's w, h, fl_x, fl_y,
// cx, cy (per frame; camera_model at the top level, where nerfstudio reads it), file_path
// "images/<name>", and the pose as camera-to-world with OpenGL's axes, moved into the
// world the source's frames were in (its applied_transform / applied_scale written back,
// or its dataparser_transforms.json written beside); with the model's points, when it
// has any, in sparse_pc.ply (nerfstudio's ply_file_path: ASCII x y z and colour, in the
// frames' world).

#include <filesystem>
#include <string>
#include <vector>

#include "libcam/io/detail/colmap_format.hpp"
#include "libcam/io/detail/nerf_transforms.hpp"

namespace libcam {

// What the dataset command reads: COLMAP's records, wherever they came from.
struct DatasetModel {
    std::vector<ColmapCameraRecord> cameras;
    std::vector<ColmapImage> images;
    ColmapPoints3D points;
    NerfWorld world;                       // a transforms.json's move (none for COLMAP)
    std::filesystem::path images_folder;  // the folder the images' names are relative to, when the source says
};

// Whether `source` is a transforms.json (a .json file) rather than a COLMAP model folder.
bool is_nerf_dataset_source(const std::filesystem::path& source);

// The frames of a transforms.json as COLMAP's records (above). Throws FileError naming the
// file and the frame for a file of no frames, a frame without file_path, or one outside
// the json's folder.
DatasetModel read_nerf_dataset(const std::filesystem::path& json);

// The folder a transforms.json's images are in (DatasetModel::images_folder), without
// reading its cameras.
std::filesystem::path nerf_dataset_images_folder(const std::filesystem::path& json);

// OUT/transforms.json (and what else write_nerf_scene gives), and OUT/sparse_pc.ply when
// `points` has any: the images' new cameras, named "images/<name>", each frame with
// mask_path "masks/<name>.png" when `masks` (the masks the dataset writes). Returns the
// names of the files written, transforms.json (which names the images) last.
std::vector<std::filesystem::path> write_nerf_dataset(const std::filesystem::path& output, const std::vector<ColmapCameraRecord>& cameras,
                        const std::vector<ColmapImage>& images, const ColmapPoints3D& points, const NerfWorld& world,
                        bool masks = false);

// The name of the points file write_nerf_dataset writes.
inline constexpr const char* kNerfPointsName = "sparse_pc.ply";

}  // namespace libcam
