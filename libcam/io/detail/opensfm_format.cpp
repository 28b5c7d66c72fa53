#include "libcam/io/detail/opensfm_format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <unordered_map>

#include "libcam/error.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

// OpenSfM's pixel (0, 0) is the image's top-left corner: libcam's pixels are its minus 0.5.
constexpr double kPixelCentre = 0.5;

using Kind = DocumentNode::Kind;

// ---- cameras -------------------------------------------------------------------------

// Where normalized (0, 0) is in libcam's pixels, and what one normalized unit is.
struct Normalized {
    double scale = 1.0;  // max(width, height)
    Vec2 centre = Vec2::Zero();
    Vec2 pixel(double x, double y) const { return centre + scale * Vec2(x, y); }
};

Normalized normalized_frame(const ImageSize& size) {
    const auto width = static_cast<double>(size.width);
    const auto height = static_cast<double>(size.height);
    return {std::max(width, height), {0.5 * width - kPixelCentre, 0.5 * height - kPixelCentre}};
}

std::string projection_type(const Field& camera) {
    // OpenSfM's own reader takes a camera without a projection_type as perspective.
    const std::optional<Field> type = camera.find({"projection_type"});
    return type ? type->text() : "perspective";
}

// The lens of an OpenSfM camera and whether the model has focal_x, focal_y, c_x, c_y
// (else one focal and the principal point at the centre).
struct OpenSfmLens {
    Lens lens;
    bool affine = false;
};

OpenSfmLens opensfm_lens(const Field& camera, const std::string& type) {
    const auto k = [&](std::string_view key) { return camera.at({key}).number(); };
    if (type == "perspective") return {{LensType::OpenCv4, {k("k1"), k("k2"), 0.0, 0.0}}, false};
    if (type == "fisheye") return {{LensType::Fisheye, {k("k1"), k("k2"), 0.0, 0.0}}, false};
    if (type == "brown") return {{LensType::OpenCv5, {k("k1"), k("k2"), k("p1"), k("p2"), k("k3")}}, true};
    if (type == "radial") return {{LensType::OpenCv4, {k("k1"), k("k2"), 0.0, 0.0}}, true};
    if (type == "simple_radial") return {{LensType::OpenCv4, {k("k1"), 0.0, 0.0, 0.0}}, true};
    if (type == "fisheye_opencv") return {{LensType::Fisheye, {k("k1"), k("k2"), k("k3"), k("k4")}}, true};
    if (type == "spherical" || type == "equirectangular") return {{LensType::Lonlat, {}}, false};
    if (type == "fisheye62" || type == "fisheye624" || type == "dual") {
        camera.fail_at("projection_type", shown_value(type) +
                                              " is refused: libcam has no lens model that holds OpenSfM's " + type +
                                              " exactly");
    }
    camera.fail_at("projection_type", "unknown projection type " + shown_value(type) +
                                          " (OpenSfM's: perspective, brown, radial, simple_radial, fisheye, "
                                          "fisheye_opencv, spherical)");
}

Camera opensfm_camera(const Field& camera) {
    Camera out;
    out.size = {static_cast<long>(camera.at({"width"}).whole_number(1, kMaxImageSide)),
                static_cast<long>(camera.at({"height"}).whole_number(1, kMaxImageSide))};
    const Normalized frame = normalized_frame(out.size);
    const std::string type = projection_type(camera);
    const OpenSfmLens lens = opensfm_lens(camera, type);
    if (lens.lens.type == LensType::Lonlat) {
        // Spherical: normalized (lon, lat) / (2 pi), the same lon and lat as LONLAT's.
        const double focal = frame.scale / (2.0 * std::numbers::pi);
        out.intrinsics = {focal, focal, frame.centre.x(), frame.centre.y(), 0.0};
    } else if (lens.affine) {
        const Vec2 centre = frame.pixel(camera.at({"c_x"}).number(), camera.at({"c_y"}).number());
        out.intrinsics = {camera.at({"focal_x"}).number() * frame.scale, camera.at({"focal_y"}).number() * frame.scale,
                          centre.x(), centre.y(), 0.0};
    } else {
        const double focal = camera.at({"focal"}).number() * frame.scale;
        out.intrinsics = {focal, focal, frame.centre.x(), frame.centre.y(), 0.0};
    }
    out.lens = simplest_equal_lens(lens.lens);
    return validated_camera(out, camera.source() + ": \"" + camera.name() + "\"");
}

// ---- reconstructions -------------------------------------------------------------------

Vec3 three_numbers(const Field& field) {
    const std::vector<double> values = field.numbers(3);
    if (values.size() != 3) field.fail("expected 3 numbers, got " + field.shown());
    return {values[0], values[1], values[2]};
}

