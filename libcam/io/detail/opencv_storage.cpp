#include "libcam/io/detail/opencv_storage.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

// Every switch over LensType here names every model, with no default: a new model stops
// the build until someone decides what this file does with it.
#pragma GCC diagnostic error "-Wswitch"

namespace libcam {

namespace {

// The most elements a camera matrix or coefficient vector can have. A file that
// declares more (rows: 2000000000) is refused before anything is allocated for it.
constexpr long long kMaxMatrixElements = 64;

// ---- writing ----

// A double as OpenCV writes one: every digit that matters, and a '.' when the shortest
// form would read as an integer ("500." rather than "500").
std::string opencv_number(double value) {
    std::string text = format_number(value);
    if (text.find_first_of(".eEn") == std::string::npos) text += '.';
    return text;
}

using Matrix = OpenCvMatrix;


std::string xml_matrix(const std::string& key, const Matrix& m) {
    std::string out = "<" + key + " type_id=\"opencv-matrix\">\n  <rows>" + std::to_string(m.rows) + "</rows>\n  <cols>" +
                      std::to_string(m.cols) + "</cols>\n  <dt>d</dt>\n  <data>\n   ";
    for (double value : m.values) out += " " + opencv_number(value);
    return out + "</data></" + key + ">\n";
}

Matrix column(const std::vector<double>& values) {
    return {static_cast<long long>(values.size()), 1, values};
}

// ---- reading ----

// The element type of an opencv-matrix: dt is a type letter (d, f, i, u, s, w, c, h),
// after a channel count for a matrix of several channels ("2f": CV_32FC2, the image
// points of the calibration sample), which XML writes in quotes.
std::pair<int, char> element_type(const Field& dt, int max_channels) {
    std::string type = dt.text();
    if (type.size() >= 2 && type.front() == '"' && type.back() == '"') type = type.substr(1, type.size() - 2);
    static constexpr std::string_view kDepths = "dfiuswch";
    int channels = 1;
    if (type.size() == 2 && type[0] >= '1' && type[0] <= '4') channels = type[0] - '0';
    const bool known = !type.empty() && type.size() <= 2 && kDepths.find(type.back()) != std::string_view::npos &&
                       (type.size() == 1 || channels > 1 || type[0] == '1');
    if (!known || channels > max_channels) {
        dt.fail(max_channels == 1
                    ? "expected a one-channel element type (d, f, i, u, s, w, c or h), got " + shown_value(type)
                    : "expected an element type of at most " + std::to_string(max_channels) +
                          " channels (d, f, ..., or \"2f\"), got " + shown_value(type));
    }
    return {channels, type.back()};
}

}  // namespace

// A matrix as cv::FileStorage writes it (a map tagged opencv-matrix with rows, cols,
// dt and data), or a plain list of numbers, which OpenCV reads as a column.
OpenCvMatrix read_opencv_matrix(const Field& field, long long max_elements, int max_channels) {
    const DocumentNode& node = field.node();
    if (node.kind != DocumentNode::Kind::Map) {
        std::vector<double> values = field.numbers(static_cast<std::size_t>(max_elements));
        return column(values);
    }
    if (!node.tag.empty() && node.tag != "opencv-matrix") {
        field.fail("expected an opencv-matrix, got the type " + shown_value(node.tag));
    }
    Matrix m;
    m.rows = field.at({"rows"}).integer(0, max_elements);
    m.cols = field.at({"cols"}).integer(0, max_elements);
    // ROS's camera_info writes rows, cols and data without OpenCV's tag and dt.
    if (const std::optional<Field> dt = node.tag.empty() ? field.find({"dt"}) : std::optional<Field>(field.at({"dt"}))) {
        std::tie(m.channels, m.depth) = element_type(*dt, max_channels);
    }
    const long long count = m.rows * m.cols * m.channels;
    if (count > max_elements) {
        field.fail("declares " + std::to_string(m.rows) + "x" + std::to_string(m.cols) +
                   (m.channels > 1 ? "x" + std::to_string(m.channels) + " channels" : "") + " (at most " +
                   std::to_string(max_elements) + " elements)");
    }
    if (count == 0) return m;
    const Field data = field.at({"data"});
    m.values = data.numbers(static_cast<std::size_t>(max_elements));
    if (static_cast<long long>(m.values.size()) != count) {
        data.fail("holds " + std::to_string(m.values.size()) + " numbers, but rows x cols" +
                  (m.channels > 1 ? " x channels" : "") + " is " + std::to_string(m.rows) + "x" +
                  std::to_string(m.cols) + (m.channels > 1 ? "x" + std::to_string(m.channels) : ""));
    }
    return m;
}

namespace {

Matrix read_matrix(const Field& field) { return read_opencv_matrix(field, kMaxMatrixElements, 1); }

Vec3 read_vector3(const Field& field) {
    const Matrix m = read_matrix(field);
    if (m.values.size() != 3) field.fail("expected 3 numbers, got " + std::to_string(m.values.size()));
    return {m.values[0], m.values[1], m.values[2]};
}

// A rotation, snapped to the nearest rotation when the file printed it rounded. How
// strict the shape is differs by layout: ROS's camera_info and ORB-SLAM2's R must be
// 3x3 (`exactly_3x3`); the stereo layout's R has always been taken as any 9 numbers in
// row order (a plain list among them).
Mat3 read_rotation(const Field& field, bool exactly_3x3) {
    const Matrix m = read_matrix(field);
    if (exactly_3x3 && (m.rows != 3 || m.cols != 3)) field.fail("expected a 3x3 matrix");
    if (m.values.size() != 9) field.fail("expected a 3x3 rotation, got " + std::to_string(m.values.size()) + " numbers");
    Mat3 rotation;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) rotation(r, c) = m.values[static_cast<std::size_t>(3 * r + c)];
    return nearest_rotation_if_rounded(rotation);
}

// One camera of a rectified stereo pair, as ROS's camera_info and ORB-SLAM2's stereo
// settings describe it: the raw camera, R turning its frame into the rectified one, and
// P = K' [I | t] projecting points of the pair's rectified frame (the first camera's),
// which is the world: t = (Tx / fx', Ty / fy', 0). Returns the rectified camera P
// describes and places the raw camera: the rectified camera's centre, turned by R^T.
Camera place_in_rectified_pair(Camera& raw, const Mat3& R, const Field& projection) {
    const Matrix P = read_matrix(projection);
    if (P.rows != 3 || P.cols != 4) projection.fail("expected a 3x4 matrix");
    const auto p = [&](int r, int c) { return P.values[static_cast<std::size_t>(4 * r + c)]; };
    if (p(1, 0) != 0.0 || p(2, 0) != 0.0 || p(2, 1) != 0.0 || p(2, 2) != 1.0 || p(2, 3) != 0.0) {
        projection.fail("expected [fx' s cx' Tx; 0 fy' cy' Ty; 0 0 1 0]");
    }
    Camera rectified;
    rectified.size = raw.size;
    rectified.intrinsics = {p(0, 0), p(1, 1), p(0, 2), p(1, 2), p(0, 1)};
    if (!(rectified.intrinsics.fx > 0) || !(rectified.intrinsics.fy > 0)) projection.fail("fx' and fy' must be > 0");
    rectified.pose.t = Vec3((p(0, 3) - rectified.intrinsics.skew * p(1, 3) / rectified.intrinsics.fy) / rectified.intrinsics.fx,
                            p(1, 3) / rectified.intrinsics.fy, 0.0);
    raw.pose = Pose{R.transpose(), Vec3::Zero()}.after(rectified.pose);
    return rectified;
}

Intrinsics read_camera_matrix(const Field& field) {
    const Matrix m = read_matrix(field);
    if (m.rows != 3 || m.cols != 3) {
        field.fail("expected a 3x3 matrix, got " + std::to_string(m.rows) + "x" + std::to_string(m.cols));
    }
    Mat3 k;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) k(r, c) = m.values[static_cast<std::size_t>(3 * r + c)];
    try {
        return Intrinsics::from_K(k, field.name().c_str());
    } catch (const InvalidArgument& error) {
        throw FileError(field.source() + ": " + error.what());
    }
}

