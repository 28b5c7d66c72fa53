#include "libcam/io/detail/driveworks_rig.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>

#include "libcam/error.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

constexpr std::size_t kMaxPolynomialCoefficients = 6;  // degree 5, as NCore and 3DGUT hold it
constexpr std::string_view kBackward = "pixeldistance-to-angle";
constexpr std::string_view kForward = "angle-to-pixeldistance";

// The rotation from OpenCV's camera axes (x right, y down, z forward) to the sensor's FLU
// axes (x forward, y left, z up).
Mat3 camera_to_flu() {
    Mat3 s;
    s << 0, 0, 1, -1, 0, 0, 0, -1, 0;
    return s;
}

// A property that DriveWorks writes as a string ("1919.420") or a tool writes as a number.
double property_number(const Field& field) {
    DocumentNode as_number = field.node();
    if (as_number.kind == DocumentNode::Kind::Scalar && as_number.tag == "string") as_number.tag = "number";
    return Field(as_number, field.name(), field.source()).number();
}

long long property_integer(const Field& field, long long max) {
    DocumentNode as_number = field.node();
    if (as_number.kind == DocumentNode::Kind::Scalar && as_number.tag == "string") as_number.tag = "number";
    return Field(as_number, field.name(), field.source()).whole_number(1, max);
}

// The coefficients of a polynomial written as one string of numbers separated by spaces.
std::vector<double> polynomial_of(const Field& field) {
    if (field.node().kind != DocumentNode::Kind::Scalar) field.fail("expected the coefficients as a string of numbers");
    DocumentNode list;
    list.kind = DocumentNode::Kind::Sequence;
    const std::string& text = field.node().text;
    for (std::size_t i = 0; i < text.size();) {
        const std::size_t start = text.find_first_not_of(" \t\r\n", i);
        if (start == std::string::npos) break;
        const std::size_t end = std::min(text.find_first_of(" \t\r\n", start), text.size());
        DocumentNode word;
        word.kind = DocumentNode::Kind::Scalar;
        word.tag = "number";
        word.text = text.substr(start, end - start);
        list.items.push_back(std::move(word));
        // More words than a degree-5 polynomial has are refused below; stop collecting.
        if (list.items.size() > kMaxPolynomialCoefficients) break;
        i = end;
    }
    const std::vector<double> b = Field(list, field.name(), field.source()).numbers(kMaxPolynomialCoefficients);
    if (b.size() < 2) field.fail("expected at least 2 coefficients (b0 b1), got " + std::to_string(b.size()));
    if (b[0] != 0.0) {
        field.fail("b0 (the polynomial at the principal point) must be 0, got " + format_number(b[0]) +
                   ": the principal point is the optical axis");
    }
    if (!(b[1] > 0.0)) field.fail("b1 must be positive (it must grow from the centre), got " + format_number(b[1]));
    return b;
}

// The calibrated polynomial and which way it maps.
struct Polynomial {
    std::vector<double> coefficients;
    bool forward = false;  // angle to pixel distance (FTHETA_FORWARD), else the backward one (FTHETA)
};

// "polynomial" with its "polynomial-type", or an older rig's "bw-poly" (backward).
Polynomial calibrated_polynomial(const Field& properties) {
    if (const std::optional<Field> polynomial = properties.find({"polynomial"})) {
        const Field type = properties.at({"polynomial-type"});
        const std::string kind = type.text();
        if (kind != kBackward && kind != kForward) {
            type.fail("must be " + std::string(kBackward) + " or " + std::string(kForward) + ", got " +
                      shown_value(kind));
        }
        return {polynomial_of(*polynomial), kind == kForward};
    }
    return {polynomial_of(properties.at({"bw-poly"})), false};
}

double property_or(const Field& properties, std::string_view key, double fallback) {
    const std::optional<Field> field = properties.find({key});
    return field ? property_number(*field) : fallback;
}

