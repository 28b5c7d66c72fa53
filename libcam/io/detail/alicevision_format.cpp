#include "libcam/io/detail/alicevision_format.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include <nlohmann/json.hpp>

#include "libcam/error.hpp"
#include "libcam/geometry/image_size.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"

// Every switch over LensType here names every model, with no default: a new model stops
// the build until someone decides what this file does with it.
#pragma GCC diagnostic error "-Wswitch"

namespace libcam {

namespace {

using Kind = DocumentNode::Kind;

// AliceVision's ids are 32-bit (IndexT); its largest marks "undefined".
constexpr long long kMaxId = 0xffffffffLL;
// AliceVision's UndefinedIndexT: the id of an intrinsic or pose a view does not have.
constexpr long long kUndefinedId = kMaxId;

// The newest version libcam knows: AliceVision refuses a file newer than itself, and so
// does libcam (the focal length's meaning changed as late as 1.2.11).
constexpr std::array<long long, 3> kNewestVersion = {1, 2, 11};

// boost writes every value as a string: read them as the numbers they hold.
void numbers_from_strings(DocumentNode& node) {
    if (node.kind == Kind::Scalar && node.tag == "string") node.tag.clear();
    for (DocumentNode& item : node.items) numbers_from_strings(item);
}

// A list, or boost's "" for an empty one.
std::vector<Field> items_of(const Field& list) {
    if (list.node().kind == Kind::Scalar && list.node().text.empty()) return {};
    std::vector<Field> items;
    for (std::size_t i = 0; i < list.size(); ++i) items.push_back(list.item(i));
    return items;
}

std::vector<Field> items_at(const Field& top, std::string_view key) {
    const std::optional<Field> list = top.find({key});
    return list ? items_of(*list) : std::vector<Field>{};
}

std::vector<double> exactly(const Field& field, std::size_t count) {
    const std::vector<double> values = field.numbers(count);
    if (values.size() != count) field.fail("expected " + std::to_string(count) + " numbers, got " + field.shown());
    return values;
}

bool truth(const Field& field) {
    if (const std::optional<bool> value = field.boolean()) return *value;
    const std::string text = field.node().text;
    if (text == "true" || text == "1") return true;
    if (text == "false" || text == "0") return false;
    field.fail("expected true or false, got " + field.shown());
}

using Version = std::array<long long, 3>;

Version read_version(const Field& top) {
    const Field field = top.at({"version"});
    if (field.size() != 3) field.fail("expected 3 numbers (major, minor, revision), got " + field.shown());
    Version version{};
    for (std::size_t i = 0; i < 3; ++i) version[i] = field.item(i).integer(0, 1000);
    if (version > kNewestVersion) {
        field.fail(std::to_string(version[0]) + "." + std::to_string(version[1]) + "." + std::to_string(version[2]) +
                   " is newer than the newest libcam reads (1.2.11)");
    }
    return version;
}

// ---- intrinsics ----------------------------------------------------------------------

// What an intrinsic's model is: the camera (pinhole or equidistant) and its distortion.
struct Model {
    bool equidistant = false;
    std::string distortion;  // none, radialk1, radialk3, radialk3pt, brown, fisheye, fisheye1
};

// Before 1.2.8 one "type" names both (cameraCommon.hpp's compatibilityStringToEnums).
Model model_before_1_2_8(const Field& type_field) {
    std::string type = type_field.text();
    std::transform(type.begin(), type.end(), type.begin(), [](unsigned char c) { return std::tolower(c); });
    if (type == "pinhole") return {false, "none"};
    if (type == "radial1") return {false, "radialk1"};
    if (type == "radial3") return {false, "radialk3"};
    if (type == "brown") return {false, "brown"};
    if (type == "fisheye4") return {false, "fisheye"};
    if (type == "fisheye1") return {false, "fisheye1"};
    if (type == "equidistant") return {true, "none"};
    if (type == "equidistant_r3") return {true, "radialk3pt"};
    type_field.fail("'" + type + "' has no libcam lens (libcam reads pinhole, radial1, radial3, brown, fisheye4, "
                                 "fisheye1, equidistant and equidistant_r3; the 3DE models are refused)");
}

std::string lower_text(const Field& field) {
    std::string text = field.text();
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
    return text;
}

Model read_model(const Field& intrinsic, const Version& version) {
    if (version < Version{1, 2, 8}) return model_before_1_2_8(intrinsic.at({"type"}));
    const Field type = intrinsic.at({"type"});
    const std::string camera = lower_text(type);
    if (camera != "pinhole" && camera != "equidistant") type.fail("expected pinhole or equidistant, got " + type.shown());
    if (const std::optional<Field> undistortion = intrinsic.find({"undistortionType"})) {
        if (lower_text(*undistortion) != "none") {
            undistortion->fail("'" + undistortion->text() + "' has no libcam lens (an undistortion map: libcam reads "
                                                           "intrinsics whose undistortionType is none)");
        }
    }
    const Field distortion = intrinsic.at({"distortionType"});
    const std::string name = lower_text(distortion);
    constexpr std::string_view kKnown[] = {"none", "radialk1", "radialk3", "radialk3pt", "brown", "fisheye", "fisheye1"};
    if (std::find(std::begin(kKnown), std::end(kKnown), name) == std::end(kKnown)) {
        distortion.fail("'" + name + "' is not one of AliceVision's distortions (none, radialk1, radialk3, radialk3pt, "
                                     "brown, fisheye, fisheye1)");
    }
    return {camera == "equidistant", name};
}

std::size_t coefficient_count(const std::string& distortion) {
    if (distortion == "none") return 0;
    if (distortion == "radialk1" || distortion == "fisheye1") return 1;
    if (distortion == "fisheye") return 4;
    if (distortion == "brown") return 5;
    return 3;  // radialk3, radialk3pt
}

// fx and fy in pixels, by the version's rules (the header's table).
std::array<double, 2> focal_lengths(const Field& intrinsic, const Version& version, double width, double sensor_width) {
    const auto number_or = [&](std::string_view key, double fallback) {
        const std::optional<Field> field = intrinsic.find({key});
        return field ? field->number() : fallback;
    };
    if (version < Version{1, 2, 0}) {
        const double focal = intrinsic.at({"pxFocalLength"}).number();
        return {focal, focal};
    }
    if (version < Version{1, 2, 2}) {
        const std::vector<double> focal = exactly(intrinsic.at({"pxFocalLength"}), 2);
        return {focal[0], focal[1]};
    }
    const double millimetres = number_or("focalLength", 1.0);
    const double ratio = number_or("pixelRatio", 1.0);
    if (!(ratio > 0.0)) intrinsic.fail_at("pixelRatio", "must be positive, got " + format_number(ratio));
    const double to_pixels = width / sensor_width;
    if (version < Version{1, 2, 5}) {
        const double fx = millimetres * to_pixels;
        return {fx, fx / ratio};
    }
    if (version < Version{1, 2, 11}) {
        const double fx = millimetres * to_pixels;
        return {fx, fx * ratio};
    }
    return {millimetres / ratio * to_pixels, millimetres * to_pixels};
}

// The pinhole's lens and the factor its focal lengths take (radialk3pt's normalisation).
Lens pinhole_lens(const Model& model, const std::vector<double>& k, double& focal_factor) {
    focal_factor = 1.0;
    const std::string& d = model.distortion;
    if (d == "none") return {LensType::Pinhole, {}};
    if (d == "radialk1") return {LensType::OpenCv4, {k[0], 0.0, 0.0, 0.0}};
    if (d == "radialk3") return {LensType::OpenCv5, {k[0], k[1], 0.0, 0.0, k[2]}};
    if (d == "brown") return {LensType::OpenCv5, {k[0], k[1], k[3], k[4], k[2]}};
    if (d == "fisheye") return {LensType::Fisheye, k};
    if (d == "fisheye1") return {LensType::Fov, k};
    focal_factor = 1.0 / (1.0 + k[0] + k[1] + k[2]);  // radialk3pt
    return {LensType::OpenCv5, {k[0], k[1], 0.0, 0.0, k[2]}};
}

struct SensorSize {
    double width = 36.0;
    double height = 24.0;
};

// The equidistant camera as FISHEYE (the header's derivation).
Lens equidistant_lens(const Model& model, const std::vector<double>& k, const Field& intrinsic, double fx,
                      const ImageSize& size, const SensorSize& sensor, double& focal_factor) {
    const std::string& d = model.distortion;
    if (d != "none" && d != "radialk1" && d != "radialk3" && d != "radialk3pt") {
        intrinsic.fail_at("distortionType", "'" + d + "' on an equidistant camera has no libcam lens (libcam reads none, "
                                                      "radialk1, radialk3 and radialk3pt there)");
    }
    const double fmm = fx * sensor.width / static_cast<double>(std::max(size.width, size.height));
    const double c = 2.0 * fmm / std::min(sensor.width, sensor.height);
    focal_factor = c;
    if (d == "none") return {LensType::Fisheye, {0.0, 0.0, 0.0, 0.0}};
    const double k1 = k[0];
    const double k2 = d == "radialk1" ? 0.0 : k[1];
    const double k3 = d == "radialk1" ? 0.0 : k[2];
    if (d == "radialk3pt") focal_factor = c / (1.0 + k1 + k2 + k3);
    return {LensType::Fisheye, {k1 * c * c, k2 * std::pow(c, 4), k3 * std::pow(c, 6), 0.0}};
}

Camera read_intrinsic(const Field& intrinsic, const Version& version) {
    Camera camera;
    camera.size = {static_cast<long>(intrinsic.at({"width"}).whole_number(1, kMaxImageSide)),
                   static_cast<long>(intrinsic.at({"height"}).whole_number(1, kMaxImageSide))};
    SensorSize sensor;
    if (const std::optional<Field> w = intrinsic.find({"sensorWidth"})) sensor.width = w->number();
    if (const std::optional<Field> h = intrinsic.find({"sensorHeight"})) sensor.height = h->number();
    if (!(sensor.width > 0.0)) intrinsic.fail_at("sensorWidth", "must be positive, got " + format_number(sensor.width));
    if (!(sensor.height > 0.0)) intrinsic.fail_at("sensorHeight", "must be positive, got " + format_number(sensor.height));
    const Model model = read_model(intrinsic, version);
    const auto width = static_cast<double>(camera.size.width);
    const auto height = static_cast<double>(camera.size.height);
    const std::array<double, 2> focal = focal_lengths(intrinsic, version, width, sensor.width);
    std::vector<double> k;
    if (const std::size_t count = coefficient_count(model.distortion); count > 0) {
        k = exactly(intrinsic.at({"distortionParams"}), count);
    }
    double factor = 1.0;
    camera.lens = model.equidistant
                      ? equidistant_lens(model, k, intrinsic, focal[0], camera.size, sensor, factor)
                      : pinhole_lens(model, k, factor);
    camera.lens = simplest_equal_lens(camera.lens);
    std::vector<double> centre = exactly(intrinsic.at({"principalPoint"}), 2);
    if (version >= Version{1, 2, 1}) {
        centre[0] += 0.5 * width;
        centre[1] += 0.5 * height;
    }
    camera.intrinsics = {focal[0] * factor, focal[1] * factor, centre[0], centre[1], 0.0};
    return validated_camera(camera, intrinsic.source() + ": \"" + intrinsic.name() + "\"");
}

// ---- poses ---------------------------------------------------------------------------

// A Pose3 as AliceVision writes it: rotation column by column, then the centre.
Pose read_pose3(const Field& pose) {
    const std::vector<double> r = exactly(pose.at({"rotation"}), 9);
    Mat3 R;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) R(i, j) = r[static_cast<std::size_t>(i + 3 * j)];
    }
    const std::vector<double> centre = exactly(pose.at({"center"}), 3);
    const Pose out = Pose::from_centre(nearest_rotation_if_rounded(R), Vec3(centre[0], centre[1], centre[2]));
    try {
        out.validate("rotation");
    } catch (const InvalidArgument& error) {
        pose.fail(error.what());
    }
    return out;
}