// Which function of OpenCV's the coefficients are for. OpenCV's calibration sample
// writes `fisheye_model: 1` for cv::fisheye; ROS-style files name the model in
// `distortion_model`. Without either they are cv::projectPoints' coefficients.
enum class CoefficientFamily { RadialTangential, Fisheye };

CoefficientFamily coefficient_family(const Field& file) {
    std::optional<CoefficientFamily> family;
    if (const std::optional<Field> flag = file.find({"fisheye_model"})) {
        family = flag->integer(0, 1) == 1 ? CoefficientFamily::Fisheye : CoefficientFamily::RadialTangential;
    }
    if (const std::optional<Field> model = file.find({"distortion_model"})) {
        std::string name = model->text();
        std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
        static constexpr std::string_view kRadialTangential[] = {"plumb_bob", "rational_polynomial", "radtan",
                                                                 "radial-tangential", "pinhole"};
        static constexpr std::string_view kFisheye[] = {"fisheye", "equidistant", "kannala_brandt"};
        const auto named = [&](const auto& names) { return std::find(std::begin(names), std::end(names), name) != std::end(names); };
        const std::optional<CoefficientFamily> by_name =
            named(kRadialTangential) ? std::optional(CoefficientFamily::RadialTangential)
            : named(kFisheye)        ? std::optional(CoefficientFamily::Fisheye)
                                     : std::nullopt;
        if (!by_name) {
            model->fail(shown_value(model->text()) +
                        " is not a model this reader knows (plumb_bob, rational_polynomial, equidistant or fisheye)");
        }
        if (family && *family != *by_name) model->fail("disagrees with \"fisheye_model\"");
        family = by_name;
    }
    return family.value_or(CoefficientFamily::RadialTangential);
}