Camera read_intrinsics(const Field& properties) {
    const Field model = properties.at({"Model"});
    if (model.text() != "ftheta") {
        model.fail("libcam reads DriveWorks' ftheta cameras, got " + shown_value(model.text()));
    }
    const Polynomial polynomial = calibrated_polynomial(properties);
    const std::vector<double>& b = polynomial.coefficients;
    // Pixels per unit of m: the focal length at the centre, so that k1 = 1.
    const double f = polynomial.forward ? b[1] : 1.0 / b[1];
    Camera camera;
    camera.size = {static_cast<long>(property_integer(properties.at({"width"}), kMaxImageSide)),
                   static_cast<long>(property_integer(properties.at({"height"}), kMaxImageSide))};
    camera.intrinsics = {f, f, property_number(properties.at({"cx"})), property_number(properties.at({"cy"})), 0.0};
    camera.lens.type = polynomial.forward ? LensType::FThetaForward : LensType::FTheta;
    camera.lens.coefficients = {property_or(properties, "linear-c", 1.0), property_or(properties, "linear-d", 0.0),
                                property_or(properties, "linear-e", 0.0)};
    // Backward: theta = b_i p^i = b_i f^i r^i. Forward: p = a_i theta^i, r = p / f.
    for (std::size_t i = 1; i <= 5; ++i) {
        const double scale = polynomial.forward ? 1.0 / f : std::pow(f, static_cast<double>(i));
        camera.lens.coefficients.push_back(i < b.size() ? b[i] * scale : 0.0);
    }
    camera.lens.coefficients.push_back(std::numbers::pi);
    return camera;
}

// Rz(yaw) Ry(pitch) Rx(roll) of roll-pitch-yaw in degrees.
Mat3 rotation_of(const Field& roll_pitch_yaw) {
    const std::vector<double> angles = roll_pitch_yaw.numbers(3);
    if (angles.size() != 3) roll_pitch_yaw.fail("expected [roll, pitch, yaw] in degrees, got " + std::to_string(angles.size()) + " numbers");
    const double to_radians = std::numbers::pi / 180.0;
    return (Eigen::AngleAxisd(angles[2] * to_radians, Vec3::UnitZ()) * Eigen::AngleAxisd(angles[1] * to_radians, Vec3::UnitY()) *
            Eigen::AngleAxisd(angles[0] * to_radians, Vec3::UnitX()))
        .toRotationMatrix();
}

Vec3 translation_of(const Field& field) {
    const std::vector<double> t = field.numbers(3);
    if (t.size() != 3) field.fail("expected [x, y, z] in metres, got " + std::to_string(t.size()) + " numbers");
    return {t[0], t[1], t[2]};
}

// Rig to camera (OpenCV's axes), from the sensor's place in the rig and its corrections.
Pose read_pose(const Field& sensor) {
    const Field nominal = sensor.at({"nominalSensor2Rig_FLU"});
    Mat3 sensor_to_rig = rotation_of(nominal.at({"roll-pitch-yaw"}));
    Vec3 position = translation_of(nominal.at({"t"}));
    if (const std::optional<Field> correction = sensor.find({"correction_sensor_R_FLU"})) {
        sensor_to_rig = sensor_to_rig * rotation_of(correction->at({"roll-pitch-yaw"}));
    }
    if (const std::optional<Field> correction = sensor.find({"correction_rig_T"})) position += translation_of(*correction);
    const Mat3 camera_to_rig = sensor_to_rig * camera_to_flu();
    return Pose{camera_to_rig, position}.inverse();
}

bool is_camera(const DocumentNode& sensor) {
    if (const DocumentNode* protocol = sensor.find("protocol"); protocol && protocol->kind == DocumentNode::Kind::Scalar) {
        return protocol->text.starts_with("camera");
    }
    const DocumentNode* properties = sensor.find("properties");
    return properties != nullptr && properties->find("Model") != nullptr;
}

}  // namespace

bool claims_driveworks_rig(const DocumentNode& root) {
    const DocumentNode* rig = root.find("rig");
    return rig != nullptr && rig->find("sensors") != nullptr;
}

