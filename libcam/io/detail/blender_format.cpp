#include "libcam/io/detail/blender_format.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "libcam/error.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

using nlohmann::ordered_json;

constexpr std::string_view kFormatName = "libcam Blender cameras";

// Blender's camera axes from OpenCV's: x stays, y and z turn round.
const Mat3 kFlipYZ = Vec3(1.0, -1.0, -1.0).asDiagonal();

struct PanoramaName {
    BlenderCameraType type;
    std::string_view name;
};
constexpr std::array<PanoramaName, 4> kPanoramaTypes = {{
    {BlenderCameraType::FisheyeEquidistant, "FISHEYE_EQUIDISTANT"},
    {BlenderCameraType::FisheyeEquisolid, "FISHEYE_EQUISOLID"},
    {BlenderCameraType::FisheyeLensPolynomial, "FISHEYE_LENS_POLYNOMIAL"},
    {BlenderCameraType::Equirectangular, "EQUIRECTANGULAR"},
}};

std::string_view panorama_name(BlenderCameraType type) {
    for (const PanoramaName& entry : kPanoramaTypes) {
        if (entry.type == type) return entry.name;
    }
    return "";
}

constexpr std::array<std::pair<SensorFit, std::string_view>, 3> kSensorFits = {{
    {SensorFit::Auto, "AUTO"}, {SensorFit::Horizontal, "HORIZONTAL"}, {SensorFit::Vertical, "VERTICAL"}}};

// A number the file may leave out (Blender's default then).
double number_or(const Field& camera, std::string_view key, double fallback) {
    const std::optional<Field> value = camera.find({key});
    return value ? value->number() : fallback;
}

BlenderCameraType camera_type(const Field& camera) {
    const Field type = camera.at({"type"});
    const std::string text = type.text();
    if (text == "PERSP") return BlenderCameraType::Perspective;
    if (text == "ORTHO") type.fail("an orthographic camera has no ray through a centre; libcam models central cameras only");
    if (text != "PANO") type.fail("expected PERSP or PANO, got " + shown_value(text));
    const Field panorama = camera.at({"panorama_type"});
    const std::string name = panorama.text();
    for (const PanoramaName& entry : kPanoramaTypes) {
        if (entry.name == name) return entry.type;
    }
    panorama.fail("libcam reads FISHEYE_EQUIDISTANT, FISHEYE_EQUISOLID, FISHEYE_LENS_POLYNOMIAL and EQUIRECTANGULAR, "
                  "got " + shown_value(name));
}

SensorFit sensor_fit(const Field& camera) {
    const std::optional<Field> field = camera.find({"sensor_fit"});
    if (!field) return SensorFit::Auto;
    const std::string text = field->text();
    for (const auto& [fit, name] : kSensorFits) {
        if (name == text) return fit;
    }
    field->fail("expected AUTO, HORIZONTAL or VERTICAL, got " + shown_value(text));
}

// The pose of a camera object's world matrix: its columns' lengths are the object's scale,
// which Blender takes out before rendering; a mirrored or sheared matrix is refused.
Pose pose_of_world_matrix(const Field& field) {
    if (field.size() != 4) field.fail("expected 4 rows, got " + std::to_string(field.size()));
    Eigen::Matrix4d m;
    for (std::size_t r = 0; r < 4; ++r) {
        const Field row = field.item(r);
        if (row.size() != 4) row.fail("expected 4 numbers, got " + std::to_string(row.size()));
        for (std::size_t c = 0; c < 4; ++c) m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = row.item(c).number();
    }
    if (m.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) field.fail("the last row must be 0 0 0 1");
    Mat3 axes = m.topLeftCorner<3, 3>();
    for (int c = 0; c < 3; ++c) {
        const double scale = axes.col(c).norm();
        if (!(scale > 0) || !std::isfinite(scale)) field.fail("column " + std::to_string(c) + " has no direction");
        axes.col(c) /= scale;
    }
    // Blender's camera axes in the world: B = R^T diag(1, -1, -1).
    Pose pose;
    pose.R = nearest_rotation_if_rounded(kFlipYZ * axes.transpose());
    pose.t = -pose.R * m.topRightCorner<3, 1>();
    try {
        pose.validate("matrix_world");
    } catch (const InvalidArgument& error) {
        field.fail(error.what());
    }
    return pose;
}