Lens read_distortion(const Field& field, CoefficientFamily family) {
    const Matrix m = read_matrix(field);
    if (m.rows != 1 && m.cols != 1 && !m.values.empty()) {
        field.fail("expected a vector, got a " + std::to_string(m.rows) + "x" + std::to_string(m.cols) + " matrix");
    }
    Lens lens;
    if (family == CoefficientFamily::Fisheye) {
        // cv::fisheye's k1..k4. All zero is the equidistant lens r = f theta, not PINHOLE.
        if (m.values.size() != 4) field.fail("expected cv::fisheye's 4 coefficients, got " + std::to_string(m.values.size()));
        lens.type = LensType::Fisheye;
        lens.coefficients = m.values;
        return lens;
    }
    if (std::all_of(m.values.begin(), m.values.end(), [](double v) { return v == 0.0; })) return lens;  // PINHOLE
    const std::optional<LensType> type = opencv_model_with(m.values.size());
    if (!type) field.fail("expected 4, 5, 8, 12 or 14 coefficients, got " + std::to_string(m.values.size()));
    lens.type = *type;
    lens.coefficients = m.values;
    return lens;
}

DocumentNode parse_tree(std::string_view text, const std::string& source) {
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos) throw FileError(source + ": file is empty");
    DocumentNode tree = text[first] == '<' ? parse_opencv_xml_document(text, source) : parse_yaml_document(text, source);
    if (tree.kind != DocumentNode::Kind::Map) {
        throw FileError(source + ": expected OpenCV's keys (image_width, image_height, camera_matrix, ...), found " +
                        (tree.kind == DocumentNode::Kind::Null ? "none" : "a single value or a list"));
    }
    return tree;
}

}  // namespace

std::string yaml_matrix(const std::string& key, const OpenCvMatrix& m) {
    const std::string dt = m.channels == 1 ? "d" : "\"" + std::to_string(m.channels) + "d\"";
    std::string out = key + ": !!opencv-matrix\n   rows: " + std::to_string(m.rows) + "\n   cols: " +
                      std::to_string(m.cols) + "\n   dt: " + dt + "\n   data: [";
    for (std::size_t i = 0; i < m.values.size(); ++i) out += (i == 0 ? " " : ", ") + opencv_number(m.values[i]);
    return out + " ]\n";
}

