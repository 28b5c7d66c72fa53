#include "libcam/io/detail/colmap_observations.hpp"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "libcam/convert/colmap_models.hpp"
#include "libcam/io/detail/colmap_format.hpp"
#include "libcam/io/detail/colmap_model.hpp"

namespace libcam {

namespace {

void add_cameras(ObservationSet& set, const std::vector<ColmapCameraRecord>& cameras) {
    set.cameras.reserve(cameras.size());
    for (const ColmapCameraRecord& record : cameras) set.cameras.push_back({std::to_string(record.id), record.camera});
}

// Every image as a view (its camera is in the model: colmap_model.hpp).
void add_views(ObservationSet& set, const ColmapModelRecords& model) {
    set.views.reserve(model.images.size());
    for (const ColmapImage& image : model.images) {
        set.views.push_back({image.name, model.camera_index.find(image.camera_id), image.pose});
    }
}

// Every point, its id, and its ERROR (NaN where it is -1: COLMAP's Point3D::HasError).
void add_points(ObservationSet& set, ColmapPoints3D& points) {
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

// Every 2-D point with a 3-D point (which the model has: colmap_model.hpp), in OpenCV's pixels.
void add_observations(ObservationSet& set, ColmapModelRecords& model) {
    std::size_t count = 0;
    for (const ColmapImage& image : model.images) {
        for (const ColmapPoint2D& point : image.points) count += point.point3d_id != kColmapNoPoint3D ? 1 : 0;
    }
    set.observations.reserve(count);
    for (std::size_t v = 0; v < model.images.size(); ++v) {
        ColmapImage& image = model.images[v];
        for (const ColmapPoint2D& point : image.points) {
            if (point.point3d_id == kColmapNoPoint3D) continue;
            const Vec2 pixel(point.x - kColmapPixelShift, point.y - kColmapPixelShift);
            set.observations.push_back({static_cast<int>(v), model.point_index.find(point.point3d_id), pixel});
        }
        image.points = {};  // the model's largest part, no longer needed
    }
}

}  // namespace

ObservationSet read_colmap_observations(const std::filesystem::path& file, std::string_view text,
                                        const ObservationReadOptions&) {
    ColmapModelRecords model = read_whole_colmap_model(file, text);
    ObservationSet set;
    set.tool = ObservationTool::Colmap;
    set.source = file.parent_path().empty() ? std::string(".") : file.parent_path().string();
    set.pixel_offset = Vec2(kColmapPixelShift, kColmapPixelShift);
    add_cameras(set, model.cameras);
    add_views(set, model);
    add_points(set, model.points);
    add_observations(set, model);
    return set;
}

}  // namespace libcam
