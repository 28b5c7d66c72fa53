#pragma once
// The output side of plan_dataset (colmap_dataset.hpp): what a run writes and where, checked
// before anything is written (dataset_paths.hpp), the image tasks, and the model written to
// the staging folder (dataset_staging.hpp).

#include <string>
#include <vector>

#include "libcam/dataset/colmap_dataset.hpp"
#include "libcam/io/detail/colmap_format.hpp"
#include "libcam/io/detail/nerf_transforms.hpp"

namespace libcam {

// The run's files: the model's (COLMAP's; NeRF's are known once written), the output
// images' names and the stamp of what makes them (none without images).
DatasetStaging dataset_staging(const DatasetOptions& options, const std::vector<ColmapImage>& images,
                               const std::vector<ColmapCameraRecord>& cameras, const std::vector<DatasetCamera>& chosen);

// Throws FileError unless every folder the run writes into stays inside the output folder
// (and the staging folder's inside it), and the source images and model are not what the
// output replaces.
void check_output_folders(const DatasetOptions& options, const DatasetStaging& staging);

// One task per output image not already made by an earlier run (counted in
// summary.images_kept), in camera order; `source_names[i]`: output image i's source image.
// Throws FileError naming the first source image of a task that is not there, and how many
// are not. Writes nothing.
std::vector<ImageTask> dataset_image_tasks(const DatasetOptions& options, const DatasetStaging& staging,
                                           const std::vector<ColmapImage>& images,
                                           const std::vector<std::string>& source_names,
                                           const std::vector<std::size_t>& camera_of, DatasetSummary& summary);

// The model written into the staging folder (NeRF's files then listed in staging.model_files).
void write_staged_model(const DatasetOptions& options, DatasetStaging& staging,
                        const std::vector<ColmapCameraRecord>& cameras, const std::vector<ColmapImage>& images,
                        const ColmapPoints3D& points, const NerfWorld& world);

}  // namespace libcam
