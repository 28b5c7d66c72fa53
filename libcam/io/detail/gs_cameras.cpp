#include "libcam/io/detail/gs_cameras.hpp"

#include <string>

#include "libcam/error.hpp"
#include "libcam/geometry/pose.hpp"

namespace libcam {

namespace {

using Kind = DocumentNode::Kind;

Vec3 three_numbers(const Field& field) {
    if (field.size() != 3) field.fail("expected 3 numbers, got " + field.shown());
    return {field.item(0).number(), field.item(1).number(), field.item(2).number()};
}

// camera_to_JSON's rotation: the camera-to-world rotation's rows.
Mat3 camera_to_world(const Field& rotation) {
    if (rotation.size() != 3) rotation.fail("expected 3 rows of 3 numbers, got " + rotation.shown());
    Mat3 m;
    for (std::size_t r = 0; r < 3; ++r) m.row(static_cast<long>(r)) = three_numbers(rotation.item(r)).transpose();
    return m;
}

Pose read_pose(const Field& camera) {
    const Field rotation = camera.at({"rotation"});
    const Mat3 world_to_camera = nearest_rotation_if_rounded(camera_to_world(rotation)).transpose();
    const Pose pose = Pose::from_centre(world_to_camera, three_numbers(camera.at({"position"})));
    try {
        pose.validate("rotation");
    } catch (const InvalidArgument& error) {
        rotation.fail(std::string(error.what()) + " (a scaled or sheared matrix is not a camera's rotation)");
    }
    return pose;
}

NamedCamera read_camera(const Field& item) {
    Camera camera;
    camera.size = {static_cast<long>(item.at({"width"}).whole_number(1, kMaxImageSide)),
                   static_cast<long>(item.at({"height"}).whole_number(1, kMaxImageSide))};
    // The image centre, where 3DGS's rasterizer puts the optical axis (gs_cameras.hpp).
    camera.intrinsics = {item.at({"fx"}).number(), item.at({"fy"}).number(),
                         (static_cast<double>(camera.size.width) - 1.0) / 2.0,
                         (static_cast<double>(camera.size.height) - 1.0) / 2.0, 0.0};
    camera.lens = {LensType::Pinhole, {}};
    camera.pose = read_pose(item);
    return {item.at({"img_name"}).text(), {validated_camera(camera, item.source() + ": " + item.name()), std::nullopt}};
}

}  // namespace

bool claims_gs_cameras(const DocumentNode& root) {
    return root.kind == Kind::Sequence && !root.items.empty() && root.items[0].find("img_name") != nullptr &&
           root.items[0].find("fx") != nullptr;
}

std::vector<NamedCamera> read_gs_cameras(std::string_view text, const ReadContext& context) {
    const DocumentNode root = parse_json_tree(text, context.source);
    const Field top(root, "", context.source);
    if (root.kind != Kind::Sequence) top.fail("expected a list of cameras, got " + top.shown());
    if (top.size() == 0) top.fail("no camera");
    std::vector<NamedCamera> cameras;
    for (std::size_t i = 0; i < top.size(); ++i) cameras.push_back(read_camera(top.item(i)));
    return cameras;
}

}  // namespace libcam
