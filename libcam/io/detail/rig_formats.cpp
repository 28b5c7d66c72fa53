#include "libcam/io/detail/rig_formats.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/kalibr_rig.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/io/detail/ocamcalib_format.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

// A camera a reader has put together, validated; an error names the file and the camera.
NamedCamera checked(std::string name, Camera camera, const std::string& where) {
    return {std::move(name), {validated_camera(std::move(camera), where), std::nullopt}};
}

ImageSize size_of(const Field& width, const Field& height) {
    return {static_cast<int>(width.integer(1, kMaxImageSide)), static_cast<int>(height.integer(1, kMaxImageSide))};
}

// A resolution written as [width, height] (Kalibr, EuRoC, basalt).
ImageSize size_of(const Field& resolution) {
    if (resolution.node().kind != DocumentNode::Kind::Sequence || resolution.size() != 2) {
        resolution.fail("expected [width, height]");
    }
    return size_of(resolution.item(0), resolution.item(1));
}

// ---- Kalibr ----------------------------------------------------------------------------

// A 4x4 homogeneous transform [R t; 0 0 0 1] as a pose (X_to = R X_from + t).
Pose read_transform(const Field& field) {
    const DocumentNode& node = field.node();
    if (node.kind != DocumentNode::Kind::Sequence || node.items.size() != 4) field.fail("expected 4 rows of 4 numbers");
    Eigen::Matrix4d m;
    for (int r = 0; r < 4; ++r) {
        const Field row = field.item(static_cast<std::size_t>(r));
        const std::vector<double> values = row.numbers(4);
        if (values.size() != 4) row.fail("expected 4 numbers, got " + std::to_string(values.size()));
        for (int c = 0; c < 4; ++c) m(r, c) = values[static_cast<std::size_t>(c)];
    }
    if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9) {
        field.fail("the last row must be 0 0 0 1");
    }
    Pose pose{m.topLeftCorner<3, 3>(), m.topRightCorner<3, 1>()};
    pose.R = nearest_rotation_if_rounded(pose.R);
    try {
        pose.validate(field.name().c_str());
    } catch (const InvalidArgument& error) {
        field.fail(error.what());
    }
    return pose;
}

// Kalibr's distortion_model as the table's kalibr names spell it (camera-distortion).
std::string kalibr_distortion_short(const Field& field) {
    const std::string model = field.text();
    if (model == "radtan" || model == "fov" || model == "none") return model;
    if (model == "equidistant" || model == "equi") return "equi";
    field.fail("must be radtan, equidistant, fov or none, got " + shown_value(model));
}

// How many of Kalibr's intrinsics lead K for each camera_model: omni's xi, ds's xi and
// alpha, eucm's alpha and beta (Kalibr's order, which is libcam's coefficient order).
int leading_coefficients(const std::string& camera_model) {
    if (camera_model == "pinhole") return 0;
    if (camera_model == "omni") return 1;
    return 2;  // ds, eucm
}

