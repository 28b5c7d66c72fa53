#include "libcam/interop/opencv.hpp"

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <limits>
#include <optional>
#include <vector>

#include "libcam/error.hpp"

namespace libcam {

cv::Mat opencv_camera_matrix(const Intrinsics& k) {
    return (cv::Mat_<double>(3, 3) << k.fx, k.skew, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0);
}

namespace {

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

bool uses_opencv_fisheye(const Lens& lens) { return lens_info(lens.type).opencv == OpenCvFunction::Fisheye; }

}  // namespace

cv::Mat opencv_distortion(const Lens& lens) {
    if (lens_info(lens.type).opencv == OpenCvFunction::None) {
        throw NotRepresentable("lens: OpenCV has no model " + std::string(lens_info(lens.type).name));
    }
    cv::Mat dist(1, static_cast<int>(lens.coefficients.size()), CV_64F);
    std::copy(lens.coefficients.begin(), lens.coefficients.end(), dist.ptr<double>());
    return dist;
}

cv::Mat opencv_vector(const Vec3& v) { return (cv::Mat_<double>(3, 1) << v.x(), v.y(), v.z()); }

std::vector<Vec2> opencv_project_points(const Camera& camera, const std::vector<Vec3>& camera_points) {
    camera.validate();
    if (camera_points.empty()) return {};
    std::vector<cv::Point3d> object;
    for (const Vec3& p : camera_points) object.emplace_back(p.x(), p.y(), p.z());
    std::vector<cv::Point2d> image;
    const cv::Mat K = opencv_camera_matrix(camera.intrinsics);
    const cv::Mat dist = opencv_distortion(camera.lens);
    const cv::Mat zero = cv::Mat::zeros(3, 1, CV_64F);
    if (uses_opencv_fisheye(camera.lens)) {
        cv::fisheye::projectPoints(object, image, zero, zero, K, dist);
    } else {
        cv::projectPoints(object, zero, zero, K, dist, image);
    }
    std::vector<Vec2> pixels;
    for (const cv::Point2d& q : image) pixels.emplace_back(q.x, q.y);
    return pixels;
}

std::string format_opencv_storage(const Camera& camera, OpenCvStorage storage) {
    camera.validate();
    const int mode = cv::FileStorage::WRITE | cv::FileStorage::MEMORY |
                     (storage == OpenCvStorage::Yaml ? cv::FileStorage::FORMAT_YAML : cv::FileStorage::FORMAT_XML);
    cv::FileStorage fs(storage == OpenCvStorage::Yaml ? ".yaml" : ".xml", mode);
    fs << "image_width" << static_cast<int>(camera.size.width);
    fs << "image_height" << static_cast<int>(camera.size.height);
    fs << "camera_matrix" << opencv_camera_matrix(camera.intrinsics);
    if (lens_info(camera.lens.type).opencv != OpenCvFunction::ProjectPoints) {
        // FISHEYE's four coefficients would read back as OPENCV4: refuse, never convert silently.
        throw NotRepresentable("lens: OpenCV's camera file holds only OpenCV's radial-tangential models, not " +
                               std::string(lens_info(camera.lens.type).name));
    }
    const cv::Mat dist = camera.lens.type == LensType::Pinhole ? cv::Mat::zeros(5, 1, CV_64F)
                                                               : opencv_distortion(camera.lens).t();
    fs << "distortion_coefficients" << dist;
    fs << "rvec" << opencv_vector(camera.pose.rvec());
    fs << "tvec" << opencv_vector(camera.pose.t);
    return fs.releaseAndGetString();
}

namespace {

// The most elements a camera matrix or coefficient vector can have. A file that
// declares more (rows: 2000000000) is refused before OpenCV allocates it.
constexpr int kMaxMatrixElements = 64;

void check_matrix_size(const cv::FileNode& node, const char* key, const std::string& source) {
    const auto refuse = [&](const std::string& what) {
        throw FileError(source + ": \"" + key + "\": " + what + " (at most " + std::to_string(kMaxMatrixElements) +
                        " elements)");
    };
    if (node.isSeq() && node.size() > static_cast<std::size_t>(kMaxMatrixElements)) {
        refuse("too many elements: " + std::to_string(node.size()));
    }
    if (!node.isMap()) return;
    const cv::FileNode rows = node["rows"], cols = node["cols"], data = node["data"];
    if (!rows.isInt() || !cols.isInt()) refuse("rows and cols must be integers");
    const long long count = static_cast<long long>(static_cast<int>(rows)) * static_cast<int>(cols);
    if (static_cast<int>(rows) < 0 || static_cast<int>(cols) < 0 || count > kMaxMatrixElements) {
        refuse("declares " + std::to_string(static_cast<int>(rows)) + "x" + std::to_string(static_cast<int>(cols)));
    }
    if (data.isSeq() && data.size() > static_cast<std::size_t>(kMaxMatrixElements)) {
        refuse("too many data elements: " + std::to_string(data.size()));
    }
}

// A node as a CV_64F matrix; FileError naming the key unless it is a matrix of `count`
// finite numbers (count < 0: any count).
cv::Mat read_matrix(const cv::FileNode& node, const char* key, const std::string& source, int rows, int cols) {
    if (node.empty() || node.isNone()) throw FileError(source + ": \"" + key + "\": missing");
    check_matrix_size(node, key, source);
    cv::Mat m;
    try {
        node >> m;
    } catch (const cv::Exception& error) {
        throw FileError(source + ": \"" + key + "\": not a matrix: " + error.msg);
    }
    if (m.empty() && !(rows < 0 && cols < 0)) throw FileError(source + ": \"" + key + "\": not a matrix or empty");
    if (!m.empty()) m.convertTo(m, CV_64F);
    if ((rows >= 0 && m.rows != rows) || (cols >= 0 && m.cols != cols)) {
        throw FileError(source + ": \"" + key + "\": expected a " + std::to_string(rows) + "x" + std::to_string(cols) +
                        " matrix, got " + std::to_string(m.rows) + "x" + std::to_string(m.cols));
    }
    for (int i = 0; i < static_cast<int>(m.total()); ++i) {
        const double value = m.ptr<double>()[i];
        if (!std::isfinite(value)) {
            throw FileError(source + ": \"" + key + "\"[" + std::to_string(i) + "]: must be finite, got " +
                            format_number(value));
        }
    }
    return m;
}

long read_side(const cv::FileNode& node, const char* key, const std::string& source) {
    if (node.empty() || node.isNone()) throw FileError(source + ": \"" + key + "\": missing");
    if (!node.isInt()) throw FileError(source + ": \"" + key + "\": expected an integer");
    const long value = static_cast<int>(node);
    if (value < 1 || value > kMaxImageSide) {
        throw FileError(source + ": \"" + key + "\": must be in [1, " + std::to_string(kMaxImageSide) + "], got " +
                        std::to_string(value));
    }
    return value;
}

Vec3 read_vector3(const cv::FileNode& node, const char* key, const std::string& source) {
    cv::Mat m = read_matrix(node, key, source, -1, -1).reshape(1, 1);
    if (m.total() != 3) {
        throw FileError(source + ": \"" + key + "\": expected 3 numbers, got " + std::to_string(m.total()));
    }
    return {m.at<double>(0), m.at<double>(1), m.at<double>(2)};
}

// OpenCV 4.6 reads every integer literal into a 32-bit int and wraps it silently:
// image_width 4294967936 reads as 640, and so does 4294967936 inside a matrix of
// doubles (5700000000000 as fx reads 578398208). So every integer literal of the text
// is checked before OpenCV sees it; `field` names where it stands.
bool is_word_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-' || c == '_';
}

void check_integer_literal(std::string_view word, const std::string& field, const std::string& source) {
    const std::string_view digits = word.starts_with('+') || word.starts_with('-') ? word.substr(1) : word;
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string_view::npos) return;  // not an integer
    long long value = 0;
    const char* first = word.data() + (word.starts_with('+') ? 1 : 0);
    const auto [end, error] = std::from_chars(first, word.data() + word.size(), value);
    const bool fits = error == std::errc() && end == word.data() + word.size() &&
                      value >= std::numeric_limits<int>::min() && value <= std::numeric_limits<int>::max();
    if (!fits) {
        throw FileError(source + ": \"" + field + "\": the integer " + std::string(word) +
                        " is outside OpenCV's 32-bit int range (OpenCV would read another number in its place)");
    }
}