std::vector<NamedCamera> parse_driveworks_rig(std::string_view text, const std::string& source) {
    const DocumentNode root = parse_json_tree(text, source);
    const Field sensors = Field(root, "", source).at({"rig"}).at({"sensors"});
    std::vector<NamedCamera> cameras;
    for (std::size_t i = 0; i < sensors.size(); ++i) {
        const Field sensor = sensors.item(i);
        if (!is_camera(sensor.node())) continue;
        Camera camera = read_intrinsics(sensor.at({"properties"}));
        camera.pose = read_pose(sensor);
        try {
            camera.validate();
        } catch (const InvalidArgument& error) {
            sensor.fail(error.what());
        }
        const std::optional<Field> name = sensor.find({"name"});
        cameras.push_back({name ? name->text() : "camera" + std::to_string(i), {std::move(camera), std::nullopt}});
    }
    if (cameras.empty()) sensors.fail("no camera sensor (protocol camera.*) in the rig");
    return cameras;
}

std::string format_driveworks_rig(const Camera& camera, const WriteOptions& options) {
    camera.validate();
    const bool forward = camera.lens.type == LensType::FThetaForward;
    if (camera.lens.type != LensType::FTheta && !forward) {
        throw NotRepresentable("a DriveWorks rig holds an FTHETA or FTHETA_FORWARD lens (ftheta) only; this camera's is " +
                               std::string(lens_info(camera.lens.type).name));
    }
    const Intrinsics& k = camera.intrinsics;
    if (k.skew != 0.0) throw NotRepresentable("a DriveWorks rig has no skew; the camera's is " + format_number(k.skew));
    const std::vector<double>& lens = camera.lens.coefficients;
    if (lens[8] != std::numbers::pi) {
        throw NotRepresentable("a DriveWorks rig has no max_angle; the camera's is " + format_number(lens[8]) + " (not pi)");
    }
    const double f = k.fy, ratio = k.fx / k.fy;
    std::string polynomial = "0";
    for (std::size_t i = 1; i <= 5; ++i) {
        const double scale = forward ? f : 1.0 / std::pow(f, static_cast<double>(i));
        polynomial += " " + format_number(lens[2 + i] * scale);
    }
    nlohmann::ordered_json properties;
    properties["Model"] = "ftheta";
    properties["cx"] = format_number(k.cx);
    properties["cy"] = format_number(k.cy);
    properties["width"] = std::to_string(camera.size.width);
    properties["height"] = std::to_string(camera.size.height);
    properties["polynomial"] = polynomial;
    properties["polynomial-type"] = std::string(forward ? kForward : kBackward);
    properties["linear-c"] = format_number(lens[0] * ratio);
    properties["linear-d"] = format_number(lens[1] * ratio);
    properties["linear-e"] = format_number(lens[2]);
    // The camera in the rig: R S^T is the sensor's rotation, Rz(yaw) Ry(pitch) Rx(roll).
    const Pose to_rig = camera.pose.inverse();
    const Mat3 sensor_to_rig = to_rig.R * camera_to_flu().transpose();
    const double degrees = 180.0 / std::numbers::pi;
    const double pitch = -std::asin(std::clamp(sensor_to_rig(2, 0), -1.0, 1.0));
    const double roll = std::atan2(sensor_to_rig(2, 1), sensor_to_rig(2, 2));
    const double yaw = std::atan2(sensor_to_rig(1, 0), sensor_to_rig(0, 0));
    nlohmann::ordered_json sensor;
    sensor["name"] = options.camera_name;
    sensor["protocol"] = "camera.virtual";
    sensor["properties"] = properties;
    sensor["nominalSensor2Rig_FLU"] = {{"roll-pitch-yaw", {roll * degrees + 0.0, pitch * degrees + 0.0, yaw * degrees + 0.0}},
                                       {"t", {to_rig.t.x() + 0.0, to_rig.t.y() + 0.0, to_rig.t.z() + 0.0}}};
    nlohmann::ordered_json out;
    out["rig"]["sensors"] = nlohmann::ordered_json::array({sensor});
    return out.dump(2) + "\n";
}

}  // namespace libcam