std::string format_opencv_storage(const Camera& camera, OpenCvStorage storage) {
    camera.validate();
    const OpenCvFunction function = lens_info(camera.lens.type).opencv;
    if (function != OpenCvFunction::ProjectPoints && function != OpenCvFunction::Fisheye) {
        throw NotRepresentable("lens: OpenCV's camera file holds OpenCV's radial-tangential models and cv::fisheye's, "
                               "not " + std::string(lens_info(camera.lens.type).name));
    }
    const Intrinsics& k = camera.intrinsics;
    const Matrix K{3, 3, {k.fx, k.skew, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0}};
    const Matrix dist = column(camera.lens.type == LensType::Pinhole ? std::vector<double>(5, 0.0) : camera.lens.coefficients);
    const Vec3 rvec = camera.pose.rvec();
    const Matrix r = column({rvec.x(), rvec.y(), rvec.z()});
    const Matrix t = column({camera.pose.t.x(), camera.pose.t.y(), camera.pose.t.z()});
    const std::string width = std::to_string(camera.size.width), height = std::to_string(camera.size.height);
    // cv::fisheye's four coefficients would read as OPENCV4 without a word saying whose
    // they are: the calibration sample's fisheye_model, and ROS's distortion_model.
    const bool fisheye = function == OpenCvFunction::Fisheye;
    if (storage == OpenCvStorage::Yaml) {
        return "%YAML:1.0\n---\nimage_width: " + width + "\nimage_height: " + height + "\n" +
               (fisheye ? "fisheye_model: 1\ndistortion_model: equidistant\n" : "") + yaml_matrix("camera_matrix", K) +
               yaml_matrix("distortion_coefficients", dist) + yaml_matrix("rvec", r) + yaml_matrix("tvec", t);
    }
    return "<?xml version=\"1.0\"?>\n<opencv_storage>\n<image_width>" + width + "</image_width>\n<image_height>" + height +
           "</image_height>\n" +
           (fisheye ? "<fisheye_model>1</fisheye_model>\n<distortion_model>equidistant</distortion_model>\n" : "") +
           xml_matrix("camera_matrix", K) + xml_matrix("distortion_coefficients", dist) + xml_matrix("rvec", r) +
           xml_matrix("tvec", t) + "</opencv_storage>\n";
}

namespace {

// The calibration sample's layout (and cv::fisheye's, and ROS's camera_info).
Camera read_single(const Field& file, const ReadOptions& options, const std::string& source) {
    Camera camera;
    const std::optional<Field> width = file.find({"image_width", "image_Width"});
    const std::optional<Field> height = file.find({"image_height", "image_Height"});
    if (width || height || !options.size) {
        camera.size = {static_cast<long>(file.at({"image_width", "image_Width"}).integer(1, kMaxImageSide)),
                       static_cast<long>(file.at({"image_height", "image_Height"}).integer(1, kMaxImageSide))};
    } else {
        camera.size = *options.size;
    }
    camera.intrinsics = read_camera_matrix(file.at({"camera_matrix", "Camera_Matrix"}));
    const CoefficientFamily family = coefficient_family(file);
    if (const std::optional<Field> dist = file.find({"distortion_coefficients", "Distortion_Coefficients"})) {
        camera.lens = read_distortion(*dist, family);
    } else if (family == CoefficientFamily::Fisheye) {
        file.fail("\"distortion_coefficients\": missing (the file names a fisheye model)");
    }
    if (const std::optional<Field> rvec = file.find({"rvec"})) camera.pose.R = rotation_from_rvec(read_vector3(*rvec));
    if (const std::optional<Field> tvec = file.find({"tvec"})) camera.pose.t = read_vector3(*tvec);
    return validated_camera(camera, source);
}

// The image size of a file that may leave it out: its keys, else --image-size.
ImageSize size_from(const Field& file, std::initializer_list<std::string_view> width_keys,
                    std::initializer_list<std::string_view> height_keys, const ReadOptions& options) {
    const std::optional<Field> width = file.find(width_keys);
    const std::optional<Field> height = file.find(height_keys);
    if (width && height) {
        return {static_cast<long>(width->integer(1, kMaxImageSide)), static_cast<long>(height->integer(1, kMaxImageSide))};
    }
    if (options.size) return *options.size;
    file.at(width ? height_keys : width_keys);  // throws "missing"
    return {};
}

// A 4x4 (or 3x4) transform [R t] from a matrix key.
Pose read_transform(const Field& field) {
    const Matrix m = read_matrix(field);
    if (m.cols != 4 || (m.rows != 4 && m.rows != 3)) {
        field.fail("expected a 4x4 transform, got " + std::to_string(m.rows) + "x" + std::to_string(m.cols));
    }
    Pose pose;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) pose.R(r, c) = m.values[static_cast<std::size_t>(4 * r + c)];
        pose.t(r) = m.values[static_cast<std::size_t>(4 * r + 3)];
    }
    // ORB-SLAM's settings print rotations as float (dt: f).
    pose.R = nearest_rotation_if_rounded(pose.R);
    try {
        pose.validate(field.name().c_str());
    } catch (const InvalidArgument& error) {
        throw FileError(field.source() + ": " + error.what());
    }
    return pose;
}