// The words of `text` (runs of letters, digits, '.', '+', '-', '_') from `i`, each checked;
// returns where the word that starts at i ends.
std::size_t check_word_at(std::string_view text, std::size_t i, const std::string& field, const std::string& source) {
    std::size_t end = i;
    while (end < text.size() && is_word_char(text[end])) ++end;
    check_integer_literal(text.substr(i, end - i), field, source);
    return end;
}

void check_integer_literals(std::string_view text, const std::string& field, const std::string& source) {
    for (std::size_t i = 0; i < text.size();) i = is_word_char(text[i]) ? check_word_at(text, i, field, source) : i + 1;
}

// OpenCV 4.6's YAML parser loops forever on some malformed documents (found by
// fuzzing: "%YAML:1.0\n----m\nm\nm"), so YAML is checked line by line against the
// shape cv::FileStorage writes before OpenCV sees it: the %YAML header, "---", then
// "key: value" lines (indented with spaces for matrix fields), comments, "- item" lines,
// and flow sequences [ ... ] that may span lines. Anything else is refused here.
void check_opencv_yaml_shape(std::string_view text, const std::string& source) {
    std::size_t start = 0;
    int line_number = 0;
    int open_brackets = 0;
    auto is_key_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; };
    std::string top_key, field;  // the key at indentation 0, and top_key.key below it
    while (start < text.size()) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        std::string_view line = text.substr(start, end - start);
        start = end + 1;
        ++line_number;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        const auto refuse = [&](const std::string& what) {
            throw FileError(source + ": line " + std::to_string(line_number) + ": " + what +
                            " (not the YAML cv::FileStorage writes)");
        };
        if (line_number == 1) {
            if (!line.starts_with("%YAML")) refuse("expected the %YAML header");
            continue;
        }
        if (line_number == 2) {
            if (line != "---") refuse("expected '---'");
            continue;
        }
        const std::size_t indent = line.find_first_not_of(' ');
        if (indent == std::string_view::npos || line[indent] == '#') continue;  // blank or comment
        if (line.find('\t') != std::string_view::npos) refuse("tab character");
        std::string_view rest = line.substr(indent);
        // One document: a second "---" or "..." hangs OpenCV 4.6's parser (found by fuzzing:
        // "%YAML:1.5\n---\n   data:([ 1.5%YAML:1.5\n---\n..." inside a flow sequence).
        if (rest.starts_with("---") || rest.starts_with("...")) refuse("a second YAML document marker");
        if (open_brackets == 0) {
            if (rest.starts_with("- ") || rest == "-") {
                rest.remove_prefix(1);
            } else {
                std::size_t key_end = 0;
                while (key_end < rest.size() && is_key_char(rest[key_end])) ++key_end;
                if (key_end == 0 || key_end >= rest.size() || rest[key_end] != ':') refuse("expected 'key: value'");
                const std::string key(rest.substr(0, key_end));
                if (indent == 0) top_key = key;
                field = indent == 0 ? key : top_key + "." + key;
                rest.remove_prefix(key_end + 1);
            }
        }
        for (std::size_t i = 0; i < rest.size(); ++i) {
            const char c = rest[i];
            if (c == '"' || c == '\'') {
                const std::size_t close = rest.find(c, i + 1);
                if (close == std::string_view::npos) refuse("unterminated string");
                i = close;
            } else if (c == '[' || c == '{') {
                if (++open_brackets > 4) refuse("nested too deep");
            } else if (c == ']' || c == '}') {
                if (--open_brackets < 0) refuse("unbalanced '" + std::string(1, c) + "'");
            } else if (c == '#' && open_brackets == 0) {
                break;
            } else if (std::string_view("%&*|>@`()").find(c) != std::string_view::npos) {
                // Directives, anchors, aliases, block scalars, reserved: never in what
                // cv::FileStorage writes outside a string.
                refuse("'" + std::string(1, c) + "' outside a string");
            } else if (is_word_char(c) && (i == 0 || !is_word_char(rest[i - 1]))) {
                i = check_word_at(rest, i, field, source) - 1;
            }
        }
    }
    if (open_brackets != 0) throw FileError(source + ": unclosed '[' (truncated file?)");
}

