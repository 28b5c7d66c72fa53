#include "libcam/dataset/colmap_dataset.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "libcam/camera/parallel.hpp"
#include "libcam/convert/colmap_models.hpp"
#include "libcam/error.hpp"
#include "libcam/dataset/detail/dataset_output.hpp"
#include "libcam/dataset/detail/dataset_paths.hpp"
#include "libcam/dataset/detail/dataset_views.hpp"
#include "libcam/dataset/detail/dataset_sources.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/detail/colmap_format.hpp"
#include "libcam/io/detail/colmap_model.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/remap/remap_map.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

namespace fs = std::filesystem;

// A COLMAP model, or another source taken in as one (detail/dataset_sources.hpp).
using ColmapModelRead = DatasetModel;

// The model a source names: a transforms.json itself; for a folder, the COLMAP model
// colmap_model_folder finds (a workspace's sparse/ holding 0/: sparse/0).
fs::path named_model(const fs::path& source) {
    if (is_nerf_dataset_source(source)) return source;
    const fs::path folder = colmap_model_folder(source);
    return folder.empty() ? source : folder;
}

// The model read and checked as every command reads it (io/detail/colmap_model.hpp).
ColmapModelRead read_model(const fs::path& folder) {
    ColmapModelRecords records = read_whole_colmap_model(folder);
    ColmapModelRead model;
    model.cameras = std::move(records.cameras);
    model.images = std::move(records.images);
    model.points = std::move(records.points);
    return model;
}

// Whether a source camera is kept as it is: already a pinhole, and nothing asks for another
// view or size.
bool kept_as_is(const ColmapCameraRecord& record, const NewCameraRequest& asked) {
    const bool pinhole = simplest_equal_lens(record.camera.lens).type == LensType::Pinhole;
    return pinhole && record.camera.intrinsics.skew == 0.0 && !asked.size && asked.keep;
}

// The new camera of one source camera: the source itself when kept_as_is, else
// new_camera's choice, which must be a pinhole.

DatasetCamera choose_camera(const ColmapCameraRecord& record, const NewCameraRequest& asked, int threads) {
    DatasetCamera chosen;
    chosen.id = record.id;
    chosen.source_id = record.id;
    chosen.source_model = std::string(record.model);
    chosen.source = record.camera;
    if (kept_as_is(record, asked)) {
        chosen.camera = record.camera;
        chosen.camera.lens = Lens{};
        chosen.kept = true;
        chosen.why = "already a pinhole: kept, its images copied";
        return chosen;
    }
    NewCameraRequest request = asked;
    request.model = LensType::Pinhole;
    request.rotation = Mat3::Identity();
    request.threads = threads;
    const std::string name = "camera " + std::to_string(record.id) + " (" + chosen.source_model + ")";
    NewCamera picked;
    try {
        picked = choose_new_camera(PreparedCamera(record.camera), request);
    } catch (const InvalidArgument& error) {
        throw InvalidArgument(name + ": " + error.what());
    }
    if (picked.camera.lens.type != LensType::Pinhole) {
        throw InvalidArgument(name + ": no pinhole keeps every pixel of this lens (" + picked.why +
                              "); ask for valid or a field of view");
    }
    chosen.camera = picked.camera;
    chosen.why = picked.why;
    return chosen;
}

// Positions of ids: COLMAP's ids are 32-bit, so a map is small enough and simple.
template <class Items, class IdOf>
std::map<std::uint64_t, std::size_t> index_by_id(const Items& items, IdOf&& id_of, const std::string& what) {
    std::map<std::uint64_t, std::size_t> index;
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (!index.emplace(id_of(items[i]), i).second) {
            throw FileError(what + " id " + std::to_string(id_of(items[i])) + " appears more than once");
        }
    }
    return index;
}

