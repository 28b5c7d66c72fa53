#include "libcam/io/detail/colmap_observations.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "libcam/convert/colmap_models.hpp"
#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/detail/colmap_format.hpp"

namespace libcam {

namespace {

struct ModelFiles {
    std::filesystem::path cameras;
    std::filesystem::path images;
    std::filesystem::path points3d;
    bool binary;
};

ModelFiles model_files(const std::filesystem::path& file) {
    const std::filesystem::path folder = file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path();
    const bool binary = file.extension() == ".bin";
    const std::string extension = binary ? ".bin" : ".txt";
    ModelFiles files{folder / ("cameras" + extension), folder / ("images" + extension),
                     folder / ("points3D" + extension), binary};
    for (const std::filesystem::path* path : {&files.cameras, &files.images, &files.points3d}) {
        if (!regular_file_exists(*path)) {
            throw FileError(folder.string() + ": a COLMAP model's observations are in cameras" + extension + ", images" +
                            extension + " and points3D" + extension + "; " + path->filename().string() +
                            " is missing");
        }
    }
    return files;
}

// A file's ids to their positions: a table where the ids are compact (COLMAP numbers
// them from 1), else a sorted list searched by halving.
class IdIndex {
public:
    template <class Ids>
    explicit IdIndex(const Ids& ids) {
        std::uint64_t largest = 0;
        for (const auto id : ids) largest = std::max<std::uint64_t>(largest, id);
        if (largest < 4 * static_cast<std::uint64_t>(ids.size()) + 1024) {
            table_.assign(static_cast<std::size_t>(largest) + 1, -1);
            for (std::size_t i = 0; i < ids.size(); ++i) {
                int& slot = table_[static_cast<std::size_t>(ids[i])];
                if (slot != -1 && !duplicate_) duplicate_ = ids[i];
                slot = static_cast<int>(i);
            }
            return;
        }
        sorted_.reserve(ids.size());
        for (std::size_t i = 0; i < ids.size(); ++i) sorted_.emplace_back(ids[i], static_cast<int>(i));
        std::sort(sorted_.begin(), sorted_.end());
        for (std::size_t i = 1; i < sorted_.size(); ++i) {
            if (sorted_[i].first == sorted_[i - 1].first && !duplicate_) duplicate_ = sorted_[i].first;
        }
    }

    // The position of `id`, or -1.
    int find(std::uint64_t id) const {
        if (sorted_.empty()) return id < table_.size() ? table_[static_cast<std::size_t>(id)] : -1;
        const auto at = std::lower_bound(sorted_.begin(), sorted_.end(), std::pair<std::uint64_t, int>(id, -1));
        return at != sorted_.end() && at->first == id ? at->second : -1;
    }