std::unordered_map<long long, Pose> read_poses(const Field& top) {
    std::unordered_map<long long, Pose> poses;
    for (const Field& entry : items_at(top, "poses")) {
        const long long id = entry.at({"poseId"}).integer(0, kMaxId);
        if (!poses.emplace(id, read_pose3(entry.at({"pose"}).at({"transform"}))).second) {
            entry.fail_at("poseId", std::to_string(id) + " given twice");
        }
    }
    return poses;
}

// Each rig's sub-poses, by rig id.
std::unordered_map<long long, std::vector<Pose>> read_rigs(const Field& top) {
    std::unordered_map<long long, std::vector<Pose>> rigs;
    for (const Field& rig : items_at(top, "rigs")) {
        std::vector<Pose> sub_poses;
        for (const Field& sub_pose : items_of(rig.at({"subPoses"}))) sub_poses.push_back(read_pose3(sub_pose.at({"pose"})));
        rigs[rig.at({"rigId"}).integer(0, kMaxId)] = std::move(sub_poses);
    }
    return rigs;
}

// ---- the file ------------------------------------------------------------------------

struct SfmData {
    ObservationSet set;
    std::unordered_map<long long, int> posed_view;  // view id -> index into set.views
    std::unordered_set<long long> every_view;
    // Views with an intrinsic but no pose (not localised).
    std::vector<ObservedView> unposed_views;
};