// Each image's POINTS2D moved into its new camera; `kept_index[image][k]` is the new
// position of POINTS2D k, or -1 where it was dropped.
std::vector<std::vector<int>> move_points2d(std::vector<ColmapImage>& images, const std::vector<std::size_t>& camera_of,
                                            const std::vector<PreparedCamera>& sources,
                                            const std::vector<PreparedCamera>& targets, const std::vector<Mat3>& turns,
                                            int threads) {
    std::vector<std::vector<int>> kept_index(images.size());
    parallel_chunks(images.size(), threads, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const PreparedCamera& source = sources[camera_of[i]];
            const PreparedCamera& target = targets[camera_of[i]];
            std::vector<ColmapPoint2D> moved;
            std::vector<int>& index = kept_index[i];
            index.assign(images[i].points.size(), -1);
            for (std::size_t k = 0; k < images[i].points.size(); ++k) {
                const ColmapPoint2D& point = images[i].points[k];
                const Unprojection ray =
                    source.unproject(Vec2(point.x - kColmapPixelShift, point.y - kColmapPixelShift));
                if (!ray.valid) continue;
                const Projection pixel = target.project_camera_point(turns[camera_of[i]] * ray.direction);
                if (!pixel.valid || !on_image(pixel.pixel.x(), pixel.pixel.y(), target.camera().size)) continue;
                index[k] = static_cast<int>(moved.size());
                moved.push_back({pixel.pixel.x() + kColmapPixelShift, pixel.pixel.y() + kColmapPixelShift, point.point3d_id});
            }
            images[i].points = std::move(moved);
        }
    });
    return kept_index;
}

// The points' tracks renumbered to the kept POINTS2D, points left with none dropped, each
// ERROR recomputed in the new cameras' pixels.
ColmapPoints3D carry_points(const ColmapPoints3D& points, const std::vector<ColmapImage>& images,
                            const std::map<std::uint64_t, std::size_t>& image_index,
                            const std::vector<std::vector<int>>& kept_index, const std::vector<std::size_t>& camera_of,
                            const std::vector<PreparedCamera>& targets, const std::string& source) {
    ColmapPoints3D out;
    for (std::size_t i = 0; i < points.ids.size(); ++i) {
        const std::size_t track_start = out.track.size();
        double error_sum = 0.0;
        std::size_t error_count = 0;
        for (std::size_t k = points.track_begin[i]; k < points.track_begin[i + 1]; ++k) {
            const auto [image_id, index] = points.track[k];
            const auto found = image_index.find(image_id);
            if (found == image_index.end() || index >= kept_index[found->second].size()) {
                throw FileError(source + ": point " + std::to_string(points.ids[i]) + ": track element (" +
                                std::to_string(image_id) + ", " + std::to_string(index) + ") names no image's POINTS2D");
            }
            const int kept = kept_index[found->second][index];
            if (kept < 0) continue;
            out.track.push_back({image_id, static_cast<std::uint32_t>(kept)});
            const ColmapImage& image = images[found->second];
            const Projection projected =
                targets[camera_of[found->second]].project_camera_point(image.pose.R * points.xyz[i] + image.pose.t);
            if (!projected.valid) continue;
            const ColmapPoint2D& seen = image.points[static_cast<std::size_t>(kept)];
            error_sum += (projected.pixel + Vec2(kColmapPixelShift, kColmapPixelShift) - Vec2(seen.x, seen.y)).norm();
            ++error_count;
        }
        if (out.track.size() == track_start) continue;
        out.ids.push_back(points.ids[i]);
        out.xyz.push_back(points.xyz[i]);
        out.colours.push_back(points.colours[i]);
        out.errors.push_back(error_count ? error_sum / static_cast<double>(error_count) : points.errors[i]);
        out.track_begin.push_back(out.track.size());
    }
    return out;
}

// POINTS2D naming a point the output does not have (dropped, or never in the file) made
// pointless, as COLMAP marks a 2-D point of no 3-D point.
void unlink_missing_points(std::vector<ColmapImage>& images, const ColmapPoints3D& points) {
    std::vector<std::uint64_t> ids = points.ids;
    std::sort(ids.begin(), ids.end());
    for (ColmapImage& image : images) {
        for (ColmapPoint2D& point : image.points) {
            if (point.point3d_id != kColmapNoPoint3D && !std::binary_search(ids.begin(), ids.end(), point.point3d_id)) {
                point.point3d_id = kColmapNoPoint3D;
            }
        }
    }
}

