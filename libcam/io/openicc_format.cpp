#include "libcam/io/openicc_format.hpp"

#include <nlohmann/json.hpp>

#include "libcam/error.hpp"
#include "libcam/io/json_field.hpp"

namespace libcam {

bool is_openicc_camera(std::string_view text) {
    const nlohmann::json root = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
    return root.is_object() && root.contains("intrinsic_type");
}

std::vector<NamedCamera> parse_openicc_camera(std::string_view text, const std::string& source) {
    const nlohmann::json root = parse_json_document(text, source);
    const JsonField top{root, "", source};
    if (!root.is_object()) top.fail("expected an object");
    const JsonField type = top.at("intrinsic_type");
    if (type.text() != "FISHEYE") type.fail("libcam reads the FISHEYE type (cv::fisheye's model), not '" + type.text() + "'");
    const JsonField k = top.at("intrinsics");
    const double focal = k.at("focal_length").number();
    const double aspect = k.has("aspect_ratio") ? k.at("aspect_ratio").number() : 1.0;
    Camera camera;
    camera.size = {top.at("image_width").integer(1, kMaxImageSide), top.at("image_height").integer(1, kMaxImageSide)};
    camera.intrinsics = {focal, aspect * focal, k.at("principal_pt_x").number(), k.at("principal_pt_y").number(),
                         k.has("skew") ? k.at("skew").number() : 0.0};
    camera.lens = {LensType::Fisheye,
                   {k.at("radial_distortion_1").number(), k.at("radial_distortion_2").number(),
                    k.at("radial_distortion_3").number(), k.at("radial_distortion_4").number()}};
    try {
        camera.validate();
    } catch (const InvalidArgument& error) {
        top.fail(error.what());
    }
    return {{std::string(), {std::move(camera), std::nullopt}}};
}

}  // namespace libcam