NamedCamera read_kalibr_camera(const std::string& name, const Field& cam, const std::optional<Pose>& previous,
                               const std::string& source) {
    const Field camera_model = cam.at({"camera_model"});
    const std::string projection = camera_model.text();
    if (projection != "pinhole" && projection != "omni" && projection != "ds" && projection != "eucm") {
        camera_model.fail("must be pinhole, omni, ds or eucm, got " + shown_value(projection));
    }
    const Field distortion_model = cam.at({"distortion_model"});
    const std::string kalibr_name = projection + "-" + kalibr_distortion_short(distortion_model);
    const auto row = std::find_if(lens_models().begin(), lens_models().end(),
                                  [&](const LensInfo& info) { return info.kalibr == kalibr_name; });
    if (row == lens_models().end()) {
        distortion_model.fail("libcam has no model for Kalibr's " + projection + " camera with " +
                              distortion_model.text() + " distortion");
    }
    const int leading = leading_coefficients(projection);
    const Field intrinsics_field = cam.at({"intrinsics"});
    const std::vector<double> intrinsics = intrinsics_field.numbers(8);
    if (static_cast<int>(intrinsics.size()) != leading + 4) {
        intrinsics_field.fail("a " + projection + " camera has " + std::to_string(leading + 4) + " numbers, got " +
                              std::to_string(intrinsics.size()));
    }
    std::vector<double> coefficients(intrinsics.begin(), intrinsics.begin() + leading);
    if (const std::optional<Field> distortion = cam.find({"distortion_coeffs"})) {
        const std::vector<double> values = distortion->numbers(kMaxLensCoefficients);
        coefficients.insert(coefficients.end(), values.begin(), values.end());
    }
    const ImageSize size = size_of(cam.at({"resolution"}));

    Camera camera;
    camera.size = size;
    const std::size_t k = static_cast<std::size_t>(leading);
    camera.intrinsics = {intrinsics[k], intrinsics[k + 1], intrinsics[k + 2], intrinsics[k + 3], 0.0};
    camera.lens = {row->type, std::move(coefficients)};
    if (const std::optional<Field> to_camera = cam.find({"T_cam_imu"})) {
        camera.pose = read_transform(*to_camera);
    } else if (const std::optional<Field> to_imu = cam.find({"T_imu_cam"})) {
        camera.pose = read_transform(*to_imu).inverse();
    } else if (const std::optional<Field> chain = cam.find({"T_cn_cnm1"})) {
        if (!previous) chain->fail("the first camera has no camera before it");
        camera.pose = read_transform(*chain).after(*previous);
    } else if (previous) {
        cam.fail("no T_cam_imu, T_imu_cam or T_cn_cnm1: where this camera is in the rig is not known");
    }
    const std::string where = source + ": line " + std::to_string(cam.node().line) + ": \"" + name + "\"";
    return checked(name, std::move(camera), where);
}