    // An id that appears more than once, if any.
    std::optional<std::uint64_t> duplicate() const { return duplicate_; }

private:
    std::vector<int> table_;
    std::vector<std::pair<std::uint64_t, int>> sorted_;
    std::optional<std::uint64_t> duplicate_;
};

template <class Ids>
IdIndex unique_ids(const Ids& ids, const std::filesystem::path& file, const char* field) {
    IdIndex index(ids);
    if (const auto id = index.duplicate()) {
        throw FileError(file.string() + ": " + field + " " + std::to_string(*id) + " appears more than once");
    }
    return index;
}

// COLMAP counts a 32-bit int of positions at most; a model past it is not one COLMAP wrote.
void check_count(std::size_t count, const std::filesystem::path& file, const char* what) {
    if (count > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
        throw FileError(file.string() + ": " + std::to_string(count) + " " + what + ", more than libcam indexes");
    }
}

void add_cameras(ObservationSet& set, const std::vector<ColmapCameraRecord>& cameras) {
    set.cameras.reserve(cameras.size());
    for (const ColmapCameraRecord& record : cameras) set.cameras.push_back({std::to_string(record.id), record.camera});
}

// Every image as a view. COLMAP refuses an image whose camera is not in the cameras file
// (Reconstruction::AddImage), and so does this.
void add_views(ObservationSet& set, const std::vector<ColmapImage>& images, const IdIndex& camera_index,
               const ModelFiles& files) {
    set.views.reserve(images.size());
    for (const ColmapImage& image : images) {
        const int camera = camera_index.find(image.camera_id);
        if (camera < 0) {
            throw FileError(image.where + " (" + image.name + "): CAMERA_ID " + std::to_string(image.camera_id) +
                            " is not in " + files.cameras.filename().string());
        }
        set.views.push_back({image.name, camera, image.pose});
    }
}

// Every point, its id, and its ERROR (NaN where it is -1: COLMAP's Point3D::HasError).
// A track naming an image the model lacks is refused: COLMAP loads such a file but fails
// on it at the first use of the track (Reconstruction::Image throws), and its writer,
// which deletes a deregistered image's observations, never leaves one.
void add_points(ObservationSet& set, ColmapPoints3D& points, const IdIndex& image_index, const ModelFiles& files) {
    for (std::size_t i = 0; i < points.ids.size(); ++i) {
        for (std::size_t k = points.track_begin[i]; k < points.track_begin[i + 1]; ++k) {
            const std::uint32_t image_id = points.track[k].image_id;
            if (image_index.find(image_id) < 0) {
                throw FileError(files.points3d.string() + ": POINT3D_ID " + std::to_string(points.ids[i]) + ": TRACK[" +
                                std::to_string(k - points.track_begin[i]) + "]: IMAGE_ID " + std::to_string(image_id) +
                                " is not in " + files.images.filename().string());
            }
        }
    }
    set.points = std::move(points.xyz);
    set.point_ids.assign(points.ids.begin(), points.ids.end());
    set.reported_per_point.reserve(points.errors.size());
    double sum = 0.0;
    std::size_t with_error = 0;
    for (const double error : points.errors) {
        const bool has_error = error != -1.0;
        set.reported_per_point.push_back(has_error ? error : std::numeric_limits<double>::quiet_NaN());
        if (has_error) {
            sum += error;
            ++with_error;
        }
    }
    // model_analyzer's "Mean reprojection error" (Reconstruction::ComputeMeanReprojectionError).
    if (with_error > 0) {
        set.reported.push_back({"mean_point_error_px", sum / static_cast<double>(with_error),
                                ReportedMeasure::MeanOfPointMeans});
    }
}

// Every 2-D point with a 3-D point, in OpenCV's pixels. COLMAP loads a POINT3D_ID that
// points3D lacks without a word, but then has no point to project; it is refused here.
void add_observations(ObservationSet& set, std::vector<ColmapImage>& images, const IdIndex& point_index,
                      const ModelFiles& files) {
    std::size_t count = 0;
    for (const ColmapImage& image : images) {
        for (const ColmapPoint2D& point : image.points) count += point.point3d_id != kColmapNoPoint3D ? 1 : 0;
    }
    check_count(count, files.images, "observations");
    set.observations.reserve(count);
    for (std::size_t v = 0; v < images.size(); ++v) {
        ColmapImage& image = images[v];
        for (std::size_t k = 0; k < image.points.size(); ++k) {
            const ColmapPoint2D& point = image.points[k];
            if (point.point3d_id == kColmapNoPoint3D) continue;
            const int index = point_index.find(point.point3d_id);
            if (index < 0) {
                throw FileError(image.where + " (" + image.name + "): POINTS2D[" + std::to_string(k) + "]: POINT3D_ID " +
                                std::to_string(point.point3d_id) + " is not in " + files.points3d.filename().string());
            }
            const Vec2 pixel(point.x - kColmapPixelShift, point.y - kColmapPixelShift);
            set.observations.push_back({static_cast<int>(v), index, pixel});
        }
        image.points = {};  // the model's largest part, no longer needed
    }
}

}  // namespace

ObservationSet read_colmap_observations(const std::filesystem::path& file, std::string_view text,
                                        const ObservationReadOptions&) {
    const ModelFiles files = model_files(file);
    // The model's files, the one detection read (`file`) not read again.
    const auto text_of = [&](const std::filesystem::path& path) {
        return path == file ? std::string(text) : read_text_file(path, kColmapModelPartLimit);
    };
    const std::vector<ColmapCameraRecord> cameras =
        read_colmap_cameras(text_of(files.cameras), files.cameras.string(), files.binary);
    std::vector<ColmapImage> images = read_colmap_images(text_of(files.images), files.images.string(), files.binary, true);
    ColmapPoints3D points = read_colmap_points3d(text_of(files.points3d), files.points3d.string(), files.binary);
    check_count(images.size(), files.images, "images");
    check_count(points.ids.size(), files.points3d, "points");

    ObservationSet set;
    set.tool = ObservationTool::Colmap;
    set.source = files.cameras.parent_path().string();
    set.pixel_offset = Vec2(kColmapPixelShift, kColmapPixelShift);
    std::vector<std::uint64_t> camera_ids;
    for (const ColmapCameraRecord& camera : cameras) camera_ids.push_back(camera.id);
    std::vector<std::uint64_t> image_ids;
    for (const ColmapImage& image : images) image_ids.push_back(image.id);
    const IdIndex camera_index = unique_ids(camera_ids, files.cameras, "CAMERA_ID");
    const IdIndex image_index = unique_ids(image_ids, files.images, "IMAGE_ID");
    const IdIndex point_index = unique_ids(points.ids, files.points3d, "POINT3D_ID");

    add_cameras(set, cameras);
    add_views(set, images, camera_index, files);
    add_points(set, points, image_index, files);
    add_observations(set, images, point_index, files);
    return set;
}

}  // namespace libcam