std::size_t count_with_point(const std::vector<ColmapImage>& images) {
    std::size_t count = 0;
    for (const ColmapImage& image : images) {
        for (const ColmapPoint2D& point : image.points) count += point.point3d_id != kColmapNoPoint3D;
    }
    return count;
}

// Each source POINTS2D counted once however many views hold it (kept_index of output
// image e are the places of its source's POINTS2D), and each camera's observations.
void count_kept(const std::vector<ColmapImage>& images, const std::vector<std::vector<int>>& kept_index,
                const std::vector<std::size_t>& source_of, const std::vector<std::size_t>& camera_of,
                DatasetSummary& summary) {
    std::map<std::size_t, std::vector<std::uint8_t>> kept;  // by source image: 1 kept, 2 kept with its 3-D point
    for (std::size_t e = 0; e < images.size(); ++e) {
        std::vector<std::uint8_t>& of_source = kept[source_of[e]];
        of_source.resize(kept_index[e].size(), 0);
        for (std::size_t k = 0; k < kept_index[e].size(); ++k) {
            const int at = kept_index[e][k];
            if (at < 0) continue;
            const bool with_point = images[e].points[static_cast<std::size_t>(at)].point3d_id != kColmapNoPoint3D;
            of_source[k] = std::max<std::uint8_t>(of_source[k], with_point ? 2 : 1);
        }
        for (const ColmapPoint2D& point : images[e].points) {
            summary.cameras[camera_of[e]].observations += point.point3d_id != kColmapNoPoint3D;
        }
    }
    for (const auto& [image, flags] : kept) {
        for (const std::uint8_t flag : flags) {
            summary.points2d_kept += flag > 0;
            summary.observations_kept += flag == 2;
        }
    }
}

// --camera views: the model's cameras, images and tracks replaced by the views'
// (detail/dataset_views.hpp), `source_of` and `source_names` saying where each image comes from.
void split_model_into_views(ColmapModelRead& model, std::vector<std::size_t>& camera_of,
                            std::vector<std::size_t>& source_of, std::vector<std::string>& source_names,
                            std::vector<ColmapCameraRecord>& new_records, DatasetSummary& summary,
                            const std::string& source, int threads) {
    NewCameraRequest keep_all;
    keep_all.keep = Keep::All;
    std::vector<std::optional<DatasetCamera>> as_is(model.cameras.size());
    for (std::size_t c = 0; c < model.cameras.size(); ++c) {
        if (kept_as_is(model.cameras[c], keep_all)) as_is[c] = choose_camera(model.cameras[c], keep_all, threads);
    }
    ViewSplit split = split_into_views(model.cameras, model.images, model.points, camera_of, as_is, source, threads);
    std::vector<std::string> names;
    for (const std::size_t i : split.source_of) names.push_back(model.images[i].name);
    source_names = std::move(names);
    summary.cameras = std::move(split.cameras);
    new_records = std::move(split.records);
    model.images = std::move(split.images);
    model.points = std::move(split.points);
    camera_of = std::move(split.camera_of);
    source_of = std::move(split.source_of);
}

// Every image's name made plain, or the run refused (detail/dataset_paths.hpp).
void plain_names(std::vector<ColmapImage>& images, const std::string& field) {
    for (ColmapImage& image : images) image.name = plain_image_name(image.name, image.where, field, "the images folder");
}

}  // namespace