bool is_kalibr_camera_key(std::string_view key) {
    return key.size() > 3 && key.starts_with("cam") &&
           std::all_of(key.begin() + 3, key.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// ---- camodocal ---------------------------------------------------------------------------

// camodocal's models as data: each model_type, the lens model it is, the keys of K in
// projection_parameters, and where each of the lens's coefficients is (section, key).
struct CamodocalKey {
    std::string_view section;
    std::string_view key;
};

struct CamodocalModel {
    std::string_view model_type;
    LensType lens;
    std::array<std::string_view, 4> k;  // fx, fy, cx, cy
    std::array<CamodocalKey, 5> coefficients;
    int coefficient_count;
};

constexpr CamodocalModel kCamodocalModels[] = {
    {"PINHOLE", LensType::OpenCv4, {"fx", "fy", "cx", "cy"},
     {{{"distortion_parameters", "k1"}, {"distortion_parameters", "k2"}, {"distortion_parameters", "p1"},
       {"distortion_parameters", "p2"}}},
     4},
    // Mei's model is cv::omnidir's: gamma1 gamma2 u0 v0 are K.
    {"MEI", LensType::Mei, {"gamma1", "gamma2", "u0", "v0"},
     {{{"mirror_parameters", "xi"}, {"distortion_parameters", "k1"}, {"distortion_parameters", "k2"},
       {"distortion_parameters", "p1"}, {"distortion_parameters", "p2"}}},
     5},
    // camodocal's k2..k5 are theta's coefficients of theta^3..theta^9 (OpenCV fisheye's k1..k4).
    {"KANNALA_BRANDT", LensType::Fisheye, {"mu", "mv", "u0", "v0"},
     {{{"projection_parameters", "k2"}, {"projection_parameters", "k3"}, {"projection_parameters", "k4"},
       {"projection_parameters", "k5"}}},
     4},
};

// Every lens model's coefficient count matches the table's.
static_assert([] {
    for (const CamodocalModel& model : kCamodocalModels) {
        if (lens_info(model.lens).num_coefficients != model.coefficient_count) return false;
    }
    return true;
}());

// camodocal's OCAMCamera (SCARAMUZZA, written "scaramuzza" in VINS's files): Scaramuzza's
// model on (x, y) = (column, row), as its spaceToPlane has it: poly_parameters p0..p4
// with z = -poly (p0 < 0), affine_parameters ac ad ae acting on (x, y) about (cx, cy).
// Its inv_poly_parameters approximate the projection; libcam projects exactly.
Camera camodocal_scaramuzza(const Field& file) {
    const Field poly = file.at({"poly_parameters"});
    std::vector<double> forward;
    for (int i = 0; i < 5; ++i) forward.push_back(-poly.at({"p" + std::to_string(i)}).number());
    const Field affine = file.at({"affine_parameters"});
    const auto value = [&](std::string_view key) { return affine.at({key}).number(); };
    return ocamcalib_camera_on_xy(forward, value("ac"), value("ad"), value("ae"), Vec2(value("cx"), value("cy")),
                                  size_of(file.at({"image_width"}), file.at({"image_height"})),
                                  poly.source() + ": \"" + poly.name() + "\"");
}

NamedCamera read_camodocal(const Field& file, const std::string& source) {
    const Field model_type = file.at({"model_type"});
    const std::string model_name = model_type.text();
    const std::string name = file.find({"camera_name"}) ? file.at({"camera_name"}).text() : std::string();
    if (model_name == "SCARAMUZZA" || model_name == "scaramuzza") return checked(name, camodocal_scaramuzza(file), source);
    const auto found = std::find_if(std::begin(kCamodocalModels), std::end(kCamodocalModels),
                                    [&](const CamodocalModel& model) { return model.model_type == model_name; });
    if (found == std::end(kCamodocalModels)) {
        model_type.fail("must be PINHOLE, MEI, KANNALA_BRANDT or SCARAMUZZA (libcam has no model for " +
                        shown_value(model_name) + ")");
    }
    Camera camera;
    camera.size = size_of(file.at({"image_width"}), file.at({"image_height"}));
    const Field projection = file.at({"projection_parameters"});
    const auto k = [&](std::size_t i) { return projection.at({found->k[i]}).number(); };
    camera.intrinsics = {k(0), k(1), k(2), k(3), 0.0};
    camera.lens.type = found->lens;
    for (int i = 0; i < found->coefficient_count; ++i) {
        const CamodocalKey& where = found->coefficients[static_cast<std::size_t>(i)];
        camera.lens.coefficients.push_back(file.at({where.section}).at({where.key}).number());
    }
    return checked(name, std::move(camera), source);
}

// ---- basalt -------------------------------------------------------------------------------

// basalt's T_imu_cam: camera to IMU, px py pz and the unit quaternion qx qy qz qw.
Pose basalt_pose(const Field& transform) {
    const auto value = [&](std::string_view key) { return transform.at({key}).number(); };
    const Eigen::Vector3d position(value("px"), value("py"), value("pz"));
    Eigen::Quaterniond q(value("qw"), value("qx"), value("qy"), value("qz"));
    if (std::abs(q.norm() - 1.0) > 1e-6) transform.fail("the quaternion's norm is " + std::to_string(q.norm()) + ", not 1");
    q.normalize();
    return Pose{q.toRotationMatrix(), position}.inverse();
}

// basalt's name for one of a model's coefficients: the lens table's, but for FOV's omega,
// which basalt calls w.
std::string basalt_coefficient_name(std::string_view name) { return name == "omega" ? "w" : std::string(name); }

// basalt's camera types that are not a lens-table name, in words for messages.
constexpr std::string_view kBasaltOwnTypes = "ucm";

std::string basalt_type_names() {
    std::string names;
    for (const LensInfo& info : lens_models()) {
        if (!info.basalt.empty()) names += std::string(info.basalt) + ", ";
    }
    return names + std::string(kBasaltOwnTypes);
}

Camera basalt_camera(const Field& entry) {
    const Field camera_type = entry.at({"camera_type"});
    const std::string type = camera_type.text();
    const Field k = entry.at({"intrinsics"});
    const auto value = [&](std::string_view key) { return k.at({key}).number(); };
    Camera camera;
    camera.intrinsics = {value("fx"), value("fy"), value("cx"), value("cy"), 0.0};
    if (type == "ucm") {
        // basalt's m = (x, y) / (alpha d + (1 - alpha) z) = UCM's (x, y) / (z + xi d) times
        // 1 / (1 - alpha), with xi = alpha / (1 - alpha).
        const double alpha = value("alpha");
        if (!(alpha >= 0 && alpha < 1)) k.at({"alpha"}).fail("must be in [0, 1), got " + std::to_string(alpha));
        const double scale = 1.0 / (1.0 - alpha);
        camera.intrinsics.fx *= scale;
        camera.intrinsics.fy *= scale;
        camera.lens = {LensType::Ucm, {alpha / (1.0 - alpha)}};
        return camera;
    }
    // Every other type is the lens table's basalt name, its coefficients under the
    // table's names.
    const auto models = lens_models();
    const auto found = std::find_if(models.begin(), models.end(), [&](const LensInfo& info) { return info.basalt == type; });
    if (found == models.end()) camera_type.fail("must be " + basalt_type_names() + ", got " + shown_value(type));
    camera.lens.type = found->type;
    for (const std::string_view name : found->coefficients.view()) {
        camera.lens.coefficients.push_back(value(basalt_coefficient_name(name)));
    }
    return camera;
}

// ---- EuRoC (ASL) sensor.yaml ----------------------------------------------------------

NamedCamera read_euroc_sensor(const Field& file, const std::string& source) {
    const Field sensor_type = file.at({"sensor_type"});
    if (sensor_type.text() != "camera") sensor_type.fail("must be camera, got " + shown_value(sensor_type.text()));
    const Field camera_model = file.at({"camera_model"});
    if (camera_model.text() != "pinhole") camera_model.fail("must be pinhole, got " + shown_value(camera_model.text()));
    const Field distortion_model = file.at({"distortion_model"});
    const std::string distortion = distortion_model.text();
    LensType type = LensType::OpenCv4;
    if (distortion == "equidistant") {
        type = LensType::Fisheye;
    } else if (distortion != "radial-tangential" && distortion != "radtan") {
        distortion_model.fail("must be radial-tangential or equidistant, got " + shown_value(distortion));
    }
    const Field intrinsics = file.at({"intrinsics"});
    const std::vector<double> k = intrinsics.numbers(4);
    if (k.size() != 4) intrinsics.fail("expected fu, fv, cu, cv");
    Camera camera;
    camera.size = size_of(file.at({"resolution"}));
    camera.intrinsics = {k[0], k[1], k[2], k[3], 0.0};
    const Field coefficients = file.at({"distortion_coefficients"});
    camera.lens = {type, coefficients.numbers(4)};
    if (camera.lens.coefficients.size() != 4) coefficients.fail("expected 4 coefficients");
    // T_BS: the sensor (camera) in the body (IMU) frame, a 4x4 given as rows, cols, data.
    const Field transform = file.at({"T_BS"});
    const Field data = transform.at({"data"});
    const std::vector<double> values = data.numbers(16);
    if (values.size() != 16) data.fail("expected 16 numbers, got " + std::to_string(values.size()));
    Eigen::Matrix4d m;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m(r, c) = values[static_cast<std::size_t>(4 * r + c)];
    if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-9) data.fail("the last row must be 0 0 0 1");
    Pose in_body{nearest_rotation_if_rounded(m.topLeftCorner<3, 3>()), m.topRightCorner<3, 1>()};
    try {
        in_body.validate("T_BS");
    } catch (const InvalidArgument& error) {
        data.fail(error.what());
    }
    camera.pose = in_body.inverse();
    const std::string name = file.find({"comment"}) ? file.at({"comment"}).text() : std::string();
    return checked(name, std::move(camera), source);
}

// ---- writing Kalibr -------------------------------------------------------------------------

std::string yaml_list(const std::vector<double>& values) {
    std::string out = "[";
    for (std::size_t i = 0; i < values.size(); ++i) out += (i == 0 ? "" : ", ") + yaml_number(values[i]);
    return out + "]";
}

// ---- writing basalt -------------------------------------------------------------------------

// basalt's camera_type and intrinsics for a camera: the table's basalt name with K and the
// coefficients under basalt's names; OPENCV4 and OPENCV5 as pinhole-radtan8 with the
// higher terms 0; UCM in basalt's parametrisation (alpha = xi / (1 + xi), focal lengths
// divided by 1 + xi: the inverse of basalt_camera's conversion).
nlohmann::ordered_json basalt_intrinsics(const Camera& camera) {
    const Intrinsics& k = camera.intrinsics;
    const std::vector<double>& c = camera.lens.coefficients;
    nlohmann::ordered_json values;
    values["fx"] = k.fx;
    values["fy"] = k.fy;
    values["cx"] = k.cx;
    values["cy"] = k.cy;
    std::string type(lens_info(camera.lens.type).basalt);
    if (camera.lens.type == LensType::Ucm) {
        const double xi = c[0];
        values["fx"] = k.fx / (1.0 + xi);
        values["fy"] = k.fy / (1.0 + xi);
        values["alpha"] = xi / (1.0 + xi);
        type = "ucm";
    } else if (lens_contains(LensType::OpenCv8, camera.lens.type) && camera.lens.type != LensType::Pinhole) {
        std::vector<double> radtan8 = c;
        radtan8.resize(8, 0.0);
        type = lens_info(LensType::OpenCv8).basalt;
        const std::span<const std::string_view> names = lens_info(LensType::OpenCv8).coefficients.view();
        for (std::size_t i = 0; i < names.size(); ++i) values[basalt_coefficient_name(names[i])] = radtan8[i];
    } else {
        const std::span<const std::string_view> names = lens_info(camera.lens.type).coefficients.view();
        for (std::size_t i = 0; i < names.size(); ++i) values[basalt_coefficient_name(names[i])] = c[i];
    }
    nlohmann::ordered_json entry;
    entry["camera_type"] = type;
    entry["intrinsics"] = values;
    return entry;
}

nlohmann::ordered_json triple(double value) { return {value, value, value}; }

}  // namespace