// OpenCV 4.6's XML parser reads past the end of its input on a truncated tag such as
// "<im rn=" (found by fuzzing), so XML is checked first: every tag closed with '>',
// attribute values quoted and closed, comments and declarations closed, elements
// nested and balanced; the text between tags is checked for integer literals only.
void check_opencv_xml_shape(std::string_view text, const std::string& source) {
    constexpr int kMaxDepth = 8;
    std::vector<std::string_view> open_elements;
    const auto refuse = [&](std::size_t at, const std::string& what) {
        throw FileError(source + ": byte " + std::to_string(at) + ": " + what + " (not the XML cv::FileStorage writes)");
    };
    auto is_name_char = [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == ':';
    };
    // The element a text between tags belongs to: the one below the root, and the
    // innermost if deeper ("camera_matrix.data").
    const auto field = [&open_elements] {
        if (open_elements.size() < 2) return std::string(open_elements.empty() ? "" : open_elements.back());
        std::string name(open_elements[1]);
        if (open_elements.size() > 2) name += "." + std::string(open_elements.back());
        return name;
    };
    std::size_t i = 0, content = 0;  // content: where the text after the last tag starts
    while ((i = text.find('<', i)) != std::string_view::npos) {
        const std::size_t tag = i;
        check_integer_literals(text.substr(content, tag - content), field(), source);
        for (std::string_view closer : {"<!--", "<?"}) {
            if (text.substr(i).starts_with(closer)) {
                const std::string_view end = closer == "<?" ? "?>" : "-->";
                const std::size_t close = text.find(end, i + closer.size());
                if (close == std::string_view::npos) refuse(tag, "unclosed '" + std::string(closer) + "'");
                i = close + end.size();
                content = i;
                break;
            }
        }
        if (i != tag) continue;
        const bool closing = i + 1 < text.size() && text[i + 1] == '/';
        std::size_t name_end = i + (closing ? 2 : 1);
        const std::size_t name_start = name_end;
        while (name_end < text.size() && is_name_char(text[name_end])) ++name_end;
        if (name_end == name_start) refuse(tag, "a tag without a name");
        const std::string_view name = text.substr(name_start, name_end - name_start);
        // Attributes: name="value" pairs up to '>' or '/>'.
        i = name_end;
        bool self_closing = false;
        while (true) {
            while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
            if (i >= text.size()) refuse(tag, "unclosed tag <" + std::string(name));
            if (text[i] == '>') break;
            if (!closing && text.substr(i).starts_with("/>")) {
                self_closing = true;
                ++i;
                break;
            }
            const std::size_t attribute = i;
            while (i < text.size() && is_name_char(text[i])) ++i;
            if (closing || i == attribute || i + 1 >= text.size() || text[i] != '=' ||
                (text[i + 1] != '"' && text[i + 1] != '\'')) {
                refuse(attribute, "malformed attribute in <" + std::string(name) + ">");
            }
            const std::size_t close = text.find(text[i + 1], i + 2);
            if (close == std::string_view::npos) refuse(attribute, "unterminated attribute value");
            i = close + 1;
        }
        ++i;  // past '>'
        content = i;
        if (closing) {
            if (open_elements.empty() || open_elements.back() != name) refuse(tag, "unbalanced </" + std::string(name) + ">");
            open_elements.pop_back();
        } else if (!self_closing) {
            open_elements.push_back(name);
            if (static_cast<int>(open_elements.size()) > kMaxDepth) refuse(tag, "nested too deep");
        }
    }
    if (!open_elements.empty()) {
        throw FileError(source + ": <" + std::string(open_elements.back()) + "> is never closed (truncated file?)");
    }
}

}  // namespace

