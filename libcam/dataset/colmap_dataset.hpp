#pragma once
// A whole COLMAP reconstruction turned into pinhole cameras, for the tools that take
// nothing else (3D Gaussian Splatting, most MVS): every camera replaced by a pinhole
// chosen for its lens (remap/new_camera.hpp), every image undistorted into it, every 2-D
// observation moved to the pixel of the same ray in the new camera.
//
//   DatasetOptions options;
//   options.model = "scene/sparse/0";  options.images = "scene/images";  options.output = "out";
//   const DatasetSummary summary = make_pinhole_dataset(options);
//   // out/sparse/0/{cameras,images,points3D}.bin, out/images/<each image's name>
//
// What it keeps: the new camera looks along the source's axes (no rotation), so each image
// keeps its pose; each 3-D point keeps its position, colour and track. An observation is
// unprojected through its source camera and projected through the new one (the exact
// ray, not the image map's interpolation); one whose ray has no pixel on the new image is
// dropped, from its image's POINTS2D and from its point's track (the remaining POINT2D_IDX
// renumbered), and a point left with no observation is dropped. Each point's ERROR is
// recomputed in the new pixels (the mean over its track, as COLMAP defines it).
//
// With `views` (detail/dataset_views.hpp) a wide lens becomes several pinholes turned away from
// its axis: each source image becomes one image per view (its pose turned), each
// observation is written in every view it lands on and its point's track names each.
//
// Images: read whole (any depth, channels and format OpenCV reads), remapped with one map
// per camera shared by its images, written in the same format under the same name, each
// to a temporary file renamed into place; N workers, one image each in memory at a time.
// A source camera that is already a pinhole, given no --size or field of view, is kept as
// it is and its images copied.
//
// Paths (detail/dataset_paths.hpp): each image's name is a plain relative path inside the images
// folder, and the output's folders stay inside the output folder, or the run is refused
// before it writes anything, as it is for a model it cannot read, a camera it cannot
// choose or a source image that is not there.
//
// Nothing half made (dataset_staging.hpp): the run writes its model, images, masks and
// stamp into OUT/.libcam-dataset-partial and moves them into OUT only when every image is
// there. A run with an image that cannot be read or written leaves OUT as it was; started
// again with the same cameras and interpolation (the stamp kStampName says) it keeps the
// images already made, in the staging folder or in a finished OUT, and makes the rest.
//
// The same in three steps, for images spread over several processes or machines
// (dataset_tasks.hpp): plan_dataset does everything but the images and returns one task
// per image still to write; each task runs anywhere the source and output folders are
// (run_image_task); finish_dataset moves the whole into place. make_pinhole_dataset is
// plan_dataset, every task here, and finish_dataset.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "libcam/dataset/dataset_staging.hpp"
#include "libcam/dataset/dataset_tasks.hpp"
#include "libcam/interop/image_remap.hpp"
#include "libcam/remap/new_camera.hpp"

