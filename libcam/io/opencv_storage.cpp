#include "libcam/io/opencv_storage.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/document.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

// The most elements a camera matrix or coefficient vector can have. A file that
// declares more (rows: 2000000000) is refused before anything is allocated for it.
constexpr long long kMaxMatrixElements = 64;

// OpenCV's radial-tangential models (cv::projectPoints), told apart by their number of
// coefficients; PINHOLE's empty list is written as five zeros and read back as PINHOLE.
std::optional<LensType> opencv_model_with(std::size_t count) {
    for (const LensInfo& info : lens_models()) {
        if (info.opencv == OpenCvFunction::ProjectPoints && info.num_coefficients > 0 &&
            static_cast<std::size_t>(info.num_coefficients) == count) {
            return info.type;
        }
    }
    return std::nullopt;
}

// ---- writing ----

// A double as OpenCV writes one: every digit that matters, and a '.' when the shortest
// form would read as an integer ("500." rather than "500").
std::string opencv_number(double value) {
    std::string text = format_number(value);
    if (text.find_first_of(".eEn") == std::string::npos) text += '.';
    return text;
}

struct Matrix {
    long long rows = 0, cols = 0;
    std::vector<double> values;  // row-major
};

std::string yaml_matrix(const std::string& key, const Matrix& m) {
    std::string out = key + ": !!opencv-matrix\n   rows: " + std::to_string(m.rows) + "\n   cols: " +
                      std::to_string(m.cols) + "\n   dt: d\n   data: [";
    for (std::size_t i = 0; i < m.values.size(); ++i) out += (i == 0 ? " " : ", ") + opencv_number(m.values[i]);
    return out + " ]\n";
}

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

// A matrix as cv::FileStorage writes it (a map tagged opencv-matrix with rows, cols,
// dt and data), or a plain list of numbers, which OpenCV reads as a column.
Matrix read_matrix(const Field& field) {
    const DocumentNode& node = field.node();
    if (node.kind != DocumentNode::Kind::Map) {
        std::vector<double> values = field.numbers(static_cast<std::size_t>(kMaxMatrixElements));
        return column(values);
    }
    if (!node.tag.empty() && node.tag != "opencv-matrix") field.fail("expected an opencv-matrix, got a " + node.tag);
    Matrix m;
    m.rows = field.at({"rows"}).integer(0, kMaxMatrixElements);
    m.cols = field.at({"cols"}).integer(0, kMaxMatrixElements);
    if (m.rows * m.cols > kMaxMatrixElements) {
        field.fail("declares " + std::to_string(m.rows) + "x" + std::to_string(m.cols) + " (at most " +
                   std::to_string(kMaxMatrixElements) + " elements)");
    }
    const Field dt = field.at({"dt"});
    // One channel of any element type: the numbers are read as doubles whatever it is.
    static constexpr std::string_view kSingleChannel[] = {"d", "f", "i", "u", "s", "w", "c", "h"};
    const std::string type = dt.text();
    if (std::find(std::begin(kSingleChannel), std::end(kSingleChannel), type) == std::end(kSingleChannel)) {
        dt.fail("expected a one-channel element type (d, f, i, u, s, w, c or h), got '" + type + "'");
    }
    if (m.rows * m.cols == 0) return m;
    const Field data = field.at({"data"});
    m.values = data.numbers(static_cast<std::size_t>(kMaxMatrixElements));
    if (static_cast<long long>(m.values.size()) != m.rows * m.cols) {
        data.fail("holds " + std::to_string(m.values.size()) + " numbers, but rows x cols is " + std::to_string(m.rows) +
                  "x" + std::to_string(m.cols));
    }
    return m;
}

Vec3 read_vector3(const Field& field) {
    const Matrix m = read_matrix(field);
    if (m.values.size() != 3) field.fail("expected 3 numbers, got " + std::to_string(m.values.size()));
    return {m.values[0], m.values[1], m.values[2]};
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
            model->fail("'" + model->text() +
                        "' is not a model this reader knows (plumb_bob, rational_polynomial, equidistant or fisheye)");
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

Camera parse_opencv_storage(std::string_view text, const std::string& source) {
    const DocumentNode tree = parse_tree(text, source);
    const Field file(tree, "", source);
    Camera camera;
    camera.size = {static_cast<long>(file.at({"image_width", "image_Width"}).integer(1, kMaxImageSide)),
                   static_cast<long>(file.at({"image_height", "image_Height"}).integer(1, kMaxImageSide))};
    camera.intrinsics = read_camera_matrix(file.at({"camera_matrix", "Camera_Matrix"}));
    const CoefficientFamily family = coefficient_family(file);
    if (const std::optional<Field> dist = file.find({"distortion_coefficients", "Distortion_Coefficients"})) {
        camera.lens = read_distortion(*dist, family);
    } else if (family == CoefficientFamily::Fisheye) {
        file.fail("\"distortion_coefficients\": missing (the file names a fisheye model)");
    }
    if (const std::optional<Field> rvec = file.find({"rvec"})) camera.pose.R = rotation_from_rvec(read_vector3(*rvec));
    if (const std::optional<Field> tvec = file.find({"tvec"})) camera.pose.t = read_vector3(*tvec);
    try {
        camera.validate();
    } catch (const InvalidArgument& error) {
        throw FileError(source + ": " + error.what());
    }
    return camera;
}

}  // namespace libcam