std::string intrinsic_name(long long id) { return "id:" + std::to_string(id); }

std::unordered_map<long long, int> read_intrinsics(const Field& top, const Version& version, ObservationSet& set) {
    std::unordered_map<long long, int> index_of;
    for (const Field& intrinsic : items_at(top, "intrinsics")) {
        const long long id = intrinsic.at({"intrinsicId"}).integer(0, kMaxId);
        if (!index_of.emplace(id, static_cast<int>(set.cameras.size())).second) {
            intrinsic.fail_at("intrinsicId", std::to_string(id) + " given twice");
        }
        set.cameras.push_back({intrinsic_name(id), read_intrinsic(intrinsic, version)});
    }
    return index_of;
}

// The view's pose: its pose, or for a view of a rig its sub-pose after the rig's.
std::optional<Pose> view_pose(const Field& view, const Pose& pose,
                              const std::unordered_map<long long, std::vector<Pose>>& rigs) {
    const std::optional<Field> rig_id = view.find({"rigId"});
    const std::optional<Field> independent = view.find({"isPoseIndependant"});
    if (!rig_id || !independent || truth(*independent)) return pose;
    const auto rig = rigs.find(rig_id->integer(0, kMaxId));
    if (rig == rigs.end()) rig_id->fail("names no rig of \"rigs\"");
    const long long sub = view.at({"subPoseId"}).integer(0, kMaxId);
    if (static_cast<std::size_t>(sub) >= rig->second.size()) {
        view.fail_at("subPoseId", std::to_string(sub) + " is not one of the rig's " +
                                      std::to_string(rig->second.size()) + " sub-poses");
    }
    return rig->second[static_cast<std::size_t>(sub)].after(pose);
}

