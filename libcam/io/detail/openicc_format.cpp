#include "libcam/io/detail/openicc_format.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "libcam/error.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

bool claims_openicc_camera(const DocumentNode& root) { return root.find("intrinsic_type") != nullptr; }

namespace {

// A PINHOLE's distortion as scripts that share the calibrator's layout write it (the
// calibrator itself writes none): OpenCV's list from cv2.calibrateCamera under
// "radial_distortion" or "dist_coeffs", or radial_distortion_1..4 left at 0.
Lens pinhole_distortion(const Field& k) {
    for (const std::string_view key : {"radial_distortion", "dist_coeffs"}) {
        const std::optional<Field> list = k.find({key});
        if (!list) continue;
        const std::vector<double> values = list->numbers(14);
        if (std::all_of(values.begin(), values.end(), [](double v) { return v == 0.0; })) return {};
        const std::optional<LensType> type = opencv_model_with(values.size());
        if (!type) list->fail("expected OpenCV's 4, 5, 8, 12 or 14 coefficients (k1 k2 p1 p2 k3 ...), got " + list->shown());
        return {*type, values};
    }
    for (const std::string_view key : {"radial_distortion_1", "radial_distortion_2", "radial_distortion_3", "radial_distortion_4"}) {
        const std::optional<Field> value = k.find({key});
        if (value && value->number() != 0.0) {
            value->fail("a PINHOLE with fisheye coefficients is not one of the calibrator's models: give FISHEYE as "
                        "intrinsic_type if they are its radial distortion");
        }
    }
    return {};
}

// fx and fy: the calibrator's focal_length and aspect_ratio (fy / fx), or the focal
// lengths themselves as other writers store them (focal_length_x and _y; fx and fy in
// UMI's RealSense files).
std::pair<double, double> focal_lengths(const Field& k, ImageSize size) {
    if (const std::optional<Field> fx = k.find({"focal_length_x"})) return {fx->number(), k.at({"focal_length_y"}).number()};
    if (const std::optional<Field> fx = k.find({"fx"})) return {fx->number(), k.at({"fy"}).number()};
    if (!k.find({"focal_length"})) {
        k.fail("no focal length: expected the calibrator's focal_length (with aspect_ratio), or focal_length_x and "
               "focal_length_y, or fx and fy");
    }
    const double focal = k.at({"focal_length"}).number();
    const std::optional<Field> aspect = k.find({"aspect_ratio"});
    if (!aspect) return {focal, focal};
    // One writer stores the image's width / height there: read as fy / fx it would make a
    // camera stretched by that much, silently.
    const double shape = static_cast<double>(size.width) / static_cast<double>(size.height);
    if (aspect->number() != 1.0 && std::abs(aspect->number() - shape) < 1e-9 * shape) {
        aspect->fail(aspect->shown() + " is the image's width / height, not the calibrator's fy / fx: this file's "
                     "writer stored the image's shape; give focal_length_x and focal_length_y, or 1");
    }
    return {focal, aspect->number() * focal};
}

// Theia's DivisionUndistortionCameraModel (the calibrator's DIVISION_UNDISTORTION) divides
// the pixel's offset from the principal point, in pixels, by 1 + k r_d^2 with r_d in
// pixels, after the focal length and aspect ratio: with fx = fy = f that is libcam's
// DIVISION with k f^2 (m = offset / f). With fx != fy the division is not radial in m, and
// Theia's model has no skew: both refused rather than changed.
Lens division_lens(const Field& k, const Intrinsics& intrinsics) {
    const Field distortion = k.at({"div_undist_distortion"});
    if (intrinsics.fx != intrinsics.fy) {
        const std::optional<Field> aspect = k.find({"aspect_ratio"});
        (aspect ? *aspect : k).fail("the division undistortion lens is read with an aspect ratio of 1 only (its "
                                    "division is in pixels, not radial in normalised coordinates otherwise), got " +
                                    format_number(intrinsics.fy / intrinsics.fx));
    }
    if (intrinsics.skew != 0.0) k.at({"skew"}).fail("the division undistortion lens has no skew, got " +
                                                     format_number(intrinsics.skew));
    return {LensType::Division, {distortion.number() * intrinsics.fx * intrinsics.fx}};
}

}  // namespace

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
        lens = pinhole_distortion(k);
    } else if (type.text() != "DIVISION_UNDISTORTION") {
        type.fail("must be FISHEYE, DOUBLE_SPHERE, EXTENDED_UNIFIED, DIVISION_UNDISTORTION or PINHOLE (the types the "
                  "calibrator writes with their parameters), got " + shown_value(type.text()));
    }
    Camera camera;
    camera.size = {static_cast<long>(top.at({"image_width"}).whole_number(1, kMaxImageSide)),
                   static_cast<long>(top.at({"image_height"}).whole_number(1, kMaxImageSide))};
    const auto [fx, fy] = focal_lengths(k, camera.size);
    camera.intrinsics = {fx, fy, value("principal_pt_x"), value("principal_pt_y"),
                         k.find({"skew"}) ? value("skew") : 0.0};
    if (type.text() == "DIVISION_UNDISTORTION") lens = division_lens(k, camera.intrinsics);
    camera.lens = std::move(lens);
    try {
        camera.validate();
    } catch (const InvalidArgument& error) {
        top.fail(error.what());
    }
    return {{std::string(), {std::move(camera), std::nullopt}}};
}

}  // namespace libcam