BlenderCamera blender_settings(const Field& camera) {
    BlenderCamera b;
    b.type = camera_type(camera);
    const std::optional<Field> percentage_field = camera.find({"resolution_percentage"});
    const long long percentage = percentage_field ? percentage_field->integer(1, 32767) : 100;
    // Blender renders resolution x percentage / 100 pixels, rounded down.
    const auto rendered = [&](std::string_view key) {
        const long long side = camera.at({key}).integer(1, 65536) * percentage / 100;
        if (side < 1) percentage_field->fail("leaves no pixel of " + std::string(key));
        return static_cast<int>(side);
    };
    b.size = {rendered("resolution_x"), rendered("resolution_y")};
    b.pixel_aspect_x = number_or(camera, "pixel_aspect_x", 1.0);
    b.pixel_aspect_y = number_or(camera, "pixel_aspect_y", 1.0);
    if (b.type == BlenderCameraType::Perspective) b.lens_mm = camera.at({"lens"}).number();
    b.sensor_width_mm = number_or(camera, "sensor_width", b.sensor_width_mm);
    b.sensor_height_mm = number_or(camera, "sensor_height", b.sensor_height_mm);
    b.sensor_fit = sensor_fit(camera);
    b.shift_x = number_or(camera, "shift_x", 0.0);
    b.shift_y = number_or(camera, "shift_y", 0.0);
    switch (b.type) {
        case BlenderCameraType::Perspective: break;
        case BlenderCameraType::FisheyeEquisolid:
            b.fisheye_lens_mm = camera.at({"fisheye_lens"}).number();
            [[fallthrough]];
        case BlenderCameraType::FisheyeEquidistant: b.fisheye_fov = camera.at({"fisheye_fov"}).number(); break;
        case BlenderCameraType::FisheyeLensPolynomial:
            for (std::size_t i = 0; i < b.fisheye_polynomial.size(); ++i) {
                b.fisheye_polynomial[i] = camera.at({"fisheye_polynomial_k" + std::to_string(i)}).number();
            }
            break;
        case BlenderCameraType::Equirectangular:
            b.latitude_min = camera.at({"latitude_min"}).number();
            b.latitude_max = camera.at({"latitude_max"}).number();
            b.longitude_min = camera.at({"longitude_min"}).number();
            b.longitude_max = camera.at({"longitude_max"}).number();
            break;
    }
    return b;
}

NamedCamera read_camera(const Field& entry) {
    Camera camera;
    try {
        camera = camera_from_blender(blender_settings(entry));
    } catch (const InvalidArgument& error) {
        entry.fail(error.what());
    }
    if (const std::optional<Field> matrix = entry.find({"matrix_world"})) camera.pose = pose_of_world_matrix(*matrix);
    const std::optional<Field> name_field = entry.find({"name"});
    std::string name = name_field ? name_field->text() : std::string();
    if (const std::optional<Field> frame = entry.find({"frame"})) {
        name += "@" + std::to_string(frame->whole_number(-1048574, 1048574));
    }
    return {std::move(name), {std::move(camera), std::nullopt}};
}

// The settings of one camera, in bpy's names.
ordered_json settings_of(const Camera& camera, const WriteOptions& options) {
    BlenderCamera b;
    try {
        b = blender_from_camera(camera);
    } catch (const InvalidArgument& error) {
        throw NotRepresentable(std::string("Blender: ") + error.what() +
                               " (libcam render-plan plans a render Blender can draw and the warp to this camera)");
    }
    ordered_json out;
    out["name"] = options.camera_name;
    out["resolution_x"] = b.size.width;
    out["resolution_y"] = b.size.height;
    out["resolution_percentage"] = 100;
    out["pixel_aspect_x"] = b.pixel_aspect_x;
    out["pixel_aspect_y"] = b.pixel_aspect_y;
    const bool perspective = b.type == BlenderCameraType::Perspective;
    out["type"] = perspective ? "PERSP" : "PANO";
    if (!perspective) out["panorama_type"] = panorama_name(b.type);
    if (perspective) out["lens"] = b.lens_mm;
    out["sensor_width"] = b.sensor_width_mm;
    out["sensor_height"] = b.sensor_height_mm;
    for (const auto& [fit, name] : kSensorFits) {
        if (fit == b.sensor_fit) out["sensor_fit"] = name;
    }
    out["shift_x"] = b.shift_x + 0.0;
    out["shift_y"] = b.shift_y + 0.0;
    out["clip_start"] = options.gl_near;
    out["clip_end"] = options.gl_far;
    switch (b.type) {
        case BlenderCameraType::Perspective: break;
        case BlenderCameraType::FisheyeEquisolid: out["fisheye_lens"] = b.fisheye_lens_mm; [[fallthrough]];
        case BlenderCameraType::FisheyeEquidistant: out["fisheye_fov"] = b.fisheye_fov; break;
        case BlenderCameraType::FisheyeLensPolynomial:
            out["fisheye_fov"] = b.fisheye_fov;
            for (std::size_t i = 0; i < b.fisheye_polynomial.size(); ++i) {
                out["fisheye_polynomial_k" + std::to_string(i)] = b.fisheye_polynomial[i];
            }
            break;
        case BlenderCameraType::Equirectangular:
            out["latitude_min"] = b.latitude_min;
            out["latitude_max"] = b.latitude_max;
            out["longitude_min"] = b.longitude_min;
            out["longitude_max"] = b.longitude_max;
            break;
    }
    // [R^T diag(1, -1, -1) | -R^T t]: Blender's camera axes and the eye in the world.
    const Mat3 axes = camera.pose.R.transpose() * kFlipYZ;
    const Vec3 eye = -camera.pose.R.transpose() * camera.pose.t;
    ordered_json rows = ordered_json::array();
    for (int r = 0; r < 3; ++r) rows.push_back({axes(r, 0) + 0.0, axes(r, 1) + 0.0, axes(r, 2) + 0.0, eye(r) + 0.0});
    rows.push_back({0.0, 0.0, 0.0, 1.0});
    out["matrix_world"] = rows;
    return out;
}

