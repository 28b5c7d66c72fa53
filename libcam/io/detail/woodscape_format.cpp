#include "libcam/io/detail/woodscape_format.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "libcam/error.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

constexpr std::string_view kModelName = "radial_poly";
constexpr long long kPolyOrder = 4;
constexpr const char* kCoefficientKeys[] = {"k1", "k2", "k3", "k4"};

// n numbers of a JSON array.
std::vector<double> numbers(const Field& field, std::size_t count) {
    if (field.size() != count) field.fail("expected " + std::to_string(count) + " numbers, got " + std::to_string(field.size()));
    std::vector<double> values;
    for (std::size_t i = 0; i < count; ++i) values.push_back(field.item(i).number());
    return values;
}

// The intrinsics' model and order, where the file gives them, must be the one WoodScape has.
void check_model(const Field& intrinsic) {
    if (const std::optional<Field> model = intrinsic.find({"model"}); model && model->text() != kModelName) {
        model->fail("must be " + std::string(kModelName) + " (WoodScape's only model), got " +
                    shown_value(model->text()));
    }
    if (const std::optional<Field> order = intrinsic.find({"poly_order"})) {
        if (order->whole_number(0, 1000) != kPolyOrder) order->fail("must be 4 (k1..k4), got " + order->shown());
    }
}

Camera read_intrinsic(const Field& intrinsic) {
    check_model(intrinsic);
    Camera camera;
    camera.size = {static_cast<long>(intrinsic.at({"width"}).whole_number(1, kMaxImageSide)),
                   static_cast<long>(intrinsic.at({"height"}).whole_number(1, kMaxImageSide))};
    const Field aspect = intrinsic.at({"aspect_ratio"});
    const double aspect_ratio = aspect.number();
    if (!(aspect_ratio > 0.0)) aspect.fail("must be positive, got " + format_number(aspect_ratio));
    const double width = static_cast<double>(camera.size.width), height = static_cast<double>(camera.size.height);
    camera.intrinsics = {1.0, aspect_ratio, width / 2 + intrinsic.at({"cx_offset"}).number() - 0.5,
                         height / 2 + intrinsic.at({"cy_offset"}).number() - 0.5, 0.0};
    camera.lens.type = LensType::ThetaPolynomial;
    for (const char* key : kCoefficientKeys) camera.lens.coefficients.push_back(intrinsic.at({key}).number());
    return camera;
}

// Camera to vehicle in the file (scipy's quaternion, scalar last); vehicle to camera in libcam.
Pose read_extrinsic(const Field& extrinsic) {
    const Field quaternion = extrinsic.at({"quaternion"});
    const std::vector<double> q = numbers(quaternion, 4);
    const std::vector<double> t = numbers(extrinsic.at({"translation"}), 3);
    Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
    if (!(std::abs(rotation.norm() - 1.0) <= 1e-6)) {
        quaternion.fail("the quaternion's norm is " + format_number(rotation.norm()) + ", not 1");
    }
    rotation.normalize();
    return Pose{rotation.toRotationMatrix(), Vec3(t[0], t[1], t[2])}.inverse();
}

}  // namespace

bool claims_woodscape_camera(const DocumentNode& root) {
    const DocumentNode* intrinsic = root.find("intrinsic");
    return intrinsic != nullptr && intrinsic->find("cx_offset") != nullptr;
}

std::vector<NamedCamera> parse_woodscape_camera(std::string_view text, const std::string& source) {
    const DocumentNode root = parse_json_tree(text, source);
    const Field top(root, "", source);
    Camera camera = read_intrinsic(top.at({"intrinsic"}));
    if (const std::optional<Field> extrinsic = top.find({"extrinsic"})) camera.pose = read_extrinsic(*extrinsic);
    try {
        camera.validate();
    } catch (const InvalidArgument& error) {
        top.fail(error.what());
    }
    const std::optional<Field> name = top.find({"name"});
    return {{name ? name->text() : std::string(), {std::move(camera), std::nullopt}}};
}

std::string format_woodscape_camera(const Camera& camera, const WriteOptions&) {
    camera.validate();
    if (camera.lens.type != LensType::ThetaPolynomial) {
        throw NotRepresentable("WoodScape's calibration holds a THETA_POLYNOMIAL lens (radial_poly) only; this camera's is " +
                               std::string(lens_info(camera.lens.type).name));
    }
    const Intrinsics& k = camera.intrinsics;
    if (k.skew != 0.0) throw NotRepresentable("WoodScape's calibration has no skew; the camera's is " + format_number(k.skew));
    const double width = static_cast<double>(camera.size.width), height = static_cast<double>(camera.size.height);
    nlohmann::ordered_json intrinsic;
    intrinsic["aspect_ratio"] = k.fy / k.fx;
    intrinsic["cx_offset"] = k.cx + 0.5 - width / 2;
    intrinsic["cy_offset"] = k.cy + 0.5 - height / 2;
    intrinsic["height"] = height;
    for (std::size_t i = 0; i < 4; ++i) intrinsic[kCoefficientKeys[i]] = camera.lens.coefficients[i] * k.fx;
    intrinsic["model"] = kModelName;
    intrinsic["poly_order"] = kPolyOrder;
    intrinsic["width"] = width;
    // Camera to vehicle: the inverse of libcam's pose.
    const Pose to_vehicle = camera.pose.inverse();
    const Eigen::Quaterniond q(to_vehicle.R);
    nlohmann::ordered_json extrinsic;
    extrinsic["quaternion"] = {q.x() + 0.0, q.y() + 0.0, q.z() + 0.0, q.w() + 0.0};
    extrinsic["translation"] = {to_vehicle.t.x() + 0.0, to_vehicle.t.y() + 0.0, to_vehicle.t.z() + 0.0};
    nlohmann::ordered_json out;
    out["extrinsic"] = extrinsic;
    out["intrinsic"] = intrinsic;
    return out.dump(2) + "\n";
}

}  // namespace libcam
