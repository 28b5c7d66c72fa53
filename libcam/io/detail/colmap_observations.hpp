#pragma once
// The observations of a COLMAP sparse model (sparse/0): every camera of cameras.txt/.bin,
// every image of images.txt/.bin as a view (its NAME, its camera, its world-to-camera pose
// as COLMAP stores it), every point of points3D.txt/.bin (XYZ, POINT3D_ID, ERROR), and
// every 2-D point of an image whose POINT3D_ID is not -1 as an observation, in OpenCV's
// pixels (COLMAP's minus 0.5). The model is read and checked by the reader every command
// shares (colmap_model.hpp).
//
// What COLMAP stored about its fit: the mean of points3D's ERROR column (points whose
// ERROR is -1 have none, as COLMAP's Point3D::HasError says), which `colmap
// model_analyzer` prints as "Mean reprojection error", and each point's ERROR.
//
// COLMAP 3.12 and later write rigs.bin and frames.bin beside the three files; images.bin
// and images.txt kept their layout and still hold each registered image's composed
// cam_from_world (WriteImagesBinary in src/colmap/scene/reconstruction_io_binary.cc, 3.12.0
// to 4.1), which COLMAP recomposes from the frame's rig_from_world and the rig's
// sensor_from_rig on reading. The two agree for every model COLMAP writes, so the rig and
// frame files are not read.

#include <filesystem>

#include "libcam/io/observations.hpp"

namespace libcam {

// `file`: any file of the model (cameras.bin, images.txt, ...); its extension says whether
// the .bin or the .txt files are read, and all three must be there.
ObservationSet read_colmap_observations(const std::filesystem::path& file, std::string_view text,
                                        const ObservationReadOptions& options);

}  // namespace libcam