ordered_json document_of(const Camera& camera, const WriteOptions& options) {
    if (!(options.gl_near > 0 && options.gl_far > options.gl_near)) {
        throw InvalidArgument("clip range: Blender wants 0 < clip_start < clip_end, got " + format_number(options.gl_near) +
                              " and " + format_number(options.gl_far));
    }
    ordered_json out;
    out["format"] = kFormatName;
    out["cameras"] = ordered_json::array({settings_of(camera, options)});
    return out;
}

// What the script does with the JSON: the same settings on the scene's camera.
constexpr std::string_view kScriptBody = R"py(

PANORAMA_SETTINGS = (
    "panorama_type", "fisheye_fov", "fisheye_lens", "fisheye_polynomial_k0", "fisheye_polynomial_k1",
    "fisheye_polynomial_k2", "fisheye_polynomial_k3", "fisheye_polynomial_k4", "latitude_min", "latitude_max",
    "longitude_min", "longitude_max",
)


def set_camera(scene, settings):
    """Sets the scene's camera (a new one if it has none) and render size to `settings`."""
    camera = scene.camera
    if camera is None:
        camera = bpy.data.objects.new(settings["name"], bpy.data.cameras.new(settings["name"]))
        scene.collection.objects.link(camera)
        scene.camera = camera
    render = scene.render
    render.resolution_x = settings["resolution_x"]
    render.resolution_y = settings["resolution_y"]
    render.resolution_percentage = settings["resolution_percentage"]
    render.pixel_aspect_x = settings["pixel_aspect_x"]
    render.pixel_aspect_y = settings["pixel_aspect_y"]
    data = camera.data
    data.type = settings["type"]
    for key in ("lens", "sensor_width", "sensor_height", "sensor_fit", "shift_x", "shift_y", "clip_start", "clip_end"):
        if key in settings:
            setattr(data, key, settings[key])
    if settings["type"] == "PANO":
        render.engine = "CYCLES"  # the only engine that draws panoramic cameras
        # Blender 3.x keeps the panorama settings on data.cycles, later versions on data.
        panorama = data if hasattr(data, "panorama_type") else data.cycles
        for key in PANORAMA_SETTINGS:
            if key in settings:
                setattr(panorama, key, settings[key])
    camera.matrix_world = Matrix(settings["matrix_world"])


set_camera(bpy.context.scene, CAMERA)
)py";

}  // namespace

bool claims_blender_cameras(const DocumentNode& root) {
    const DocumentNode* format = root.find("format");
    return format != nullptr && format->kind == DocumentNode::Kind::Scalar && format->text == kFormatName;
}

std::vector<NamedCamera> parse_blender_cameras(std::string_view text, const std::string& source) {
    const DocumentNode root = parse_json_tree(text, source);
    const Field top(root, "", source);
    if (!claims_blender_cameras(root)) top.fail("expected \"format\": \"" + std::string(kFormatName) + "\"");
    const Field list = top.at({"cameras"});
    if (list.size() == 0) list.fail("no camera");
    std::vector<NamedCamera> cameras;
    for (std::size_t i = 0; i < list.size(); ++i) {
        NamedCamera named = read_camera(list.item(i));
        try {
            named.file.camera.validate();
        } catch (const InvalidArgument& error) {
            list.item(i).fail(error.what());
        }
        cameras.push_back(std::move(named));
    }
    return cameras;
}

std::string format_blender_json(const Camera& camera, const WriteOptions& options) {
    return document_of(camera, options).dump(2) + "\n";
}

std::string format_blender_script(const Camera& camera, const WriteOptions& options) {
    const ordered_json document = document_of(camera, options);
    const ordered_json& settings = document["cameras"][0];
    std::string script;
    script += "# Sets a Blender scene's camera to a " + std::string(lens_info(camera.lens.type).name) + " camera of " +
              std::to_string(camera.size.width) + "x" + std::to_string(camera.size.height) +
              " pixels, written by libcam.\n";
    script += "# Run: blender -b scene.blend -P this_file.py (Blender 3.4 or newer; add -o and -f to render)\n";
    script += "import json\n\nimport bpy\nfrom mathutils import Matrix\n\n";
    script += "CAMERA = json.loads(r\"\"\"\n" + settings.dump(2) + "\n\"\"\")\n";
    script += kScriptBody;
    return script;
}

}  // namespace libcam
