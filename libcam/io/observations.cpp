#include "libcam/io/observations.hpp"

#include <charconv>
#include <cmath>
#include <string>

#include "libcam/error.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/io/detail/observation_table.hpp"

namespace libcam {

std::string_view to_string(ObservationTool tool) {
    switch (tool) {
        case ObservationTool::OpenCvCalibration: return "OpenCV's calibration sample";
        case ObservationTool::Mrcal: return "mrcal";
        case ObservationTool::Colmap: return "COLMAP";
        case ObservationTool::OpenSfm: return "OpenSfM";
        case ObservationTool::OpenMvg: return "OpenMVG";
        case ObservationTool::AliceVision: return "AliceVision";
        case ObservationTool::VisualSfm: return "VisualSfM";
        case ObservationTool::Bundler: return "Bundler";
        case ObservationTool::Table: return "a table of observations";
    }
    return "?";
}

std::string_view definition_of(ReportedMeasure measure) {
    switch (measure) {
        case ReportedMeasure::RmsOverObservations:
            return "the root of the mean over every observation of its squared residual length";
        case ReportedMeasure::MeanOfPointMeans:
            return "the mean over 3D points of each point's mean residual length over the observations of its track";
    }
    return "?";
}

int observed_camera_index(const ObservationSet& set, std::string_view selector) {
    for (std::size_t i = 0; i < set.cameras.size(); ++i) {
        if (set.cameras[i].name == selector) return static_cast<int>(i);
    }
    std::size_t position = 0;
    const auto [end, error] = std::from_chars(selector.data(), selector.data() + selector.size(), position);
    if (error == std::errc() && end == selector.data() + selector.size() && position < set.cameras.size()) {
        return static_cast<int>(position);
    }
    std::string names;
    for (const ObservedCamera& camera : set.cameras) names += (names.empty() ? "" : ", ") + camera.name;
    throw InvalidArgument("no camera '" + std::string(selector) + "' in " + set.source + " (its cameras: " + names +
                          "; or a position from 0 to " + std::to_string(set.cameras.size() - 1) + ")");
}

namespace {

void require(bool holds, const ObservationSet& set, const std::string& what) {
    if (!holds) throw FileError(set.source + ": " + what);
}

bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }
bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

}  // namespace

void check_observations(const ObservationSet& set) {
    require(set.point_ids.size() == set.points.size(), set,
            "point_ids: " + std::to_string(set.point_ids.size()) + " ids for " + std::to_string(set.points.size()) +
                " points");
    require(set.reported_per_view.empty() || set.reported_per_view.size() == set.views.size(), set,
            "reported per view: " + std::to_string(set.reported_per_view.size()) + " numbers for " +
                std::to_string(set.views.size()) + " views");
    require(set.reported_per_point.empty() || set.reported_per_point.size() == set.points.size(), set,
            "reported per point: " + std::to_string(set.reported_per_point.size()) + " numbers for " +
                std::to_string(set.points.size()) + " points");
    for (std::size_t i = 0; i < set.cameras.size(); ++i) {
        validated_camera(set.cameras[i].camera, set.source + ": camera " + set.cameras[i].name);
    }
    for (std::size_t i = 0; i < set.views.size(); ++i) {
        const ObservedView& view = set.views[i];
        require(view.camera >= 0 && static_cast<std::size_t>(view.camera) < set.cameras.size(), set,
                "view " + view.name + ": camera index " + std::to_string(view.camera) + " is not one of the " +
                    std::to_string(set.cameras.size()) + " cameras");
        try {
            view.pose.validate("pose");
        } catch (const Error& error) {
            throw FileError(set.source + ": view " + view.name + ": " + error.what());
        }
    }
    // Messages are made only for a failure: a reconstruction holds millions of observations.
    for (std::size_t i = 0; i < set.points.size(); ++i) {
        if (!finite(set.points[i])) require(false, set, "point " + std::to_string(set.point_ids[i]) + ": not finite");
    }
    for (std::size_t i = 0; i < set.observations.size(); ++i) {
        const Observation& o = set.observations[i];
        const auto where = [&] { return "observation " + std::to_string(i) + ": "; };
        if (o.view < 0 || static_cast<std::size_t>(o.view) >= set.views.size()) {
            require(false, set, where() + "view index " + std::to_string(o.view) + " out of range");
        }
        if (o.point < 0 || static_cast<std::size_t>(o.point) >= set.points.size()) {
            require(false, set, where() + "point index " + std::to_string(o.point) + " out of range");
        }
        if (!finite(o.pixel)) require(false, set, where() + "pixel not finite");
        if (!std::isfinite(o.weight)) require(false, set, where() + "weight not finite");
    }
}

namespace detail {

std::vector<NamedCamera> cameras_of_views(const ObservationSet& set, const std::string& source, std::string_view where,
                                          std::span<const ObservedView> unposed) {
    // The checks reading the file's observations makes, so that its cameras and its
    // observations are refused alike (`libcam info` and `libcam reproject` agree).
    check_observations(set);
    std::vector<NamedCamera> cameras;
    for (const ObservedView& view : set.views) {
        const ObservedCamera& intrinsics = set.cameras[static_cast<std::size_t>(view.camera)];
        Camera camera = intrinsics.camera;
        camera.pose = view.pose;
        cameras.push_back({view.name, {camera, std::nullopt}, intrinsics.name});
    }
    for (const ObservedView& view : unposed) {
        const ObservedCamera& intrinsics = set.cameras.at(static_cast<std::size_t>(view.camera));
        cameras.push_back({view.name, {intrinsics.camera, std::nullopt}, intrinsics.name, true});
    }
    if (cameras.empty()) {
        for (const ObservedCamera& camera : set.cameras) cameras.push_back({camera.name, {camera.camera, std::nullopt}});
    }
    if (cameras.empty()) throw FileError(source + ": " + std::string(where) + "no camera");
    return cameras;
}

}  // namespace detail

ObservationSet read_observations(const std::filesystem::path& path, const ObservationReadOptions& options) {
    // A table names no format of its own: the camera file says it is one.
    if (!options.camera_file.empty()) {
        ObservationSet set = read_observation_table(path, options.camera_file);
        check_observations(set);
        return set;
    }
    const detail::LocatedFile located = detail::locate_camera_file(path, std::nullopt);
    const detail::FormatRow& row = detail::format_rows()[static_cast<std::size_t>(located.format)];
    return detail::reading_as(located, [&] {
        if (row.read_observations == nullptr) {
            throw FileError(located.file.string() + ": " + std::string(row.title) +
                            " holds no observations (files that do: OpenCV's calibration output, a .cameramodel with "
                            "optimization_inputs, a COLMAP model, OpenSfM's reconstruction.json, OpenMVG's "
                            "sfm_data.json, AliceVision's cameras.sfm with its structure, VisualSfM's .nvm, Bundler's "
                            "bundle.out, or a table with a camera file)");
        }
        ObservationSet set = row.read_observations(located.file, located.text, options);
        if (set.source.empty()) set.source = path.string();
        check_observations(set);
        return set;
    });
}

}  // namespace libcam