DatasetPlan plan_dataset(const DatasetOptions& given) {
    DatasetOptions options = given;
    options.model = named_model(given.model);
    const int threads = worker_count(options.threads);
    const bool nerf_source = is_nerf_dataset_source(options.model);
    ColmapModelRead model = nerf_source ? read_nerf_dataset(options.model) : read_model(options.model);
    const std::string field = nerf_source ? "\"file_path\"" : "NAME";
    plain_names(model.images, field);
    const std::string source = options.model.string();
    const auto camera_index = index_by_id(model.cameras, [](const ColmapCameraRecord& c) { return c.id; }, source + ": camera");
    auto image_index = index_by_id(model.images, [](const ColmapImage& i) { return i.id; }, source + ": image");

    DatasetSummary summary;
    summary.images_in = model.images.size();
    summary.points_in = model.points.ids.size();
    summary.observations_in = count_with_point(model.images);
    std::vector<std::size_t> camera_of(model.images.size());
    for (std::size_t i = 0; i < model.images.size(); ++i) {
        const auto found = camera_index.find(model.images[i].camera_id);
        if (found == camera_index.end()) {
            throw FileError(model.images[i].where + ": CAMERA_ID " + std::to_string(model.images[i].camera_id) +
                            " is not in the cameras file");
        }
        camera_of[i] = found->second;
        summary.points2d_in += model.images[i].points.size();
    }

    std::vector<ColmapCameraRecord> new_records;
    std::vector<std::size_t> source_of(model.images.size());  // each output image's source image
    for (std::size_t i = 0; i < source_of.size(); ++i) source_of[i] = i;
    std::vector<std::string> source_names;
    for (const ColmapImage& image : model.images) source_names.push_back(image.name);
    if (options.views) {
        split_model_into_views(model, camera_of, source_of, source_names, new_records, summary, source, threads);
        image_index = index_by_id(model.images, [](const ColmapImage& i) { return i.id; }, source + ": image");
    } else {
        for (const ColmapCameraRecord& record : model.cameras) {
            summary.cameras.push_back(choose_camera(record, options.camera, threads));
            new_records.push_back({record.id, summary.cameras.back().camera, "PINHOLE"});
        }
    }
    check_distinct_names(model.images, field);
    std::vector<PreparedCamera> sources, targets;
    std::vector<Mat3> turns;
    for (const DatasetCamera& camera : summary.cameras) {
        sources.emplace_back(camera.source);
        targets.emplace_back(camera.camera);
        turns.push_back(camera.turn);
    }
    for (const std::size_t c : camera_of) ++summary.cameras[c].images;

    const std::vector<std::vector<int>> kept_index =
        move_points2d(model.images, camera_of, sources, targets, turns, threads);
    const ColmapPoints3D points =
        carry_points(model.points, model.images, image_index, kept_index, camera_of, targets, source);
    unlink_missing_points(model.images, points);
    summary.points_kept = points.ids.size();
    count_kept(model.images, kept_index, source_of, camera_of, summary);
    summary.model_images_out = model.images.size();
    summary.model_out = options.to == DatasetFormat::Nerf ? options.output / "transforms.json" : options.output / "sparse" / "0";

    // Everything checked before the first file is written.
    DatasetPlan plan;
    plan.staging = dataset_staging(options, model.images, new_records, summary.cameras);
    check_output_folders(options, plan.staging);
    if (!options.images.empty()) {
        plan.tasks = dataset_image_tasks(options, plan.staging, model.images, source_names, camera_of, summary);
    }
    plan.lock = lock_output(options.output);
    prepare_staging(plan.staging);
    write_staged_model(options, plan.staging, new_records, model.images, points, model.world);
    plan.summary = std::move(summary);
    return plan;
}

DatasetSummary finish_dataset(const DatasetPlan& plan) {
    finish_staging(plan.staging);
    DatasetSummary summary = plan.summary;
    // Every image not made by an earlier run was made by one of the plan's tasks.
    if (!plan.staging.images.empty()) summary.images_written = summary.model_images_out - summary.images_kept;
    summary.images_failed = 0;
    summary.finished = true;
    return summary;
}