void read_views(const Field& top, const std::unordered_map<long long, int>& intrinsics,
                const std::unordered_map<long long, Pose>& poses, SfmData& out) {
    const auto rigs = read_rigs(top);
    for (const Field& view : items_at(top, "views")) {
        const long long id = view.at({"viewId"}).integer(0, kMaxId);
        if (!out.every_view.insert(id).second) view.fail_at("viewId", std::to_string(id) + " given twice");
        const std::optional<Field> intrinsic_id = view.find({"intrinsicId"});
        const std::optional<Field> pose_id = view.find({"poseId"});
        if (!intrinsic_id || !pose_id) continue;
        const long long intrinsic_number = intrinsic_id->integer(0, kMaxId);
        if (intrinsic_number == kUndefinedId) continue;  // no intrinsic: not reconstructed
        // AliceVision writes an intrinsic for every id a view names; an id it lacks is a
        // dangling reference, not a view left out of the reconstruction.
        const auto intrinsic = intrinsics.find(intrinsic_number);
        if (intrinsic == intrinsics.end()) {
            intrinsic_id->fail("view " + std::to_string(id) + " names intrinsic " + std::to_string(intrinsic_number) +
                               ", which \"intrinsics\" lacks");
        }
        // "poses" holds the reconstructed views' poses alone: a view without one was not
        // localised (AliceVision's SfMData::isPoseAndIntrinsicDefined).
        const Camera& camera = out.set.cameras[static_cast<std::size_t>(intrinsic->second)].camera;
        for (const auto& [key, side] : {std::pair{"width", camera.size.width}, std::pair{"height", camera.size.height}}) {
            const std::optional<Field> given = view.find({key});
            if (given && given->whole_number(0, kMaxImageSide) != 0 && given->whole_number(0, kMaxImageSide) != side) {
                given->fail("the view's image is " + given->node().text + " pixels, its intrinsic's " + std::to_string(side));
            }
        }
        const auto pose = poses.find(pose_id->integer(0, kMaxId));
        if (pose == poses.end()) {
            out.unposed_views.push_back({view.at({"path"}).text(), intrinsic->second, Pose()});
            continue;
        }
        out.posed_view[id] = static_cast<int>(out.set.views.size());
        out.set.views.push_back({view.at({"path"}).text(), intrinsic->second, *view_pose(view, pose->second, rigs)});
    }
}