// The reconstructions read into one set, with what tracks.csv's rows are looked up by.
struct Reconstructions {
    ObservationSet set;
    // shot name -> (its view, the points of its reconstruction: track id -> point index)
    std::unordered_map<std::string, int> view_of_shot;
    std::vector<std::unordered_map<std::string, int>> points_of;  // per reconstruction
    std::vector<int> reconstruction_of_view;
    bool camera_dictionary = false;  // a file of cameras alone (camera_models.json)
};

std::int64_t point_id(const std::string& key, std::size_t index) {
    std::int64_t id = 0;
    const auto [end, error] = std::from_chars(key.data(), key.data() + key.size(), id);
    // OpenSfM's track ids are decimal; any other is known by its place in the file.
    return error == std::errc() && end == key.data() + key.size() ? id : static_cast<std::int64_t>(index);
}

// Each camera of a dictionary (id -> camera), named by its id (and its reconstruction's
// number after the first, where the same id may hold other values); id -> camera index.
std::unordered_map<std::string, int> add_cameras(const Field& cameras, const std::string& suffix,
                                                 ObservationSet& set) {
    if (cameras.node().kind != Kind::Map) cameras.fail("expected cameras by id, got " + cameras.shown());
    std::unordered_map<std::string, int> index_of;
    for (std::size_t i = 0; i < cameras.node().keys.size(); ++i) {
        const std::string& id = cameras.node().keys[i];
        const Field camera(cameras.node().items[i], cameras.name() + "." + id, cameras.source());
        index_of[id] = static_cast<int>(set.cameras.size());
        set.cameras.push_back({id + suffix, opensfm_camera(camera)});
    }
    return index_of;
}

void add_reconstruction(const Field& reconstruction, std::size_t number, Reconstructions& out) {
    const std::string suffix = number == 0 ? std::string() : " (reconstruction " + std::to_string(number + 1) + ")";
    const std::unordered_map<std::string, int> camera_of = add_cameras(reconstruction.at({"cameras"}), suffix, out.set);
    if (const std::optional<Field> shots = reconstruction.find({"shots"})) {
        if (shots->node().kind != Kind::Map) shots->fail("expected shots by name, got " + shots->shown());
        for (std::size_t i = 0; i < shots->node().keys.size(); ++i) {
            const std::string& name = shots->node().keys[i];
            const Field shot(shots->node().items[i], shots->name() + "." + name, shots->source());
            const std::string camera = shot.at({"camera"}).text();
            const auto found = camera_of.find(camera);
            if (found == camera_of.end()) shot.fail_at("camera", shown_value(camera) + " is not one of the cameras");
            Pose pose;
            try {
                pose = Pose::from_rvec(three_numbers(shot.at({"rotation"})), three_numbers(shot.at({"translation"})));
            } catch (const InvalidArgument& error) {
                shot.fail(error.what());
            }
            out.view_of_shot.emplace(name, static_cast<int>(out.set.views.size()));
            out.reconstruction_of_view.push_back(static_cast<int>(number));
            out.set.views.push_back({name, found->second, pose});
        }
    }
    std::unordered_map<std::string, int>& points = out.points_of.emplace_back();
    if (const std::optional<Field> list = reconstruction.find({"points"})) {
        if (list->node().kind != Kind::Map) list->fail("expected points by track id, got " + list->shown());
        for (std::size_t i = 0; i < list->node().keys.size(); ++i) {
            const std::string& id = list->node().keys[i];
            const Field point(list->node().items[i], list->name() + "." + id, list->source());
            points.emplace(id, static_cast<int>(out.set.points.size()));
            out.set.point_ids.push_back(point_id(id, out.set.points.size()));
            out.set.points.push_back(three_numbers(point.at({"coordinates"})));
        }
    }
}

Reconstructions read_reconstructions(std::string_view text, const std::string& source) {
    const DocumentNode root = parse_json_tree(text, source);
    const Field top(root, "", source);
    Reconstructions out;
    out.set.tool = ObservationTool::OpenSfm;
    out.set.source = source;
    out.set.pixel_offset = Vec2(kPixelCentre, kPixelCentre);
    if (root.kind == Kind::Map) {
        // camera_models.json, ODM's cameras.json: the cameras alone.
        out.camera_dictionary = true;
        add_cameras(top, "", out.set);
        if (out.set.cameras.empty()) top.fail("no camera");
        return out;
    }
    if (root.kind != Kind::Sequence) top.fail("expected a list of reconstructions, got " + top.shown());
    if (top.size() == 0) top.fail("no reconstruction");
    for (std::size_t i = 0; i < top.size(); ++i) add_reconstruction(top.item(i), i, out);
    return out;
}