std::string format_basalt_calibration(const Camera& camera, const WriteOptions&) {
    if (camera.intrinsics.skew != 0.0) {
        throw NotRepresentable("basalt's cameras have no skew; this camera's is " + yaml_number(camera.intrinsics.skew));
    }
    const LensType type = camera.lens.type;
    if (lens_info(type).basalt.empty() && type != LensType::Ucm && !lens_contains(LensType::OpenCv8, type)) {
        throw NotRepresentable("basalt has no model for a " + std::string(lens_info(type).name) +
                               " lens (it holds pinhole, kb4 (FISHEYE), ds, eucm, ucm, fov and pinhole-radtan8 "
                               "(OPENCV8) cameras)");
    }
    // T_imu_cam: the camera in the IMU frame (the world), the inverse of the pose; the
    // quaternion with qw >= 0, one of the two that mean the rotation.
    const Pose in_imu = camera.pose.inverse();
    Eigen::Quaterniond q(in_imu.R);
    if (q.w() < 0) q.coeffs() = -q.coeffs();
    nlohmann::ordered_json transform;
    transform["px"] = in_imu.t.x() + 0.0;
    transform["py"] = in_imu.t.y() + 0.0;
    transform["pz"] = in_imu.t.z() + 0.0;
    transform["qx"] = q.x() + 0.0;
    transform["qy"] = q.y() + 0.0;
    transform["qz"] = q.z() + 0.0;
    transform["qw"] = q.w() + 0.0;
    nlohmann::ordered_json calibration;
    // One-element lists built explicitly: a braced list of one JSON value is the value
    // itself to one compiler (clang) and a list of it to another (GCC).
    const auto list_of = [](nlohmann::ordered_json element) {
        nlohmann::ordered_json list = nlohmann::ordered_json::array();
        list.push_back(std::move(element));
        return list;
    };
    calibration["T_imu_cam"] = list_of(transform);
    calibration["intrinsics"] = list_of(basalt_intrinsics(camera));
    calibration["resolution"] = list_of(nlohmann::ordered_json::array({camera.size.width, camera.size.height}));
    // basalt's loader requires its IMU fields too. These are the values basalt's own
    // Calibration starts with (basalt/calibration/calibration.hpp), which its camera-only
    // calibration writes as they are: no bias, 200 Hz, its default noise densities.
    calibration["calib_accel_bias"] = std::vector<double>(9, 0.0);
    calibration["calib_gyro_bias"] = std::vector<double>(12, 0.0);
    calibration["imu_update_rate"] = 200.0;
    calibration["accel_noise_std"] = triple(0.016);
    calibration["gyro_noise_std"] = triple(0.000282);
    calibration["accel_bias_std"] = triple(0.001);
    calibration["gyro_bias_std"] = triple(0.0001);
    calibration["cam_time_offset_ns"] = 0;
    calibration["vignette"] = nlohmann::ordered_json::array();
    nlohmann::ordered_json out;
    out["value0"] = calibration;
    return out.dump(4) + "\n";
}