void read_structure(const Field& top, SfmData& out) {
    for (const Field& landmark : items_at(top, "structure")) {
        const std::vector<double> X = exactly(landmark.at({"X"}), 3);
        const int point = static_cast<int>(out.set.points.size());
        out.set.points.push_back({X[0], X[1], X[2]});
        out.set.point_ids.push_back(landmark.at({"landmarkId"}).integer(0, kMaxId));
        const std::optional<Field> observations = landmark.find({"observations"});
        if (!observations) continue;
        for (const Field& observation : items_of(*observations)) {
            const long long view_id = observation.at({"observationId"}).integer(0, kMaxId);
            if (!out.every_view.contains(view_id)) {
                observation.fail_at("observationId", std::to_string(view_id) + " is not one of the views");
            }
            const auto view = out.posed_view.find(view_id);
            if (view == out.posed_view.end()) continue;  // a view without a pose: nothing to project
            const std::vector<double> x = exactly(observation.at({"x"}), 2);
            out.set.observations.push_back({view->second, point, Vec2(x[0], x[1])});
        }
    }
}

SfmData read_sfm_data(std::string_view text, const std::string& source) {
    DocumentNode root = parse_json_tree(text, source);
    if (!claims_alicevision(root)) {
        Field(root, "", source).fail("expected AliceVision's \"version\" beside \"views\" or \"intrinsics\"");
    }
    numbers_from_strings(root);
    const Field top(root, "", source);
    const Version version = read_version(top);
    SfmData out;
    out.set.tool = ObservationTool::AliceVision;
    out.set.source = source;
    const std::unordered_map<long long, int> intrinsics = read_intrinsics(top, version, out.set);
    read_views(top, intrinsics, read_poses(top), out);
    read_structure(top, out);
    return out;
}

// ---- writing -------------------------------------------------------------------------

std::string text_of(double value) { return format_number(value); }

nlohmann::ordered_json numbers_json(std::initializer_list<double> values) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const double value : values) list.push_back(text_of(value));
    return list;
}

// The simplest of AliceVision's types (before 1.2.8's names) holding the lens, and its
// distortionParams.
std::pair<std::string, std::vector<double>> alicevision_type(const Lens& lens) {
    const std::vector<double>& k = lens.coefficients;
    switch (lens.type) {
        case LensType::Pinhole: return {"pinhole", {}};
        case LensType::OpenCv4:
        case LensType::OpenCv5: {
            const double k3 = lens.type == LensType::OpenCv5 ? k[4] : 0.0;
            if (k[2] == 0.0 && k[3] == 0.0) {
                if (k[1] == 0.0 && k3 == 0.0) return {"radial1", {k[0]}};
                return {"radial3", {k[0], k[1], k3}};
            }
            return {"brown", {k[0], k[1], k3, k[2], k[3]}};
        }
        case LensType::Fisheye: return {"fisheye4", k};
        case LensType::Fov: return {"fisheye1", k};
        // Every other model, named so that the compiler asks here about a new one.
        case LensType::OpenCv8:
        case LensType::OpenCv12:
        case LensType::OpenCv14:
        case LensType::Stereographic:
        case LensType::Lonlat:
        case LensType::Latlon:
        case LensType::DoubleSphere:
        case LensType::Ucm:
        case LensType::Eucm:
        case LensType::Mei:
        case LensType::ThinPrismFisheye:
        case LensType::RadTanThinPrismFisheye:
        case LensType::Equisolid:
        case LensType::Cahvor:
        case LensType::Cahvore:
        case LensType::LensPolynomial:
        case LensType::SplinedStereographic:
        case LensType::Cylindrical:
        case LensType::Ptlens:
        case LensType::OcamCalib:
        case LensType::Division:
        case LensType::ThetaPolynomial:
        case LensType::FTheta:
        case LensType::FThetaForward:
        case LensType::BrownK4:
        case LensType::EquidistantRadial:
        case LensType::EquisolidRadial:
        case LensType::StereographicRadial:
            detail::refuse_lens(CameraFormat::AliceVision, lens.type);
    }
    detail::refuse_lens(CameraFormat::AliceVision, lens.type);
}

}  // namespace