// ---- tracks.csv ----------------------------------------------------------------------

std::vector<std::string_view> split_tabs(std::string_view line) {
    std::vector<std::string_view> fields;
    std::size_t start = 0;
    while (true) {
        const std::size_t tab = line.find('\t', start);
        fields.push_back(line.substr(start, tab == std::string_view::npos ? std::string_view::npos : tab - start));
        if (tab == std::string_view::npos) return fields;
        start = tab + 1;
    }
}

double csv_number(std::string_view word, const std::string& where, const char* column) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (error != std::errc() || end != word.data() + word.size() || !std::isfinite(value)) {
        throw FileError(where + ": " + column + ": " + shown_value(word) + " is not a finite number");
    }
    return value;
}

// The version line OpenSfM writes first (v1..v3: shot, track, feature, x, y, scale, r, g,
// b, then segmentation and instance from v2); a file without one is the older layout,
// whose first five columns are the same.
bool is_version_line(std::string_view line, const std::string& source) {
    constexpr std::string_view kPrefix = "OPENSFM_TRACKS_VERSION";
    if (!line.starts_with(kPrefix)) return false;
    const std::string_view version = line.substr(kPrefix.size());
    if (version != "_v1" && version != "_v2" && version != "_v3") {
        throw FileError(source + ": line 1: unknown tracks version " + shown_value(line) +
                        " (OpenSfM's: OPENSFM_TRACKS_VERSION_v1, _v2, _v3)");
    }
    return true;
}

void add_track_row(std::string_view line, const std::string& where, Reconstructions& out) {
    const std::vector<std::string_view> fields = split_tabs(line);
    if (fields.size() < 5) {
        throw FileError(where + ": expected shot, track, feature, x, y separated by tabs, got " +
                        std::to_string(fields.size()) + " column(s)");
    }
    const auto view = out.view_of_shot.find(std::string(fields[0]));
    if (view == out.view_of_shot.end()) return;  // an image no reconstruction holds
    const auto& points = out.points_of[static_cast<std::size_t>(out.reconstruction_of_view[static_cast<std::size_t>(view->second)])];
    const auto point = points.find(std::string(fields[1]));
    if (point == points.end()) return;  // a track that was not triangulated
    const ObservedView& shot = out.set.views[static_cast<std::size_t>(view->second)];
    const Normalized frame = normalized_frame(out.set.cameras[static_cast<std::size_t>(shot.camera)].camera.size);
    const Vec2 pixel = frame.pixel(csv_number(fields[3], where, "x"), csv_number(fields[4], where, "y"));
    out.set.observations.push_back({view->second, point->second, pixel});
}

void add_tracks(std::string_view text, const std::string& source, Reconstructions& out) {
    std::size_t start = 0;
    for (int line_number = 1; start < text.size(); ++line_number) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(start, end - start);
        start = end + 1;
        if (line.ends_with('\r')) line.remove_suffix(1);
        if (line.empty() || (line_number == 1 && is_version_line(line, source))) continue;
        add_track_row(line, source + ": line " + std::to_string(line_number), out);
    }
}

}  // namespace

bool claims_opensfm(const DocumentNode& root) {
    if (root.kind == Kind::Sequence) {
        return !root.items.empty() && (root.items[0].find("shots") != nullptr || root.items[0].find("cameras") != nullptr);
    }
    return root.kind == Kind::Map && !root.items.empty() && root.items[0].find("projection_type") != nullptr;
}

std::vector<NamedCamera> read_opensfm(std::string_view text, const ReadContext& context) {
    return detail::cameras_of_views(read_reconstructions(text, context.source).set, context.source, "");
}

ObservationSet read_opensfm_observations(const std::filesystem::path& file, std::string_view text,
                                         const ObservationReadOptions&) {
    const std::string source = file.string();
    Reconstructions read = read_reconstructions(text, source);
    if (read.camera_dictionary) {
        throw FileError(source + ": OpenSfM's cameras alone, which hold no observations (they are in "
                                 "reconstruction.json with tracks.csv beside it)");
    }
    const std::filesystem::path tracks = file.parent_path() / "tracks.csv";
    if (!regular_file_exists(tracks)) {
        throw FileError(source + ": no tracks.csv beside it: OpenSfM keeps the observed pixels there");
    }
    add_tracks(read_text_file(tracks, kReconstructionLimit), tracks.string(), read);
    if (read.set.observations.empty()) {
        throw FileError(tracks.string() + ": no row of a shot and a point of the reconstruction");
    }
    return std::move(read.set);
}

}  // namespace libcam
