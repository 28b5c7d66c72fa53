#include "libcam/io/detail/open3d_format.hpp"

#include <nlohmann/json.hpp>
#include <optional>

#include "libcam/error.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

// n numbers of a JSON array.
std::vector<double> numbers(const Field& field, std::size_t count) {
    if (field.size() != count) field.fail("expected " + std::to_string(count) + " numbers, got " + std::to_string(field.size()));
    std::vector<double> values;
    for (std::size_t i = 0; i < count; ++i) values.push_back(field.item(i).number());
    return values;
}

Camera read_intrinsic(const Field& intrinsic) {
    Camera camera;
    camera.size = {static_cast<long>(intrinsic.at({"width"}).integer(1, kMaxImageSide)),
                   static_cast<long>(intrinsic.at({"height"}).integer(1, kMaxImageSide))};
    const Field matrix = intrinsic.at({"intrinsic_matrix"});
    const std::vector<double> k = numbers(matrix, 9);  // column-major
    if (k[1] != 0.0 || k[2] != 0.0 || k[5] != 0.0 || k[8] != 1.0) {
        matrix.fail("expected Eigen's column-major [fx, 0, 0, s, fy, 0, cx, cy, 1]");
    }
    camera.intrinsics = {k[0], k[4], k[6], k[7], k[3]};
    return camera;
}

Pose read_extrinsic(const Field& field) {
    const std::vector<double> e = numbers(field, 16);  // column-major
    const auto at = [&](int r, int c) { return e[static_cast<std::size_t>(4 * c + r)]; };
    if (at(3, 0) != 0.0 || at(3, 1) != 0.0 || at(3, 2) != 0.0 || at(3, 3) != 1.0) field.fail("the last row must be 0 0 0 1");
    Pose pose;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) pose.R(r, c) = at(r, c);
        pose.t(r) = at(r, 3);
    }
    pose.R = nearest_rotation_if_rounded(pose.R);
    try {
        pose.validate("extrinsic");
    } catch (const InvalidArgument& error) {
        field.fail(error.what());
    }
    return pose;
}

Camera read_parameters(const Field& parameters) {
    Camera camera = read_intrinsic(parameters.at({"intrinsic"}));
    camera.pose = read_extrinsic(parameters.at({"extrinsic"}));
    return camera;
}

NamedCamera checked(std::string name, Camera camera, const Field& where) {
    try {
        camera.validate();
    } catch (const InvalidArgument& error) {
        where.fail(error.what());
    }
    return {std::move(name), {std::move(camera), std::nullopt}};
}

}  // namespace

bool claims_open3d_camera(const DocumentNode& root) {
    if (root.find("intrinsic_matrix") != nullptr) return true;
    const DocumentNode* name = root.find("class_name");
    return name != nullptr && name->kind == DocumentNode::Kind::Scalar &&
           (name->text == "PinholeCameraParameters" || name->text == "PinholeCameraTrajectory" ||
            name->text == "PinholeCameraIntrinsic");
}

std::vector<NamedCamera> parse_open3d_camera(std::string_view text, const std::string& source) {
    const DocumentNode root = parse_json_tree(text, source);
    const Field top(root, "", source);
    const std::optional<Field> class_name = top.find({"class_name"});
    const std::string kind = class_name ? class_name->text() : std::string();
    if (kind == "PinholeCameraTrajectory") {
        const Field list = top.at({"parameters"});
        if (list.size() == 0) list.fail("no camera");
        std::vector<NamedCamera> cameras;
        for (std::size_t i = 0; i < list.size(); ++i) cameras.push_back(checked("", read_parameters(list.item(i)), list.item(i)));
        return cameras;
    }
    if (kind == "PinholeCameraParameters") return {checked("", read_parameters(top), top)};
    if (!kind.empty() && kind != "PinholeCameraIntrinsic") {
        class_name->fail("must be PinholeCameraIntrinsic, PinholeCameraParameters or PinholeCameraTrajectory, "
                                  "got " + shown_value(kind));
    }
    return {checked("", read_intrinsic(top), top)};
}

std::string format_open3d_camera(const Camera& camera, const WriteOptions&) {
    if (camera.lens.type != LensType::Pinhole) {
        throw NotRepresentable("Open3D's cameras have no distortion; this camera's lens is " +
                               std::string(lens_info(camera.lens.type).name));
    }
    const Intrinsics& k = camera.intrinsics;
    nlohmann::ordered_json intrinsic;
    intrinsic["height"] = camera.size.height;
    intrinsic["intrinsic_matrix"] = {k.fx, 0.0, 0.0, k.skew + 0.0, k.fy, 0.0, k.cx, k.cy, 1.0};
    intrinsic["width"] = camera.size.width;
    nlohmann::ordered_json extrinsic = nlohmann::ordered_json::array();
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            extrinsic.push_back(r == 3 ? (c == 3 ? 1.0 : 0.0) : (c == 3 ? camera.pose.t(r) : camera.pose.R(r, c)) + 0.0);
        }
    }
    nlohmann::ordered_json out;
    out["class_name"] = "PinholeCameraParameters";
    out["extrinsic"] = extrinsic;
    out["intrinsic"] = intrinsic;
    out["version_major"] = 1;
    out["version_minor"] = 0;
    return out.dump(1, '\t') + "\n";
}

}  // namespace libcam
