#include "libcam/dataset/detail/dataset_output.hpp"

#include <algorithm>
#include <set>

#include "libcam/error.hpp"
#include "libcam/dataset/detail/dataset_paths.hpp"
#include "libcam/dataset/detail/dataset_sources.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

namespace fs = std::filesystem;

const fs::path kColmapFolder = fs::path("sparse") / "0";
constexpr const char* kModelNames[] = {"cameras", "points3D", "images"};  // the images file, naming them, last

std::string stamp_of(const std::vector<ColmapCameraRecord>& cameras, const std::vector<DatasetCamera>& chosen,
                     Interpolation interpolation, int jpeg_quality) {
    std::string stamp = std::string("libcam dataset: the images here were made with these cameras\ninterpolation ") +
                        std::string(to_string(interpolation)) + "\njpeg quality " + std::to_string(jpeg_quality) + "\n" +
                        write_colmap_files(cameras, {}, {}, false).cameras;
    for (const DatasetCamera& camera : chosen) {
        if (camera.turn == Mat3::Identity()) continue;  // a run without views writes no turns
        stamp += "turn of camera " + std::to_string(camera.id);
        for (const double entry : camera.turn.reshaped<Eigen::RowMajor>()) stamp += " " + format_number(entry);
        stamp += "\n";
    }
    return stamp;
}

// Refused when the output's `replaced` (which a run replaces) is the source `source` itself.
void refuse_same(const fs::path& replaced, const fs::path& source, const std::string& what) {
    std::error_code error;
    if (fs::exists(replaced, error) && fs::exists(source, error) && fs::equivalent(replaced, source, error)) {
        throw FileError(replaced.string() + ": is the source " + what + " itself: give another output folder");
    }
}

}  // namespace

DatasetStaging dataset_staging(const DatasetOptions& options, const std::vector<ColmapImage>& images,
                               const std::vector<ColmapCameraRecord>& cameras, const std::vector<DatasetCamera>& chosen) {
    DatasetStaging staging;
    staging.output = options.output;
    staging.folder = staging_folder(options.output);
    if (options.to == DatasetFormat::Colmap) {
        const std::string extension = options.text ? ".txt" : ".bin";
        for (const char* name : kModelNames) staging.model_files.push_back(kColmapFolder / (name + extension));
        // An earlier model of either kind (COLMAP reads .bin first), its images file first.
        for (const char* name : {"images", "cameras", "points3D"}) {
            for (const char* kind : {".bin", ".txt"}) staging.replaced.push_back(kColmapFolder / (std::string(name) + kind));
        }
    } else {
        for (const char* name : {"transforms.json", kDataparserTransformsName, kNerfPointsName}) staging.replaced.push_back(name);
    }
    if (!options.images.empty()) {
        for (const ColmapImage& image : images) staging.images.push_back(image.name);
        staging.masks = options.masks;
        staging.stamp = stamp_of(cameras, chosen, options.interpolation, options.jpeg_quality);
    }
    return staging;
}

void check_output_folders(const DatasetOptions& options, const DatasetStaging& staging) {
    check_staging_folder(staging.folder);
    std::set<fs::path> folders = {kColmapFolder};
    for (const std::string& name : staging.images) {
        folders.insert((fs::path("images") / name).parent_path());
        if (staging.masks) folders.insert(mask_name(name).parent_path());
    }
    for (const fs::path& folder : folders) {
        check_folder_inside(staging.output, folder, staging.folder);
        check_folder_inside(staging.folder, folder);
    }
    if (!options.images.empty()) refuse_same(staging.output / "images", options.images, "images folder");
    refuse_same(options.to == DatasetFormat::Colmap ? staging.output / kColmapFolder : staging.output / "transforms.json",
                options.model, "model");
}

std::vector<ImageTask> dataset_image_tasks(const DatasetOptions& options, const DatasetStaging& staging,
                                           const std::vector<ColmapImage>& images,
                                           const std::vector<std::string>& source_names,
                                           const std::vector<std::size_t>& camera_of, DatasetSummary& summary) {
    const EarlierWork earlier(staging);
    // In camera order, so that a worker given a run of tasks builds each camera's map once.
    std::vector<std::size_t> order(images.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return camera_of[a] < camera_of[b]; });
    std::vector<ImageTask> tasks;
    std::set<std::string> missing;
    std::size_t first_missing = 0;  // the image of the first task whose source is missing
    for (const std::size_t i : order) {
        const std::string& name = images[i].name;
        const fs::path image_file = fs::path("images") / name;
        if (earlier.has(image_file, name) && (!options.masks || earlier.has(mask_name(name), name))) {
            ++summary.images_kept;
            continue;
        }
        const DatasetCamera& camera = summary.cameras[camera_of[i]];
        ImageTask task;
        task.source_path = options.images / source_names[i];
        task.target_path = staging.folder / image_file;
        if (options.masks) task.mask_path = staging.folder / mask_name(name);
        std::error_code error;
        if (!fs::is_regular_file(task.source_path, error) && missing.insert(source_names[i]).second && missing.size() == 1) {
            first_missing = i;
        }
        task.source = camera.source;
        task.source.pose = Pose{};
        task.camera = camera.camera;
        task.camera.pose = Pose{};
        task.turn = camera.turn;
        task.copy = camera.kept;
        task.interpolation = options.interpolation;
        task.jpeg_quality = options.jpeg_quality;
        tasks.push_back(std::move(task));
    }
    if (!missing.empty()) {
        throw FileError(images[first_missing].where + ": " + (options.images / source_names[first_missing]).string() +
                        ": no such image file (missing: " +
                        std::to_string(missing.size()) + " of the model's images): nothing was written");
    }
    return tasks;
}

void write_staged_model(const DatasetOptions& options, DatasetStaging& staging,
                        const std::vector<ColmapCameraRecord>& cameras, const std::vector<ColmapImage>& images,
                        const ColmapPoints3D& points, const NerfWorld& world) {
    if (options.to == DatasetFormat::Nerf) {
        staging.model_files =
            write_nerf_dataset(staging.folder, cameras, images, points, world, options.masks && !options.images.empty());
        return;
    }
    const ColmapModelBytes bytes = write_colmap_files(cameras, images, points, !options.text);
    const std::string* contents[] = {&bytes.cameras, &bytes.points3d, &bytes.images};  // kModelNames' order
    std::error_code error;
    fs::create_directories(staging.folder / kColmapFolder, error);
    if (error) throw FileError((staging.folder / kColmapFolder).string() + ": cannot make the folder: " + error.message());
    for (std::size_t k = 0; k < staging.model_files.size(); ++k) {
        write_file_atomically(staging.folder / staging.model_files[k], *contents[k]);
    }
}

}  // namespace libcam