// ---- ORB-SLAM's settings: Camera.fx (ORB-SLAM2, ORB-SLAM3 before 1.0) or Camera1.fx ----

bool is_orb_slam(const DocumentNode& tree) {
    return tree.find("Camera.fx") != nullptr || tree.find("Camera1.fx") != nullptr;
}

Camera orb_slam_camera(const Field& file, const std::string& prefix, const std::string& type, ImageSize size,
                       const std::string& source) {
    const auto value = [&](const char* key) { return file.at({prefix + key}).number(); };
    const auto optional = [&](const char* key) {
        const std::optional<Field> field = file.find({prefix + key});
        return field ? field->number() : 0.0;
    };
    Camera camera;
    camera.size = size;
    camera.intrinsics = {value("fx"), value("fy"), value("cx"), value("cy"), 0.0};
    if (type == "KannalaBrandt8") {
        camera.lens = {LensType::Fisheye, {value("k1"), value("k2"), value("k3"), value("k4")}};
    } else if (type == "Rectified") {
        camera.lens = {LensType::Pinhole, {}};
    } else {
        const std::vector<double> coefficients = {optional("k1"), optional("k2"), optional("p1"), optional("p2"),
                                                  optional("k3")};
        if (std::all_of(coefficients.begin(), coefficients.end(), [](double c) { return c == 0.0; })) {
            camera.lens = {LensType::Pinhole, {}};
        } else {
            camera.lens = {coefficients[4] == 0.0 ? LensType::OpenCv4 : LensType::OpenCv5,
                           {coefficients.begin(), coefficients.begin() + (coefficients[4] == 0.0 ? 4 : 5)}};
        }
    }
    return validated_camera(camera, source);
}

std::vector<NamedCamera> read_orb_slam(const Field& file, const ReadOptions& options, const std::string& source) {
    std::string type = "PinHole";
    if (const std::optional<Field> field = file.find({"Camera.type"})) type = field->text();
    if (type != "PinHole" && type != "KannalaBrandt8" && type != "Rectified") {
        file.at({"Camera.type"}).fail("must be PinHole, KannalaBrandt8 or Rectified, got " + shown_value(type));
    }
    const ImageSize size = size_from(file, {"Camera.width"}, {"Camera.height"}, options);
    const bool numbered = file.node().find("Camera1.fx") != nullptr;
    std::vector<NamedCamera> cameras;
    cameras.push_back({"Camera1", {orb_slam_camera(file, numbered ? "Camera1." : "Camera.", type, size, source), std::nullopt}});
    // The second camera: its own intrinsics and Stereo.T_c1_c2 (camera 2 in camera 1's
    // frame; Tlr before ORB-SLAM3 1.0), or a rectified pair's baseline Stereo.b.
    if (numbered && file.node().find("Camera2.fx") != nullptr) {
        Camera second = orb_slam_camera(file, "Camera2.", type, size, source);
        if (const std::optional<Field> transform = file.find({"Stereo.T_c1_c2", "Tlr"})) {
            second.pose = read_transform(*transform).inverse();
        } else {
            file.at({"Stereo.T_c1_c2"});  // throws "missing": where the second camera is is not known
        }
        cameras.push_back({"Camera2", {validated_camera(second, source), std::nullopt}});
    } else if (type == "Rectified" && file.node().find("Stereo.b") != nullptr) {
        Camera second = cameras.front().file.camera;
        second.pose.t = Vec3(-file.at({"Stereo.b"}).number(), 0.0, 0.0);
        cameras.push_back({"Camera2", {validated_camera(second, source), std::nullopt}});
    } else if (!numbered && file.node().find("Camera.bf") != nullptr && file.node().find("DepthMapFactor") == nullptr) {
        // ORB-SLAM2's stereo settings: Camera.* is the rectified left camera and
        // Camera.bf its baseline times fx. (An RGB-D file's Camera.bf, next to its
        // DepthMapFactor, is the depth sensor's baseline: no second image.)
        Camera second = cameras.front().file.camera;
        const Field bf = file.at({"Camera.bf"});
        if (!(bf.number() > 0)) bf.fail("must be > 0 (the baseline times fx), got " + shown_value(bf.text()));
        second.pose.t = Vec3(-bf.number() / second.intrinsics.fx, 0.0, 0.0);
        cameras.push_back({"Camera2", {validated_camera(second, source), std::nullopt}});
    }
    // ORB-SLAM2's stereo settings also hold the raw cameras it rectifies with
    // cv::initUndistortRectifyMap: LEFT.K, LEFT.D, LEFT.R, LEFT.P and the same for RIGHT,
    // placed in the rectified left camera's frame as ROS's camera_info places them.
    for (const std::string side : {"LEFT", "RIGHT"}) {
        if (file.node().find(side + ".K") == nullptr) continue;
        Camera raw;
        raw.size = file.node().find(side + ".width") != nullptr
                       ? size_from(file, {side + ".width"}, {side + ".height"}, options)
                       : size;
        raw.intrinsics = read_camera_matrix(file.at({side + ".K"}));
        raw.lens = read_distortion(file.at({side + ".D"}), CoefficientFamily::RadialTangential);
        const std::optional<Field> rectification = file.find({side + ".R"});
        const Mat3 R = rectification ? read_rotation(*rectification, true) : Mat3::Identity();
        if (const std::optional<Field> projection = file.find({side + ".P"})) {
            (void)place_in_rectified_pair(raw, R, *projection);
        } else {
            raw.pose = {R.transpose(), Vec3::Zero()};
        }
        cameras.push_back({side, {validated_camera(raw, source), std::nullopt}});
    }
    return cameras;
}

