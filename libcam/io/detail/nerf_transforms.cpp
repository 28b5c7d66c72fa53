#include "libcam/io/detail/nerf_transforms.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <Eigen/LU>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

// Every switch over LensType here names every model, with no default: a new model stops
// the build until someone decides what this file does with it.
#pragma GCC diagnostic error "-Wswitch"

namespace libcam {

namespace {

// transforms.json's pixel (0, 0) is the image's top-left corner (COLMAP's convention,
// which instant-ngp's and nerfstudio's ray code follow: pixel i's centre is at i + 0.5).
constexpr double kPixelCentre = 0.5;

// OpenGL's camera axes (x right, y up, z backwards) to OpenCV's (x right, y down, z forwards).
const Mat3 kGlToCv = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();

// A key of the frame, else of the file's top level (per-frame intrinsics override).
struct Keys {
    Field frame;
    Field top;

    std::optional<Field> find(std::string_view key) const {
        if (std::optional<Field> own = frame.find({key})) return own;
        return top.find({key});
    }
    double number_or(std::string_view key, double fallback) const {
        const std::optional<Field> field = find(key);
        return field ? field->number() : fallback;
    }
};

// ---- the image size, when the file does not record it ------------------------------------

// The size in a PNG's or a JPEG's header; nullopt for other files or a damaged header.
std::optional<ImageSize> image_header_size(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::string head(64 * 1024, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    const auto byte = [&](std::size_t i) { return static_cast<unsigned>(static_cast<unsigned char>(head[i])); };
    const auto big16 = [&](std::size_t i) { return (byte(i) << 8) | byte(i + 1); };
    const auto big32 = [&](std::size_t i) { return (static_cast<unsigned long>(big16(i)) << 16) | big16(i + 2); };
    const auto in_range = [](unsigned long w, unsigned long h) -> std::optional<ImageSize> {
        if (w < 1 || h < 1 || w > static_cast<unsigned long>(kMaxImageSide) ||
            h > static_cast<unsigned long>(kMaxImageSide)) {
            return std::nullopt;
        }
        return ImageSize{static_cast<long>(w), static_cast<long>(h)};
    };
    // PNG: the signature, then the IHDR chunk's width and height.
    if (head.size() >= 24 && head.starts_with("\x89PNG\r\n\x1a\n") && head.substr(12, 4) == "IHDR") {
        return in_range(big32(16), big32(20));
    }
    // JPEG: the first start-of-frame segment (SOF0..SOF15 but DHT, JPG and DAC) holds height, width.
    if (head.size() < 4 || byte(0) != 0xFF || byte(1) != 0xD8) return std::nullopt;
    std::size_t at = 2;
    while (at + 9 <= head.size()) {
        if (byte(at) != 0xFF) return std::nullopt;
        const unsigned marker = byte(at + 1);
        if (marker == 0xFF) {
            ++at;
            continue;
        }
        const bool start_of_frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
        if (start_of_frame) return in_range(big16(at + 7), big16(at + 5));
        at += 2 + big16(at + 2);
    }
    return std::nullopt;
}

// The image a frame names, relative to the file's folder; NeRF's synthetic scenes leave
// out the ".png".
std::optional<ImageSize> frame_image_size(const Field& frame, const std::filesystem::path& folder) {
    const std::optional<Field> file_path = folder.empty() ? std::nullopt : frame.find({"file_path"});
    if (!file_path || file_path->node().tag != "string") return std::nullopt;
    const std::filesystem::path image = folder / file_path->text();
    std::error_code error;
    for (const std::filesystem::path& candidate : {image, std::filesystem::path(image.string() + ".png")}) {
        if (std::filesystem::is_regular_file(candidate, error)) return image_header_size(candidate);
    }
    return std::nullopt;
}

// ---- intrinsics -----------------------------------------------------------------------------

ImageSize read_size(const Keys& keys, const Field& first_frame, const ReadContext& context) {
    const std::optional<Field> w = keys.find("w");
    const std::optional<Field> h = keys.find("h");
    if (w.has_value() != h.has_value()) (w ? *w : *h).fail("given without \"" + std::string(w ? "h" : "w") + "\"");
    if (w) {
        const ImageSize size{w->whole_number(1, kMaxImageSide), h->whole_number(1, kMaxImageSide)};
        if (context.options.size && !(*context.options.size == size)) {
            w->fail("the file says " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                    ", the image size given is " + std::to_string(context.options.size->width) + "x" +
                    std::to_string(context.options.size->height));
        }
        return size;
    }
    if (context.options.size) return *context.options.size;
    if (const std::optional<ImageSize> size = frame_image_size(first_frame, context.folder)) return *size;
    throw FileError(context.source + ": \"w\", \"h\": missing: the file does not record the image size, and the first "
                    "frame's image is not there to read it from; give the size (--image-size WxH)");
}

// A focal length: fl_x, else from the edge-to-edge angle.
std::optional<double> focal_length(const Keys& keys, std::string_view focal_key, std::string_view angle_key, long side) {
    if (const std::optional<Field> focal = keys.find(focal_key)) return focal->number();
    if (const std::optional<Field> angle = keys.find(angle_key)) {
        const double radians = angle->number();
        if (!(radians > 0 && radians < std::numbers::pi)) angle->fail("must be in (0, pi), got " + angle->node().text);
        return static_cast<double>(side) / (2.0 * std::tan(radians / 2.0));
    }
    return std::nullopt;
}

// nerfstudio's perspective camera under COLMAP's names: all read with one set of keys.
bool is_perspective_name(std::string_view model) {
    return model == "OPENCV" || model == "PINHOLE" || model == "SIMPLE_PINHOLE" || model == "SIMPLE_RADIAL" ||
           model == "RADIAL";
}

// The coefficients nerfstudio keeps in its order [k1, k2, k3, k4, p1, p2]: its
// distortion_params when given, else the keys.
std::map<std::string, double> perspective_coefficients(const Keys& keys) {
    static const char* const kOrder[] = {"k1", "k2", "k3", "k4", "p1", "p2"};
    std::map<std::string, double> coefficients;
    if (const std::optional<Field> params = keys.find("distortion_params")) {
        const std::vector<double> values = params->numbers(6);
        if (values.size() != 6) {
            params->fail("expected 6 numbers (k1, k2, k3, k4, p1, p2), got " + std::to_string(values.size()));
        }
        for (std::size_t i = 0; i < 6; ++i) coefficients[kOrder[i]] = values[i];
        return coefficients;
    }
    for (const char* name : kOrder) coefficients[name] = keys.number_or(name, 0.0);
    return coefficients;
}

// The key a coefficient came from (for a message): distortion_params where given, else its own.
Field coefficient_field(const Keys& keys, std::string_view name) {
    if (std::optional<Field> params = keys.find("distortion_params")) return *params;
    return *keys.find(name);
}

// nerfstudio's radial factor is 1 + k1 r^2 + k2 r^4 + k3 r^6 + k4 r^8 with OpenCV's
// tangential terms (camera_utils.py, _compute_residual_and_jacobian): BROWN_K4, or the
// simplest OpenCV model that is the lens when k4 = 0.
Lens perspective_lens(const Keys& keys) {
    const std::map<std::string, double> c = perspective_coefficients(keys);
    return simplest_equal_lens({LensType::BrownK4, {c.at("k1"), c.at("k2"), c.at("p1"), c.at("p2"), c.at("k3"), c.at("k4")}});
}

Lens fisheye_lens(const Keys& keys) {
    const std::map<std::string, double> c = perspective_coefficients(keys);
    for (const char* tangential : {"p1", "p2"}) {
        if (c.at(tangential) != 0.0) coefficient_field(keys, tangential).fail("OPENCV_FISHEYE has no tangential coefficients");
    }
    return {LensType::Fisheye, {c.at("k1"), c.at("k2"), c.at("k3"), c.at("k4")}};
}

// FISHEYE624's distortion_params are k0..k5 p0 p1 s0..s3, RAD_TAN_THIN_PRISM_FISHEYE's
// coefficients in its own order (the header says why).
Lens fisheye624_lens(const Keys& keys) {
    const std::optional<Field> params = keys.find("distortion_params");
    if (!params) keys.top.fail_at("distortion_params", "missing: FISHEYE624 needs its 12 coefficients k0..k5 p0 p1 s0..s3");
    std::vector<double> values = params->numbers(12);
    if (values.size() != 12) {
        params->fail("FISHEYE624 needs 12 numbers (k0..k5 p0 p1 s0..s3), got " + std::to_string(values.size()));
    }
    return {LensType::RadTanThinPrismFisheye, std::move(values)};
}

// instant-ngp's lenses that no libcam model is: refused by the key that selects them.
void refuse_instant_ngp_lenses(const Keys& keys) {
    const std::pair<const char*, const char*> refused[] = {
        {"equirectangular",
         "instant-ngp's equirectangular lens (the height linear in sin(latitude)) is not a lens model libcam has"},
        {"orthographic", "instant-ngp's orthographic camera is not a lens model libcam has"},
    };
    for (const auto& [key, why] : refused) {
        if (const std::optional<Field> field = keys.find(key)) field->fail(why);
    }
}

// instant-ngp's f-theta lens (its f_theta_undistortion): the angle from the axis
// alpha = p0 + p1 r + ... + p4 r^4 of the distance r in pixels from the principal point,
// the ray (sin(alpha) d / r, cos(alpha)) along that offset d. That is Blender's
// FISHEYE_LENS_POLYNOMIAL (theta = -(k0 + k1 r + ...)) with k = -p on m = d, so fx = fy = 1.
Lens ftheta_lens(const Keys& keys) {
    std::vector<double> coefficients;
    for (const char* name : {"ftheta_p0", "ftheta_p1", "ftheta_p2", "ftheta_p3", "ftheta_p4"}) {
        const std::optional<Field> p = keys.find(name);
        if (!p) keys.top.fail_at(name, "missing: instant-ngp's f-theta lens needs ftheta_p0..ftheta_p4");
        coefficients.push_back(-p->number() + 0.0);
    }
    return {LensType::LensPolynomial, std::move(coefficients)};
}

Camera read_intrinsics(const Keys& keys, ImageSize size, const ReadContext& context) {
    const std::optional<Field> model_field = keys.find("camera_model");
    const std::string model = model_field ? model_field->text() : "OPENCV";
    Camera camera;
    camera.size = size;
    // instant-ngp's latlong: the whole sphere over the image, whatever the focal lengths say.
    if (keys.find("latlong")) {
        const double w = static_cast<double>(size.width), h = static_cast<double>(size.height);
        camera.intrinsics = {w / (2.0 * std::numbers::pi), h / std::numbers::pi, w / 2.0 - kPixelCentre,
                             h / 2.0 - kPixelCentre, 0.0};
        camera.lens = {LensType::Lonlat, {}};
        return camera;
    }
    refuse_instant_ngp_lenses(keys);
    // Without cx, cy: the image centre, or NeRF's W / 2 on request.
    const double unstated_shift =
        context.options.nerf_principal_point == NerfPrincipalPoint::HalfSize ? 0.0 : kPixelCentre;
    const auto centre = [&](std::string_view key, long side) {
        const std::optional<Field> given = keys.find(key);
        return given ? given->number() - kPixelCentre : static_cast<double>(side) / 2.0 - unstated_shift;
    };
    // instant-ngp's f-theta: in pixels, whatever the focal lengths say.
    if (keys.find("ftheta_p0")) {
        camera.intrinsics = {1.0, 1.0, centre("cx", size.width), centre("cy", size.height), 0.0};
        camera.lens = ftheta_lens(keys);
        return camera;
    }
    const std::optional<double> fx = focal_length(keys, "fl_x", "camera_angle_x", size.width);
    const std::optional<double> fy_given = focal_length(keys, "fl_y", "camera_angle_y", size.height);
    if (!fx && !fy_given) keys.top.fail_at("fl_x", "missing (and no camera_angle_x)");
    const double fy = fy_given.value_or(*fx);
    camera.intrinsics = {fx.value_or(fy), fy, centre("cx", size.width), centre("cy", size.height), 0.0};
    const std::optional<Field> is_fisheye = keys.find("is_fisheye");
    const bool instant_ngp_fisheye = is_fisheye && is_fisheye->boolean() == std::optional<bool>(true);
    if (is_fisheye && !is_fisheye->boolean()) is_fisheye->fail("expected true or false, got " + is_fisheye->shown());
    if (instant_ngp_fisheye && model_field && model != "OPENCV_FISHEYE" && model != "OPENCV") {
        is_fisheye->fail("true, but camera_model is " + shown_value(model));
    }
    if (instant_ngp_fisheye || model == "OPENCV_FISHEYE") {
        camera.lens = fisheye_lens(keys);
    } else if (is_perspective_name(model)) {
        camera.lens = perspective_lens(keys);
    } else if (model == "EQUIRECTANGULAR") {
        // nerfstudio's longitude is pi (x - cx) / fl_x and its latitude pi (y - cy) / fl_y.
        camera.intrinsics.fx /= std::numbers::pi;
        camera.intrinsics.fy /= std::numbers::pi;
        camera.lens = {LensType::Lonlat, {}};
    } else if (model == "FISHEYE624") {
        camera.lens = fisheye624_lens(keys);
    } else {
        model_field->fail("must be OPENCV, PINHOLE, SIMPLE_PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV_FISHEYE, "
                          "EQUIRECTANGULAR or FISHEYE624, got " + shown_value(model));
    }
    return camera;
}

// A frame's camera-to-world matrix in OpenGL's axes, as libcam's world-to-camera pose.
Pose read_pose(const Field& matrix) {
    if (matrix.size() != 4 && matrix.size() != 3) matrix.fail("expected 4 rows of 4 numbers");
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    for (std::size_t r = 0; r < matrix.size(); ++r) {
        const Field row = matrix.item(r);
        if (row.size() != 4) row.fail("expected 4 numbers");
        for (std::size_t c = 0; c < 4; ++c) m(static_cast<long>(r), static_cast<long>(c)) = row.item(c).number();
    }
    if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9) matrix.fail("the last row must be 0 0 0 1");
    const Mat3 camera_to_world = nearest_rotation_if_rounded(m.topLeftCorner<3, 3>()) * kGlToCv;
    const Pose pose = Pose::from_centre(camera_to_world.transpose(), m.topRightCorner<3, 1>());
    try {
        pose.validate("transform_matrix");
    } catch (const InvalidArgument& error) {
        matrix.fail(std::string(error.what()) + " (a scaled or sheared matrix is not a camera pose)");
    }
    return pose;
}

// ---- the world the frames were moved to ---------------------------------------------------

// A 3x4 [A | b] whose A is a rotation (float32-printed ones to the nearest rotation).
Eigen::Matrix<double, 3, 4> read_world_transform(const Field& matrix) {
    if (matrix.size() != 3 && matrix.size() != 4) matrix.fail("expected 3 rows of 4 numbers");
    Eigen::Matrix<double, 3, 4> m;
    for (std::size_t r = 0; r < 3; ++r) {
        const Field row = matrix.item(r);
        if (row.size() != 4) row.fail("expected 4 numbers");
        for (std::size_t c = 0; c < 4; ++c) m(static_cast<long>(r), static_cast<long>(c)) = row.item(c).number();
    }
    if (matrix.size() == 4) {
        const Field last = matrix.item(3);
        if (last.size() != 4 || last.item(0).number() != 0 || last.item(1).number() != 0 || last.item(2).number() != 0 ||
            last.item(3).number() != 1) {
            last.fail("the last row must be 0 0 0 1");
        }
    }
    const Mat3 rotation = nearest_rotation_if_rounded(m.leftCols<3>());
    if (!((rotation.transpose() * rotation - Mat3::Identity()).cwiseAbs().maxCoeff() < kRoundedRotationTolerance) ||
        !(rotation.determinant() > 0)) {
        matrix.fail("its 3x3 part is not a rotation (libcam moves rigid poses only; scale goes in the scale)");
    }
    m.leftCols<3>() = rotation;
    return m;
}

double read_world_scale(const Field& scale) {
    const double value = scale.number();
    if (!(value > 0)) scale.fail("must be positive, got " + scale.node().text);
    return value;
}

NerfWorld read_world(const Field& top, const ReadContext& context) {
    NerfWorld world;
    if (const std::optional<Field> transform = top.find({"applied_transform"})) {
        world.transform = read_world_transform(*transform);
        world.has_transform = true;
    }
    if (const std::optional<Field> scale = top.find({"applied_scale"})) {
        world.scale = read_world_scale(*scale);
        world.has_scale = true;
    }
    if (world.has_transform || world.has_scale) world.source = NerfWorld::Source::AppliedTransform;
    if (context.folder.empty()) return world;
    const std::filesystem::path beside = context.folder / kDataparserTransformsName;
    if (!regular_file_exists(beside)) return world;
    if (world.source != NerfWorld::Source::None) {
        top.fail_at("applied_transform", std::string("given, and ") + kDataparserTransformsName +
                                             " is beside the file: which move the frames are in is not clear; "
                                             "move one of them away");
    }
    const std::string source = beside.string();
    const DocumentNode root = parse_json_tree(read_text_file(beside, kCameraFileLimit), source);
    const Field dataparser(root, "", source);
    world.transform = read_world_transform(dataparser.at({"transform"}));
    world.scale = read_world_scale(dataparser.at({"scale"}));
    world.has_transform = world.has_scale = true;
    world.source = NerfWorld::Source::DataparserTransforms;
    return world;
}

}  // namespace

Pose nerf_pose_to_source(const Pose& frames_pose, const NerfWorld& world) {
    const Mat3 a = world.transform.leftCols<3>();
    const Vec3 b = world.transform.col(3);
    const Vec3 centre = a.transpose() * (frames_pose.centre() / world.scale - b);
    // camera-to-world A^T R_c2w: world-to-camera R A.
    return Pose::from_centre(frames_pose.R * a, centre);
}

Pose nerf_pose_to_frames(const Pose& source_pose, const NerfWorld& world) {
    const Mat3 a = world.transform.leftCols<3>();
    const Vec3 b = world.transform.col(3);
    const Vec3 centre = world.scale * (a * source_pose.centre() + b);
    return Pose::from_centre(source_pose.R * a.transpose(), centre);
}

bool claims_nerf_transforms(const DocumentNode& root) {
    if (root.find("K") != nullptr) return false;
    return root.find("frames") != nullptr || root.find("camera_angle_x") != nullptr || root.find("fl_x") != nullptr;
}

NerfScene read_nerf_scene(std::string_view text, const ReadContext& context) {
    const DocumentNode root = parse_json_tree(text, context.source);
    const Field top(root, "", context.source);
    NerfScene scene;
    scene.world = read_world(top, context);
    const std::optional<Field> frames = top.find({"frames"});
    const std::size_t count = frames ? frames->size() : 0;
    // A file without frames is one camera, read as a frame with no keys of its own.
    DocumentNode no_keys;
    no_keys.kind = DocumentNode::Kind::Map;
    const Field first_frame = count > 0 ? frames->item(0) : Field(no_keys, "frames[0]", context.source);
    const auto read_camera = [&](const Field& frame) {
        const Keys keys{frame, top};
        Camera camera = read_intrinsics(keys, read_size(keys, first_frame, context), context);
        std::string name;
        const std::optional<Field> matrix = frame.find({"transform_matrix"});
        if (matrix) camera.pose = nerf_pose_to_source(read_pose(*matrix), scene.world);
        scene.posed.push_back(matrix.has_value());
        if (const std::optional<Field> file_path = frame.find({"file_path"})) name = file_path->text();
        try {
            camera.validate();
        } catch (const InvalidArgument& error) {
            frame.fail(error.what());
        }
        // A frame without its transform_matrix is a view listed without a pose.
        scene.cameras.push_back({std::move(name), {std::move(camera), std::nullopt}, {}, count > 0 && !matrix});
    };
    if (count == 0) read_camera(first_frame);
    for (std::size_t i = 0; i < count; ++i) read_camera(frames->item(i));
    return scene;
}

std::vector<NamedCamera> read_nerf_transforms(std::string_view text, const ReadContext& context) {
    return read_nerf_scene(text, context).cameras;
}

namespace {

// The coefficients of a lens beyond the first `kept`, which must all be 0.
void require_zero_after(const Lens& lens, std::size_t kept, std::string_view holds) {
    for (std::size_t i = kept; i < lens.coefficients.size(); ++i) {
        if (lens.coefficients[i] != 0.0) {
            throw NotRepresentable("transforms.json holds " + std::string(holds) + "; this " +
                                   std::string(lens_info(lens.type).name) + " lens's " +
                                   std::string(lens_info(lens.type).coefficients.names[i]) + " is " +
                                   format_number(lens.coefficients[i]));
        }
    }
}

// The camera's intrinsics as transforms.json's keys, in the order NeRF's tools write them.
nlohmann::ordered_json intrinsics_json(const Camera& camera) {
    if (camera.intrinsics.skew != 0.0) {
        throw NotRepresentable("transforms.json has no skew; this camera's is " + format_number(camera.intrinsics.skew));
    }
    nlohmann::ordered_json out;
    const Lens& lens = camera.lens;
    double fl_x = camera.intrinsics.fx;
    double fl_y = camera.intrinsics.fy;
    std::string model = "OPENCV";
    std::vector<std::pair<std::string, double>> coefficients;
    std::vector<double> distortion_params;
    switch (lens.type) {
        case LensType::Pinhole:
            break;
        case LensType::OpenCv4:
        case LensType::OpenCv5:
        case LensType::OpenCv8:
        case LensType::OpenCv12:
        case LensType::OpenCv14: {
            require_zero_after(lens, 5, "OpenCV's k1 k2 p1 p2 k3 only");
            const char* names[] = {"k1", "k2", "p1", "p2", "k3"};
            for (std::size_t i = 0; i < std::min<std::size_t>(5, lens.coefficients.size()); ++i) {
                coefficients.emplace_back(names[i], lens.coefficients[i]);
            }
            break;
        }
        case LensType::BrownK4: {
            const char* names[] = {"k1", "k2", "p1", "p2", "k3", "k4"};
            for (std::size_t i = 0; i < 6; ++i) coefficients.emplace_back(names[i], lens.coefficients[i]);
            break;
        }
        case LensType::Fisheye:
            model = "OPENCV_FISHEYE";
            for (std::size_t i = 0; i < 4; ++i) coefficients.emplace_back("k" + std::to_string(i + 1), lens.coefficients[i]);
            break;
        case LensType::Lonlat:
            model = "EQUIRECTANGULAR";
            fl_x *= std::numbers::pi;
            fl_y *= std::numbers::pi;
            break;
        case LensType::RadTanThinPrismFisheye:
            model = "FISHEYE624";
            distortion_params = lens.coefficients;
            break;
        // Every other model, named so that the compiler asks here about a new one.
        case LensType::Stereographic:
        case LensType::Latlon:
        case LensType::DoubleSphere:
        case LensType::Ucm:
        case LensType::Eucm:
        case LensType::Mei:
        case LensType::Fov:
        case LensType::ThinPrismFisheye:
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
        case LensType::EquidistantRadial:
        case LensType::EquisolidRadial:
        case LensType::StereographicRadial:
            detail::refuse_lens(CameraFormat::Nerf, lens.type);
    }
    out["camera_model"] = model;
    out["w"] = camera.size.width;
    out["h"] = camera.size.height;
    out["fl_x"] = fl_x;
    out["fl_y"] = fl_y;
    out["cx"] = camera.intrinsics.cx + kPixelCentre;
    out["cy"] = camera.intrinsics.cy + kPixelCentre;
    if (lens.type != LensType::Lonlat) {
        // What NeRF's own loader reads (it assumes the principal point at the centre).
        out["camera_angle_x"] = 2.0 * std::atan(static_cast<double>(camera.size.width) / (2.0 * camera.intrinsics.fx));
        out["camera_angle_y"] = 2.0 * std::atan(static_cast<double>(camera.size.height) / (2.0 * camera.intrinsics.fy));
    }
    for (const auto& [name, value] : coefficients) out[name] = value + 0.0;
    if (!distortion_params.empty()) {
        nlohmann::ordered_json params = nlohmann::ordered_json::array();
        for (double value : distortion_params) params.push_back(value + 0.0);
        out["distortion_params"] = params;
    }
    return out;
}

// A 3x4 or 4x4 matrix as rows of numbers.
template <class Matrix>
nlohmann::ordered_json matrix_json(const Matrix& m) {
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (long r = 0; r < m.rows(); ++r) {
        nlohmann::ordered_json row = nlohmann::ordered_json::array();
        for (long c = 0; c < m.cols(); ++c) row.push_back(m(r, c) + 0.0);
        rows.push_back(row);
    }
    return rows;
}

// The camera-to-world matrix with OpenGL's camera axes.
nlohmann::ordered_json transform_matrix_json(const Pose& pose) {
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    m.topLeftCorner<3, 3>() = pose.R.transpose() * kGlToCv;
    m.topRightCorner<3, 1>() = pose.centre();
    return matrix_json(m);
}

}  // namespace

std::string write_nerf_transforms(const Camera& camera, const WriteOptions& options) {
    nlohmann::ordered_json out = intrinsics_json(camera);
    nlohmann::ordered_json frame;
    frame["file_path"] = options.image_name;
    frame["transform_matrix"] = transform_matrix_json(camera.pose);
    out["frames"] = nlohmann::ordered_json::array({frame});
    return out.dump(2) + "\n";
}

std::vector<CameraFileText> write_nerf_scene(const std::vector<NamedCamera>& cameras, const NerfWorld& world,
                                             const std::string& ply_file_path, const std::vector<std::string>& mask_paths) {
    nlohmann::ordered_json out;
    if (world.source == NerfWorld::Source::AppliedTransform) {
        if (world.has_transform) out["applied_transform"] = matrix_json(world.transform);
        if (world.has_scale) out["applied_scale"] = world.scale;
    }
    if (!ply_file_path.empty()) out["ply_file_path"] = ply_file_path;
    nlohmann::ordered_json frames = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < cameras.size(); ++i) {
        const NamedCamera& named = cameras[i];
        nlohmann::ordered_json frame;
        frame["file_path"] = named.name;
        if (!mask_paths.empty()) frame["mask_path"] = mask_paths.at(i);
        frame.update(intrinsics_json(named.file.camera));
        frame["transform_matrix"] = transform_matrix_json(nerf_pose_to_frames(named.file.camera.pose, world));
        frames.push_back(std::move(frame));
    }
    // nerfstudio reads camera_model at the top level only: there, when the frames share it.
    const bool one_model = std::all_of(frames.begin(), frames.end(), [&](const nlohmann::ordered_json& frame) {
        return frame["camera_model"] == frames.front()["camera_model"];
    });
    if (!frames.empty() && one_model) {
        out["camera_model"] = frames.front()["camera_model"];
        for (nlohmann::ordered_json& frame : frames) frame.erase("camera_model");
    }
    out["frames"] = std::move(frames);
    std::vector<CameraFileText> files = {{"transforms.json", out.dump(2) + "\n"}};
    if (world.source == NerfWorld::Source::DataparserTransforms) {
        nlohmann::ordered_json dataparser;
        dataparser["transform"] = matrix_json(world.transform);
        dataparser["scale"] = world.scale;
        files.push_back({kDataparserTransformsName, dataparser.dump(4) + "\n"});
    }
    return files;
}

}  // namespace libcam