namespace {

// One camera of a camchain, `name` ("cam0"), with `transform` under `transform_key`
// (T_cam_imu, T_cn_cnm1) where it has one.
std::string kalibr_camera(const Camera& camera, const std::string& name, const char* transform_key,
                          const std::optional<Pose>& transform) {
    if (camera.intrinsics.skew != 0.0) {
        throw NotRepresentable("Kalibr's cameras have no skew; this camera's is " + yaml_number(camera.intrinsics.skew));
    }
    const LensInfo& info = lens_info(camera.lens.type);
    if (info.kalibr.empty()) {
        throw NotRepresentable("Kalibr has no model for a " + std::string(info.name) +
                               " lens (it holds pinhole, omni, ds and eucm cameras with radtan, equidistant, fov or no "
                               "distortion)");
    }
    const std::string_view kalibr = info.kalibr;
    const std::string projection(kalibr.substr(0, kalibr.find('-')));
    const std::string short_distortion(kalibr.substr(kalibr.find('-') + 1));
    const std::string distortion = short_distortion == "equi" ? "equidistant" : short_distortion;
    const std::size_t leading = static_cast<std::size_t>(leading_coefficients(projection));
    const std::vector<double>& c = camera.lens.coefficients;
    std::vector<double> intrinsics(c.begin(), c.begin() + static_cast<long>(leading));
    const Intrinsics& k = camera.intrinsics;
    intrinsics.insert(intrinsics.end(), {k.fx, k.fy, k.cx, k.cy});
    const std::vector<double> distortion_coeffs(c.begin() + static_cast<long>(leading), c.end());
    std::string out = name + ":\n";
    if (transform) {
        out += "  " + std::string(transform_key) + ":\n";
        for (int r = 0; r < 4; ++r) {
            const std::vector<double> row = r < 3 ? std::vector<double>{transform->R(r, 0), transform->R(r, 1),
                                                                         transform->R(r, 2), transform->t(r)}
                                                  : std::vector<double>{0.0, 0.0, 0.0, 1.0};
            out += "  - " + yaml_list(row) + "\n";
        }
    }
    out += "  camera_model: " + projection + "\n";
    out += "  distortion_coeffs: " + yaml_list(distortion_coeffs) + "\n";
    out += "  distortion_model: " + distortion + "\n";
    out += "  intrinsics: " + yaml_list(intrinsics) + "\n";
    out += "  resolution: [" + std::to_string(camera.size.width) + ", " + std::to_string(camera.size.height) + "]\n";
    return out;
}

}  // namespace