// ---- stereo files: M1 D1 M2 D2 (OpenCV's stereo_calib sample), or K1 D1 K2 D2; R and T ----

bool is_stereo(const DocumentNode& tree) {
    return (tree.find("M1") != nullptr || tree.find("K1") != nullptr) && tree.find("D1") != nullptr &&
           tree.find("camera_matrix") == nullptr;
}

std::vector<NamedCamera> read_stereo(const Field& file, const ReadOptions& options, const std::string& source) {
    const ImageSize size = size_from(file, {"image_width", "imageWidth", "width"}, {"image_height", "imageHeight", "height"},
                                     options);
    std::vector<NamedCamera> cameras;
    for (const int index : {1, 2}) {
        const std::string n = std::to_string(index);
        Camera camera;
        camera.size = size;
        camera.intrinsics = read_camera_matrix(file.at({"M" + n, "K" + n}));
        camera.lens = read_distortion(file.at({"D" + n}), CoefficientFamily::RadialTangential);
        cameras.push_back({"camera" + n, {camera, std::nullopt}});
    }
    // R, T: camera 2 from camera 1 (X2 = R X1 + T), as cv::stereoCalibrate gives them.
    const std::optional<Field> R = file.find({"R"});
    const std::optional<Field> T = file.find({"T"});
    if (R.has_value() != T.has_value()) file.at({R ? "T" : "R"});  // throws "missing"
    if (R) cameras[1].file.camera.pose = {read_rotation(*R, false), read_vector3(*T)};
    for (NamedCamera& camera : cameras) camera.file.camera = validated_camera(camera.file.camera, source);
    return cameras;
}

}  // namespace

DocumentNode parse_opencv_storage_tree(std::string_view text, const std::string& source) {
    return parse_tree(text, source);
}

Camera read_opencv_storage_camera(const Field& file, const std::string& source) {
    return read_single(file, {}, source);
}

Camera parse_opencv_storage(std::string_view text, const std::string& source) {
    return parse_opencv_storage_set(text, source, {}).front().file.camera;
}

std::vector<NamedCamera> parse_opencv_storage_set(std::string_view text, const std::string& source,
                                                  const ReadOptions& options) {
    const DocumentNode tree = parse_tree(text, source);
    const Field file(tree, "", source);
    if (is_orb_slam(tree)) return read_orb_slam(file, options, source);
    if (is_stereo(tree)) return read_stereo(file, options, source);
    return {{std::string(), {read_single(file, options, source), std::nullopt}}};
}

// ---- ROS camera_info ------------------------------------------------------------------