DatasetSummary make_pinhole_dataset(const DatasetOptions& options) {
    const DatasetPlan plan = plan_dataset(options);
    const std::size_t failed =
        run_image_tasks(plan.tasks, worker_count(options.threads), options.on_image_error, options.on_progress);
    if (failed == 0) return finish_dataset(plan);
    DatasetSummary summary = plan.summary;
    summary.images_failed = failed;
    summary.images_written = plan.tasks.size() - failed;
    return summary;
}

void set_dataset_camera(DatasetOptions& options, const std::string& camera, std::optional<ImageSize> size) {
    NewCameraRequest request;
    request.size = size;
    options.views = camera == "views";
    if (camera == "valid") {
        request.keep = Keep::Valid;
    } else if (camera == "all") {
        request.keep = Keep::All;
    } else if (camera == "views") {
        if (size) throw InvalidArgument("size: not with camera views (each view's size is its own)");
    } else if (camera.starts_with("fov:")) {
        const std::string_view degrees = std::string_view(camera).substr(4);
        double fov_deg = 0.0;
        const auto [stop, error] = std::from_chars(degrees.data(), degrees.data() + degrees.size(), fov_deg);
        if (degrees.empty() || error != std::errc() || stop != degrees.data() + degrees.size() || !std::isfinite(fov_deg)) {
            throw InvalidArgument("camera: fov:DEG takes a number of degrees, got '" + camera + "'");
        }
        request.keep.reset();
        request.fov_deg = fov_deg;
        request.fov_axis = FovAxis::Horizontal;
    } else {
        throw InvalidArgument("camera: expected valid (no pixel without a source), all (every source pixel kept), "
                              "fov:DEG (the horizontal field of view) or views (a wide lens split into several pinholes), "
                              "got '" + camera + "'");
    }
    options.camera = request;
}

fs::path default_dataset_images(const fs::path& model) {
    if (is_nerf_dataset_source(model)) return nerf_dataset_images_folder(model);
    const fs::path folder = fs::absolute(named_model(model)).lexically_normal();
    const fs::path trimmed = folder.has_filename() ? folder : folder.parent_path();
    return trimmed.parent_path().parent_path() / "images";
}

namespace {

nlohmann::ordered_json camera_json(const DatasetCamera& camera) {
    const Intrinsics& k = camera.camera.intrinsics;
    return nlohmann::ordered_json{{"id", camera.id},
                                  {"source_model", camera.source_model},
                                  {"model", "PINHOLE"},
                                  {"fx", k.fx},
                                  {"fy", k.fy},
                                  {"cx", k.cx},
                                  {"cy", k.cy},
                                  {"width", camera.camera.size.width},
                                  {"height", camera.camera.size.height},
                                  {"images", camera.images},
                                  {"observations", camera.observations},
                                  {"source_id", camera.source_id},
                                  {"view", camera.view},
                                  {"views", camera.views},
                                  {"yaw_deg", camera.yaw_deg},
                                  {"pitch_deg", camera.pitch_deg},
                                  {"why", camera.why}};
}

}  // namespace

std::string dataset_summary_json(const DatasetSummary& s, std::optional<double> seconds) {
    nlohmann::ordered_json out;
    out["model"] = s.model_out.string();
    out["observations_in"] = s.observations_in;
    out["observations_kept"] = s.observations_kept;
    out["points2d_in"] = s.points2d_in;
    out["points2d_kept"] = s.points2d_kept;
    out["points_in"] = s.points_in;
    out["points_kept"] = s.points_kept;
    out["images_in"] = s.images_in;
    out["model_images_out"] = s.model_images_out;
    out["images_out"] = s.images_written + s.images_kept;
    out["images_written"] = s.images_written;
    out["images_kept"] = s.images_kept;
    out["images_failed"] = s.images_failed;
    out["finished"] = s.finished;
    out["cameras"] = nlohmann::ordered_json::array();
    for (const DatasetCamera& camera : s.cameras) out["cameras"].push_back(camera_json(camera));
    if (seconds) out["time_s"] = *seconds;
    return out.dump(2) + "\n";
}

}  // namespace libcam