bool claims_alicevision(const DocumentNode& root) {
    const DocumentNode* version = root.find("version");
    return version != nullptr && version->kind == Kind::Sequence &&
           (root.find("views") != nullptr || root.find("intrinsics") != nullptr) &&
           root.find("sfm_data_version") == nullptr;
}

std::vector<NamedCamera> read_alicevision(std::string_view text, const ReadContext& context) {
    const SfmData read = read_sfm_data(text, context.source);
    return detail::cameras_of_views(read.set, context.source, "\"intrinsics\": ", read.unposed_views);
}

ObservationSet read_alicevision_observations(const std::filesystem::path& file, std::string_view text,
                                             const ObservationReadOptions&) {
    const std::string source = file.string();
    SfmData read = read_sfm_data(text, source);
    if (read.set.observations.empty()) {
        throw FileError(source + ": \"structure\": no observation in a view with a pose (a file saved without its "
                                 "structure or observations: ConvertSfMFormat's Structure and Observations options)");
    }
    return std::move(read.set);
}

std::string format_alicevision(const Camera& camera, const WriteOptions& options) {
    if (camera.intrinsics.skew != 0.0) {
        throw NotRepresentable("AliceVision's cameras.sfm has no skew; this camera's is " +
                               format_number(camera.intrinsics.skew));
    }
    const auto [type, k] = alicevision_type(camera.lens);
    const auto width = static_cast<double>(camera.size.width);
    const auto height = static_cast<double>(camera.size.height);
    // A 36 mm wide sensor of the image's aspect: fx = focalLength w / sensorWidth, and
    // 1.2.6's pixelRatio is fy / fx.
    const double sensor_width = 36.0;
    const Intrinsics& K = camera.intrinsics;
    nlohmann::ordered_json distortion = nlohmann::ordered_json::array();
    for (const double value : k) distortion.push_back(text_of(value));

    nlohmann::ordered_json view;
    view["viewId"] = "1";
    view["poseId"] = "1";
    view["intrinsicId"] = "1";
    view["path"] = options.image_name;
    view["width"] = std::to_string(camera.size.width);
    view["height"] = std::to_string(camera.size.height);
    view["metadata"] = "";

    nlohmann::ordered_json intrinsic;
    intrinsic["intrinsicId"] = "1";
    intrinsic["width"] = std::to_string(camera.size.width);
    intrinsic["height"] = std::to_string(camera.size.height);
    intrinsic["sensorWidth"] = text_of(sensor_width);
    intrinsic["sensorHeight"] = text_of(sensor_width * height / width);
    intrinsic["serialNumber"] = "";
    intrinsic["type"] = type;
    intrinsic["initializationMode"] = "calibrated";
    intrinsic["initialFocalLength"] = "-1";
    intrinsic["focalLength"] = text_of(K.fx * sensor_width / width);
    intrinsic["pixelRatio"] = text_of(K.fy / K.fx);
    intrinsic["pixelRatioLocked"] = K.fx == K.fy ? "true" : "false";
    intrinsic["principalPoint"] = numbers_json({K.cx - 0.5 * width, K.cy - 0.5 * height});
    intrinsic["distortionInitializationMode"] = "none";
    intrinsic["distortionParams"] = k.empty() ? nlohmann::ordered_json("") : distortion;
    intrinsic["undistortionOffset"] = numbers_json({0.0, 0.0});
    intrinsic["undistortionParams"] = "";
    intrinsic["locked"] = "false";

    const Mat3& R = camera.pose.R;
    const Vec3 centre = camera.pose.centre();
    nlohmann::ordered_json rotation = nlohmann::ordered_json::array();
    for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) rotation.push_back(text_of(R(i, j)));  // column by column
    }
    nlohmann::ordered_json pose;
    pose["poseId"] = "1";
    pose["pose"]["transform"]["rotation"] = rotation;
    pose["pose"]["transform"]["center"] = numbers_json({centre.x(), centre.y(), centre.z()});
    pose["pose"]["locked"] = "false";

    nlohmann::ordered_json out;
    out["version"] = {"1", "2", "6"};
    out["views"] = nlohmann::ordered_json::array({view});
    out["intrinsics"] = nlohmann::ordered_json::array({intrinsic});
    out["poses"] = nlohmann::ordered_json::array({pose});
    return out.dump(4) + "\n";
}

}  // namespace libcam