namespace {

// ROS's distortion_model for a lens, and its coefficients (plumb_bob has five).
std::pair<std::string, std::vector<double>> ros_distortion(const Lens& lens) {
    std::vector<double> coefficients = lens.coefficients;
    const auto zero_after = [&](std::size_t kept) {
        return std::all_of(coefficients.begin() + static_cast<long>(std::min(kept, coefficients.size())), coefficients.end(),
                           [](double c) { return c == 0.0; });
    };
    switch (lens.type) {
        case LensType::Pinhole:
        case LensType::OpenCv4:
        case LensType::OpenCv5:
            coefficients.resize(5, 0.0);
            return {"plumb_bob", coefficients};
        case LensType::OpenCv8:
        case LensType::OpenCv12:
        case LensType::OpenCv14:
            if (!zero_after(8)) break;
            coefficients.resize(8, 0.0);
            return {"rational_polynomial", coefficients};
        case LensType::Fisheye:
            return {"equidistant", coefficients};
        // Every other model, named so that the compiler asks here about a new one.
        case LensType::Stereographic:
        case LensType::Lonlat:
        case LensType::Latlon:
        case LensType::DoubleSphere:
        case LensType::Ucm:
        case LensType::Eucm:
        case LensType::Mei:
        case LensType::Fov:
        case LensType::ThinPrismFisheye:
        case LensType::RadTanThinPrismFisheye:
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
        case LensType::BrownK4:
        case LensType::EquidistantRadial:
        case LensType::EquisolidRadial:
        case LensType::StereographicRadial:
            detail::refuse_lens(CameraFormat::Ros, lens.type);
    }
    detail::refuse_lens(CameraFormat::Ros, lens.type);
}

std::string ros_matrix(const std::string& key, long long rows, long long cols, const std::vector<double>& values) {
    std::string out = key + ":\n  rows: " + std::to_string(rows) + "\n  cols: " + std::to_string(cols) + "\n  data: [";
    for (std::size_t i = 0; i < values.size(); ++i) out += (i == 0 ? "" : ", ") + yaml_number(values[i]);
    return out + "]\n";
}

}  // namespace

std::vector<NamedCamera> parse_ros_camera_info(std::string_view text, const std::string& source) {
    const DocumentNode tree = parse_tree(text, source);
    const Field file(tree, "", source);
    Camera raw = read_single(file, {}, source);
    const std::string name = file.find({"camera_name"}) ? file.at({"camera_name"}).text() : std::string();
    const std::optional<Field> rectification = file.find({"rectification_matrix"});
    const Mat3 R = rectification ? read_rotation(*rectification, true) : Mat3::Identity();
    std::vector<NamedCamera> cameras;
    const std::optional<Field> projection = file.find({"projection_matrix"});
    if (!projection) {
        raw.pose = {R.transpose(), Vec3::Zero()};
        cameras.push_back({name, {validated_camera(raw, source), std::nullopt}});
        return cameras;
    }
    const Camera rectified = place_in_rectified_pair(raw, R, *projection);
    cameras.push_back({name, {validated_camera(raw, source), std::nullopt}});
    cameras.push_back({name.empty() ? "rectified" : name + "/rectified", {validated_camera(rectified, source), std::nullopt}});
    return cameras;
}

std::string format_ros_camera_info(const Camera& camera, const WriteOptions& options) {
    camera.validate();
    if (!options.drop_pose && (camera.pose.R != Mat3::Identity() || camera.pose.t != Vec3::Zero())) {
        throw NotRepresentable("ROS's camera_info holds no pose (ROS keeps poses in tf); this camera's is not the "
                               "identity: write its intrinsics alone with --no-pose");
    }
    const auto [model, coefficients] = ros_distortion(camera.lens);
    const Intrinsics& k = camera.intrinsics;
    return "image_width: " + std::to_string(camera.size.width) + "\nimage_height: " + std::to_string(camera.size.height) +
           "\ncamera_name: " + options.camera_name + "\n" +
           ros_matrix("camera_matrix", 3, 3, {k.fx, k.skew, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0}) +
           "distortion_model: " + model + "\n" +
           ros_matrix("distortion_coefficients", 1, static_cast<long long>(coefficients.size()), coefficients) +
           ros_matrix("rectification_matrix", 3, 3, {1, 0, 0, 0, 1, 0, 0, 0, 1}) +
           ros_matrix("projection_matrix", 3, 4, {k.fx, k.skew, k.cx, 0.0, 0.0, k.fy, k.cy, 0.0, 0.0, 0.0, 1.0, 0.0});
}

}  // namespace libcam
