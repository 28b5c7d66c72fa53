#include "libcam/io/detail/openicc_format.hpp"

#include "libcam/error.hpp"
#include "libcam/io/detail/document.hpp"

namespace libcam {

bool claims_openicc_camera(const DocumentNode& root) { return root.find("intrinsic_type") != nullptr; }

std::vector<NamedCamera> parse_openicc_camera(std::string_view text, const std::string& source) {
    const DocumentNode root = parse_json_tree(text, source);
    const Field top(root, "", source);
    const Field type = top.at({"intrinsic_type"});
    const Field k = top.at({"intrinsics"});
    const auto value = [&](std::string_view key) { return k.at({key}).number(); };
    // The calibrator's writer puts each type's own parameters next to f, a, cx, cy and
    // skew; for any other type it writes none, so those files hold no lens to read.
    Lens lens;
    if (type.text() == "FISHEYE") {
        lens = {LensType::Fisheye, {value("radial_distortion_1"), value("radial_distortion_2"),
                                    value("radial_distortion_3"), value("radial_distortion_4")}};
    } else if (type.text() == "DOUBLE_SPHERE") {
        lens = {LensType::DoubleSphere, {value("xi"), value("alpha")}};
    } else if (type.text() == "EXTENDED_UNIFIED") {
        lens = {LensType::Eucm, {value("alpha"), value("beta")}};
    } else if (type.text() == "PINHOLE") {
        lens = {LensType::Pinhole, {}};  // the calibrator writes no distortion for it
    } else if (type.text() == "DIVISION_UNDISTORTION") {
        type.fail("libcam has no model for the division undistortion lens (FISHEYE, DOUBLE_SPHERE, EXTENDED_UNIFIED "
                  "and PINHOLE are read)");
    } else {
        type.fail("must be FISHEYE, DOUBLE_SPHERE, EXTENDED_UNIFIED or PINHOLE (the types the calibrator writes with "
                  "their parameters), got '" + type.text() + "'");
    }
    const double focal = value("focal_length");
    const double aspect = k.find({"aspect_ratio"}) ? value("aspect_ratio") : 1.0;
    Camera camera;
    camera.size = {static_cast<long>(top.at({"image_width"}).integer(1, kMaxImageSide)),
                   static_cast<long>(top.at({"image_height"}).integer(1, kMaxImageSide))};
    camera.intrinsics = {focal, aspect * focal, value("principal_pt_x"), value("principal_pt_y"),
                         k.find({"skew"}) ? value("skew") : 0.0};
    camera.lens = std::move(lens);
    try {
        camera.validate();
    } catch (const InvalidArgument& error) {
        top.fail(error.what());
    }
    return {{std::string(), {std::move(camera), std::nullopt}}};
}

}  // namespace libcam