Camera parse_opencv_storage(std::string_view text, const std::string& source) {
    // XML or else the YAML cv::FileStorage writes, checked before OpenCV parses it.
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos) throw FileError(source + ": file is empty");
    if (text[first] == '<') {
        check_opencv_xml_shape(text, source);
    } else {
        check_opencv_yaml_shape(text.substr(first), source);
    }
    cv::FileStorage fs;
    try {
        if (!fs.open(std::string(text), cv::FileStorage::READ | cv::FileStorage::MEMORY)) {
            throw FileError(source + ": not an OpenCV YAML/XML file");
        }
    } catch (const cv::Exception& error) {
        throw FileError(source + ": not a valid OpenCV YAML/XML file: " + error.err);
    } catch (const std::exception& error) {
        // OpenCV's parser also lets standard exceptions out (std::length_error on some
        // malformed YAML, found by fuzzing).
        throw FileError(source + ": not a valid OpenCV YAML/XML file: " + error.what());
    }
    try {
        Camera camera;
        camera.size = {read_side(fs["image_width"], "image_width", source),
                       read_side(fs["image_height"], "image_height", source)};
        const cv::Mat K = read_matrix(fs["camera_matrix"], "camera_matrix", source, 3, 3);
        Mat3 k;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) k(r, c) = K.at<double>(r, c);
        try {
            camera.intrinsics = Intrinsics::from_K(k, "camera_matrix");
        } catch (const InvalidArgument& error) {
            throw FileError(source + ": " + error.what());
        }

        const cv::FileNode dist_node = fs["distortion_coefficients"];
        if (!dist_node.empty() && !dist_node.isNone()) {
            const cv::Mat dist = read_matrix(dist_node, "distortion_coefficients", source, -1, -1);
            const bool all_zero = dist.empty() || cv::countNonZero(dist) == 0;
            if (!all_zero) {
                if (dist.rows != 1 && dist.cols != 1) {
                    throw FileError(source + ": \"distortion_coefficients\": expected a vector, got a " +
                                    std::to_string(dist.rows) + "x" + std::to_string(dist.cols) + " matrix");
                }
                const std::optional<LensType> type = opencv_model_with(dist.total());
                if (!type) {
                    throw FileError(source + ": \"distortion_coefficients\": expected 4, 5, 8, 12 or 14 coefficients, got " +
                                    std::to_string(dist.total()));
                }
                camera.lens.type = *type;
                const cv::Mat values = dist.reshape(1, 1);
                camera.lens.coefficients.assign(values.ptr<double>(), values.ptr<double>() + values.total());
            }
        }
        const cv::FileNode rvec = fs["rvec"];
        const cv::FileNode tvec = fs["tvec"];
        if (!rvec.empty() && !rvec.isNone()) camera.pose.R = rotation_from_rvec(read_vector3(rvec, "rvec", source));
        if (!tvec.empty() && !tvec.isNone()) camera.pose.t = read_vector3(tvec, "tvec", source);
        camera.validate();
        return camera;
    } catch (const cv::Exception& error) {
        throw FileError(source + ": malformed OpenCV file: " + error.err);
    } catch (const InvalidArgument& error) {
        throw FileError(source + ": " + error.what());
    } catch (const Error&) {
        throw;
    } catch (const std::exception& error) {
        throw FileError(source + ": malformed OpenCV file: " + error.what());
    }
}

}  // namespace libcam