std::string format_kalibr_camchain(const Camera& camera, const WriteOptions&) {
    return kalibr_camera(camera, "cam0", "T_cam_imu", camera.pose);
}

std::string format_kalibr_rig(const std::vector<Camera>& cameras) {
    std::string out;
    for (std::size_t i = 0; i < cameras.size(); ++i) {
        // Each camera from the one before it: X_cn = T_cn_cnm1 X_cnm1.
        const std::optional<Pose> from_previous =
            i == 0 ? std::nullopt : std::optional<Pose>(cameras[i].pose.after(cameras[i - 1].pose.inverse()));
        out += kalibr_camera(cameras[i], "cam" + std::to_string(i), "T_cn_cnm1", from_previous);
    }
    return out;
}

std::vector<NamedCamera> parse_euroc_sensor(std::string_view text, const std::string& source) {
    const DocumentNode tree = parse_yaml_document(text, source);
    if (tree.kind != DocumentNode::Kind::Map) throw FileError(source + ": expected EuRoC's keys (sensor_type, T_BS, ...)");
    return {read_euroc_sensor(Field(tree, "", source), source)};
}

std::vector<NamedCamera> parse_kalibr_camchain(std::string_view text, const std::string& source) {
    const DocumentNode tree = parse_yaml_document(text, source);
    if (tree.kind != DocumentNode::Kind::Map) throw FileError(source + ": expected Kalibr's keys cam0, cam1, ...");
    const Field file(tree, "", source);
    std::vector<NamedCamera> cameras;
    for (const std::string& key : tree.keys) {
        if (!is_kalibr_camera_key(key)) continue;
        const std::optional<Pose> previous =
            cameras.empty() ? std::nullopt : std::optional<Pose>(cameras.back().file.camera.pose);
        cameras.push_back(read_kalibr_camera(key, file.at({key}), previous, source));
    }
    if (cameras.empty()) throw FileError(source + ": no camera: expected Kalibr's keys cam0, cam1, ...");
    return cameras;
}