namespace libcam {

// What the output's cameras and poses are written as.
enum class DatasetFormat {
    Colmap,  // OUT/sparse/0/{cameras,images,points3D}
    Nerf,    // OUT/transforms.json (and sparse_pc.ply): detail/dataset_sources.hpp
};

struct DatasetOptions {
    // A COLMAP model folder (cameras, images, points3D; .bin or .txt), or NeRF's
    // transforms.json (a .json file: its frames' cameras and poses, no points;
    // detail/dataset_sources.hpp).
    std::filesystem::path model;
    std::filesystem::path images;  // the source images; empty: write the model alone
    std::filesystem::path output;  // gets sparse/0/ (or transforms.json) and images/
    DatasetFormat to = DatasetFormat::Colmap;
    // The new camera of each source camera: `keep` or `fov_deg` on `fov_axis`, and `size`
    // (default each source's); model and rotation are not used (always a pinhole, no turn).
    NewCameraRequest camera;
    Interpolation interpolation = Interpolation::Cubic;
    int jpeg_quality = kDefaultJpegQuality;  // 1 to 100, for the images written as JPEG
    int threads = 1;
    bool text = false;  // write the model as text instead of binary
    // Split a lens wider than one pinhole holds well into several pinhole views, each with
    // its own camera, images and turned pose (detail/dataset_views.hpp); `camera` is then unused.
    bool views = false;
    // Also write masks/<image name>.png: 255 where the output pixel has a source pixel, 0
    // where it is black (COLMAP's mask convention, ImageReader.mask_path).
    bool masks = false;
    // Called, one call at a time, with one line for each image that could not be read or
    // written; the others go on.
    std::function<void(const std::string&)> on_image_error;
    // Called, one call at a time, after each image with how many of this run's are done.
    std::function<void(std::size_t done, std::size_t total)> on_progress;
};

struct DatasetCamera {
    std::uint64_t id = 0;        // COLMAP's CAMERA_ID, the same in the output
    std::string source_model;    // COLMAP's model name of the source camera
    Camera source;
    Camera camera;               // the new pinhole
    std::string why;             // how it was chosen
    std::size_t images = 0;      // images taking it
    bool kept = false;           // the source was already a pinhole, kept: its images copied
    // With views: `id` is new, one per source camera and view; this camera is view `view`
    // of the `views` of source camera `source_id`, turned by `turn` (its axes relative to
    // the source's: yaw_deg about y towards +x, then pitch_deg towards +y).
    std::uint64_t source_id = 0;
    std::size_t view = 0, views = 1;
    Mat3 turn = Mat3::Identity();
    double yaw_deg = 0, pitch_deg = 0;
    std::size_t observations = 0;  // observations (with a 3-D point) written in its images
};

struct DatasetSummary {
    std::vector<DatasetCamera> cameras;
    std::size_t observations_in = 0;    // POINTS2D with a 3-D point
    std::size_t observations_kept = 0;  // each source observation once, however many views hold it
    std::size_t points2d_in = 0;        // every POINTS2D entry
    std::size_t points2d_kept = 0;
    std::size_t points_in = 0;          // 3-D points
    std::size_t points_kept = 0;
    std::size_t images_in = 0;          // images of the model
    std::size_t model_images_out = 0;   // images of the output model (more than images_in with views)
    std::size_t images_written = 0;
    std::size_t images_kept = 0;        // already in the output from an earlier run
    std::size_t images_failed = 0;
    std::filesystem::path model_out;    // the model's folder (or the transforms.json) in the output
    // Whether the run's work is in place in the output; false: an image failed (or the plan
    // is not finished yet), the output is as it was and the work waits in staging_folder.
    bool finished = false;
};

// Throws FileError for a malformed model, a name or folder leading out of its folder, a
// missing source image or an output that cannot be written, InvalidArgument when no pinhole
// can be chosen for a camera (naming it), each before anything is written. An image that
// cannot be read or written is reported through on_image_error and counted instead, and
// the run is then left unfinished (summary.finished false, the output as it was).
DatasetSummary make_pinhole_dataset(const DatasetOptions& options);

// Everything but the images: every check above, the cameras chosen, the observations moved,
// the model and (with `images`) the stamp written to the staging folder, and one task per
// output image not already made by an earlier run with the same cameras (counted in
// images_kept), in camera order. images_written and images_failed are left 0 for the caller
// to count. Nothing is in place in the output until finish_dataset.
struct DatasetPlan {
    DatasetSummary summary;
    std::vector<ImageTask> tasks;
    DatasetStaging staging;  // what finish_dataset moves into place
    // The output folder locked against another process's run while any copy of the plan
    // lives (lock_output).
    std::shared_ptr<const OutputLock> lock;
};
DatasetPlan plan_dataset(const DatasetOptions& options);

// Once every task of the plan has written its image (wherever it ran): moves the staged
// images, masks, model and stamp into the output (dataset_staging.hpp) and returns the
// plan's summary, finished, images_written counting the images the tasks made. Throws
// FileError, moving nothing, when an image is not there yet (naming the first and how many).
DatasetSummary finish_dataset(const DatasetPlan& plan);

// The new cameras a --camera word asks for, set in `options`: "valid" (every pixel has a
// source), "all" (every source pixel kept), "fov:DEG" (this horizontal field of view) or
// "views" (a wide lens split into several pinholes, setting `views`); `size` (none: each
// source's) is refused with views. Throws InvalidArgument "camera: ..." or "size: ...".
void set_dataset_camera(DatasetOptions& options, const std::string& camera, std::optional<ImageSize> size);

// The source images beside a model: X/images for the COLMAP model X/sparse/0; for a
// transforms.json where its frames are (detail/dataset_sources.hpp).
std::filesystem::path default_dataset_images(const std::filesystem::path& model);

// The summary as `libcam dataset --json` prints it (with "time_s" when `seconds` is given).
std::string dataset_summary_json(const DatasetSummary& summary, std::optional<double> seconds = std::nullopt);

}  // namespace libcam
