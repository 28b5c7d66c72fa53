#include "libcam/io/detail/openmvg_format.hpp"

#include <algorithm>
#include <numbers>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "libcam/error.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam {

namespace {

using Kind = DocumentNode::Kind;

// OpenMVG's ids are 32-bit; its UndefinedIndexT (the largest) marks a view without a pose.
constexpr long long kMaxId = 0xffffffffLL;
// cereal marks the first time it writes a polymorphic type or a pointer with this bit, and
// writes the type's name or the pointer's data only then.
constexpr long long kFirstTime = 0x80000000LL;

// cereal's polymorphic pointers, by id: the type names and the objects already given.
struct Cereal {
    std::unordered_map<long long, std::string> type_names;
    std::unordered_map<long long, const DocumentNode*> objects;
};

std::string type_name(const Field& value, Cereal& cereal) {
    const long long id = value.at({"polymorphic_id"}).integer(0, kMaxId) & ~kFirstTime;
    if (const std::optional<Field> name = value.find({"polymorphic_name"})) {
        cereal.type_names[id] = name->text();
        return name->text();
    }
    const auto found = cereal.type_names.find(id);
    if (found == cereal.type_names.end()) {
        value.fail_at("polymorphic_id", std::to_string(id) + " names no type given before it");
    }
    return found->second;
}

Field pointer_data(const Field& value, Cereal& cereal) {
    const Field wrapper = value.at({"ptr_wrapper"});
    const long long id = wrapper.at({"id"}).integer(0, kMaxId) & ~kFirstTime;
    if (const std::optional<Field> data = wrapper.find({"data"})) {
        cereal.objects[id] = &data->node();
        return *data;
    }
    const auto found = cereal.objects.find(id);
    if (found == cereal.objects.end()) wrapper.fail_at("id", std::to_string(id) + " names no object given before it");
    return Field(*found->second, wrapper.name() + ".data", wrapper.source());
}

// A key of an intrinsic's data, or of the base class cereal nested in its "value0" (newer
// OpenMVG writes the pinhole's keys there).
std::optional<Field> key_in(const Field& data, std::string_view key) {
    if (std::optional<Field> field = data.find({key})) return field;
    if (const std::optional<Field> base = data.find({"value0"}); base && base->node().kind == Kind::Map) {
        return key_in(*base, key);
    }
    return std::nullopt;
}

Field required_key(const Field& data, std::string_view key) {
    if (std::optional<Field> field = key_in(data, key)) return *field;
    data.fail_at(key, "missing");
}

std::vector<double> exactly(const Field& field, std::size_t count) {
    const std::vector<double> values = field.numbers(count);
    if (values.size() != count) field.fail("expected " + std::to_string(count) + " numbers, got " + field.shown());
    return values;
}

// The distortion of each type OpenMVG writes, as the libcam lens holding it exactly.
Lens openmvg_lens(const Field& data, const std::string& type, const Field& intrinsic) {
    const auto coefficients = [&](std::string_view key, std::size_t count) {
        return exactly(required_key(data, key), count);
    };
    if (type == "pinhole") return {LensType::Pinhole, {}};
    if (type == "pinhole_radial_k1") return {LensType::OpenCv4, {coefficients("disto_k1", 1)[0], 0.0, 0.0, 0.0}};
    if (type == "pinhole_radial_k3") {
        const std::vector<double> k = coefficients("disto_k3", 3);
        return {LensType::OpenCv5, {k[0], k[1], 0.0, 0.0, k[2]}};
    }
    if (type == "pinhole_brown_t2") {
        const std::vector<double> k = coefficients("disto_t2", 5);  // k1 k2 k3 t1 t2
        return {LensType::OpenCv5, {k[0], k[1], k[3], k[4], k[2]}};
    }
    if (type == "fisheye") return {LensType::Fisheye, coefficients("fisheye", 4)};
    if (type == "spherical") return {LensType::Lonlat, {}};
    intrinsic.fail_at("polymorphic_name", "'" + type +
                                              "' is refused: libcam holds OpenMVG's pinhole, pinhole_radial_k1, "
                                              "pinhole_radial_k3, pinhole_brown_t2, fisheye and spherical");
}

Camera openmvg_camera(const Field& data, const std::string& type, const Field& intrinsic) {
    Camera camera;
    camera.size = {static_cast<long>(required_key(data, "width").whole_number(1, kMaxImageSide)),
                   static_cast<long>(required_key(data, "height").whole_number(1, kMaxImageSide))};
    camera.lens = simplest_equal_lens(openmvg_lens(data, type, intrinsic));
    if (camera.lens.type == LensType::Lonlat) {
        // cam2ima: (lon, lat) / (2 pi) * max(width, height) + (width / 2, height / 2).
        const auto width = static_cast<double>(camera.size.width);
        const auto height = static_cast<double>(camera.size.height);
        const double focal = std::max(width, height) / (2.0 * std::numbers::pi);
        camera.intrinsics = {focal, focal, 0.5 * width, 0.5 * height, 0.0};
    } else {
        const double focal = required_key(data, "focal_length").number();
        const std::vector<double> centre = exactly(required_key(data, "principal_point"), 2);
        camera.intrinsics = {focal, focal, centre[0], centre[1], 0.0};
    }
    return validated_camera(camera, intrinsic.source() + ": \"" + intrinsic.name() + "\"");
}

// ---- the file ------------------------------------------------------------------------

struct SfmData {
    ObservationSet set;
    std::unordered_map<long long, int> posed_view;  // view id -> index into set.views
    std::unordered_set<long long> every_view;
    // Views with an intrinsic but no pose (before SfM, or not localised by it).
    std::vector<ObservedView> unposed_views;
};

std::string intrinsic_name(long long id) { return "id:" + std::to_string(id); }

// A cereal map written as a list of {key, value}: each entry's key and value.
template <class Each>
void for_each_entry(const Field& list, Each each) {
    for (std::size_t i = 0; i < list.size(); ++i) {
        const Field entry = list.item(i);
        each(entry.at({"key"}).integer(0, kMaxId), entry.at({"value"}));
    }
}

std::optional<Field> list_of(const Field& top, std::string_view key) {
    std::optional<Field> list = top.find({key});
    if (list && list->node().kind != Kind::Sequence) list->fail("expected a list of {key, value}, got " + list->shown());
    return list;
}

std::unordered_map<long long, int> read_intrinsics(const Field& top, ObservationSet& set) {
    std::unordered_map<long long, int> index_of;
    Cereal cereal;
    if (const std::optional<Field> list = list_of(top, "intrinsics")) {
        for_each_entry(*list, [&](long long id, const Field& value) {
            const std::string type = type_name(value, cereal);
            index_of[id] = static_cast<int>(set.cameras.size());
            set.cameras.push_back({intrinsic_name(id), openmvg_camera(pointer_data(value, cereal), type, value)});
        });
    }
    return index_of;
}

std::unordered_map<long long, Pose> read_extrinsics(const Field& top) {
    std::unordered_map<long long, Pose> poses;
    if (const std::optional<Field> list = list_of(top, "extrinsics")) {
        for_each_entry(*list, [&](long long id, const Field& value) {
            const Field rotation = value.at({"rotation"});
            if (rotation.size() != 3) rotation.fail("expected 3 rows, got " + rotation.shown());
            Mat3 R;
            for (Eigen::Index row = 0; row < 3; ++row) {
                const std::vector<double> numbers = exactly(rotation.item(static_cast<std::size_t>(row)), 3);
                R.row(row) = Vec3(numbers[0], numbers[1], numbers[2]).transpose();
            }
            const std::vector<double> centre = exactly(value.at({"center"}), 3);
            const Pose pose = Pose::from_centre(nearest_rotation_if_rounded(R), Vec3(centre[0], centre[1], centre[2]));
            try {
                pose.validate("rotation");
            } catch (const InvalidArgument& error) {
                value.fail(error.what());
            }
            poses[id] = pose;
        });
    }
    return poses;
}

void read_views(const Field& top, const std::unordered_map<long long, int>& intrinsics,
                const std::unordered_map<long long, Pose>& poses, SfmData& out) {
    const std::optional<Field> list = list_of(top, "views");
    if (!list) return;
    Cereal cereal;
    for_each_entry(*list, [&](long long id, const Field& value) {
        const Field data = pointer_data(value, cereal);
        out.every_view.insert(id);
        const Field intrinsic_id = data.at({"id_intrinsic"});
        const long long intrinsic_number = intrinsic_id.integer(0, kMaxId);
        if (intrinsic_number == kMaxId) return;  // UndefinedIndexT: no intrinsic, not reconstructed
        // OpenMVG writes an intrinsic for every id a view names (and its Load refuses an
        // intrinsic no view names); an id it lacks is a dangling reference.
        const auto intrinsic = intrinsics.find(intrinsic_number);
        if (intrinsic == intrinsics.end()) {
            intrinsic_id.fail("view " + std::to_string(id) + " names intrinsic " + std::to_string(intrinsic_number) +
                              ", which \"intrinsics\" lacks");
        }
        // "extrinsics" holds the reconstructed views' poses alone: a view without one was not
        // localised (OpenMVG's SfM_Data::IsPoseAndIntrinsicDefined).
        const auto pose = poses.find(data.at({"id_pose"}).integer(0, kMaxId));
        if (pose == poses.end()) {
            out.unposed_views.push_back({data.at({"filename"}).text(), intrinsic->second, Pose()});
            return;
        }
        out.posed_view[id] = static_cast<int>(out.set.views.size());
        out.set.views.push_back({data.at({"filename"}).text(), intrinsic->second, pose->second});
    });
}

void read_structure(const Field& top, SfmData& out) {
    const std::optional<Field> list = list_of(top, "structure");
    if (!list) return;
    for_each_entry(*list, [&](long long id, const Field& landmark) {
        const std::vector<double> X = exactly(landmark.at({"X"}), 3);
        const int point = static_cast<int>(out.set.points.size());
        out.set.points.push_back({X[0], X[1], X[2]});
        out.set.point_ids.push_back(id);
        const Field observations = landmark.at({"observations"});
        for_each_entry(observations, [&](long long view_id, const Field& observation) {
            if (!out.every_view.contains(view_id)) {
                observations.fail("view " + std::to_string(view_id) + " is not one of the views");
            }
            const auto view = out.posed_view.find(view_id);
            if (view == out.posed_view.end()) return;  // a view without a pose: nothing to project
            const std::vector<double> x = exactly(observation.at({"x"}), 2);
            out.set.observations.push_back({view->second, point, Vec2(x[0], x[1])});
        });
    });
}

SfmData read_sfm_data(std::string_view text, const std::string& source) {
    const DocumentNode root = parse_json_tree(text, source);
    const Field top(root, "", source);
    if (!claims_openmvg(root)) top.fail("expected OpenMVG's \"sfm_data_version\"");
    SfmData out;
    out.set.tool = ObservationTool::OpenMvg;
    out.set.source = source;
    const std::unordered_map<long long, int> intrinsics = read_intrinsics(top, out.set);
    read_views(top, intrinsics, read_extrinsics(top), out);
    read_structure(top, out);
    return out;
}

}  // namespace

bool claims_openmvg(const DocumentNode& root) { return root.find("sfm_data_version") != nullptr; }

std::vector<NamedCamera> read_openmvg(std::string_view text, const ReadContext& context) {
    const SfmData read = read_sfm_data(text, context.source);
    return detail::cameras_of_views(read.set, context.source, "\"intrinsics\": ", read.unposed_views);
}

ObservationSet read_openmvg_observations(const std::filesystem::path& file, std::string_view text,
                                         const ObservationReadOptions&) {
    const std::string source = file.string();
    SfmData read = read_sfm_data(text, source);
    if (read.set.observations.empty()) {
        throw FileError(source + ": \"structure\": no observation in a view with a pose (an sfm_data.json before "
                                 "SfM, or one saved without its structure)");
    }
    return std::move(read.set);
}

}  // namespace libcam