std::vector<NamedCamera> parse_camodocal(std::string_view text, const std::string& source) {
    const DocumentNode tree = parse_yaml_document(text, source);
    if (tree.kind != DocumentNode::Kind::Map) throw FileError(source + ": expected camodocal's keys (model_type, ...)");
    return {read_camodocal(Field(tree, "", source), source)};
}

std::vector<NamedCamera> parse_basalt_calibration(std::string_view text, const std::string& source) {
    const DocumentNode root = parse_json_tree(text, source);
    if (!claims_basalt_calibration(root)) throw FileError(source + ": expected basalt's \"value0\" object");
    const Field calibration = Field(root, "", source).at({"value0"});
    const Field intrinsics = calibration.at({"intrinsics"});
    const Field resolution = calibration.at({"resolution"});
    const std::optional<Field> poses = calibration.find({"T_imu_cam"});
    const std::size_t count = intrinsics.size();
    if (count == 0) intrinsics.fail("no camera");
    if (resolution.size() != count) resolution.fail("expected one [width, height] per camera (" + std::to_string(count) + ")");
    std::vector<NamedCamera> cameras;
    for (std::size_t i = 0; i < count; ++i) {
        Camera camera = basalt_camera(intrinsics.item(i));
        camera.size = size_of(resolution.item(i));
        if (poses) camera.pose = basalt_pose(poses->item(i));
        const std::string name = "cam" + std::to_string(i);
        cameras.push_back(checked(name, std::move(camera), source + ": \"value0.intrinsics[" + std::to_string(i) + "]\""));
    }
    return cameras;
}

bool claims_camodocal(const DocumentNode& root) { return root.find("model_type") != nullptr; }

bool claims_euroc_sensor(const DocumentNode& root) {
    return root.find("sensor_type") != nullptr && root.find("T_BS") != nullptr;
}

bool claims_kalibr_camchain(const DocumentNode& root) {
    for (std::size_t i = 0; i < root.keys.size(); ++i) {
        if (is_kalibr_camera_key(root.keys[i]) && root.items[i].find("camera_model") != nullptr) return true;
    }
    return false;
}

bool claims_basalt_calibration(const DocumentNode& root) { return root.find("value0") != nullptr; }

}  // namespace libcam
