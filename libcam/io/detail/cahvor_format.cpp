#include "libcam/io/detail/cahvor_format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>

#include "libcam/error.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

struct Entry {
    std::string value;
    int line;
};

class CahvorFile {
public:
    CahvorFile(std::string_view text, const std::string& source) : source_(source) {
        std::size_t at = 0;
        int number = 0;
        while (at < text.size()) {
            const std::size_t end = std::min(text.find('\n', at), text.size());
            std::string_view line = text.substr(at, end - at);
            at = end + 1;
            ++number;
            const auto start = line.find_first_not_of(" \t\r");
            if (start == std::string_view::npos || line[start] == '#') continue;
            line = line.substr(start);
            const auto equals = line.find('=');
            if (equals == std::string_view::npos) fail(number, "expected \"key = value\"");
            std::string key(line.substr(0, line.find_first_of(" \t=")));
            const bool word = !key.empty() && key.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                                                    "0123456789_") == std::string::npos;
            if (!word || line.find_first_not_of(" \t", key.size()) != equals) {
                fail(number, "expected \"key = value\"");
            }
            // Older files say DISTORTION_OPENCV4 for mrcal's LENSMODEL_OPENCV4.
            if (key.starts_with("DISTORTION")) key.replace(0, 10, "LENSMODEL");
            std::string_view value = line.substr(equals + 1);
            const auto first = value.find_first_not_of(" \t");
            const auto last = value.find_last_not_of(" \t\r");
            value = first == std::string_view::npos ? std::string_view() : value.substr(first, last - first + 1);
            if (value.empty()) fail(number, "\"" + key + "\": no value");
            if (!entries_.emplace(key, Entry{std::string(value), number}).second) {
                fail(number, "\"" + key + "\" given more than once");
            }
        }
    }

    bool has(const std::string& key) const { return entries_.contains(key); }
    const Entry& at(const std::string& key) const {
        const auto found = entries_.find(key);
        if (found == entries_.end()) throw FileError(source_ + ": \"" + key + "\": missing");
        return found->second;
    }
    std::vector<double> numbers(const std::string& key, std::size_t count) const {
        const Entry& entry = at(key);
        std::vector<double> values;
        std::string_view rest = entry.value;
        while (!rest.empty()) {
            const auto start = rest.find_first_not_of(" \t");
            if (start == std::string_view::npos) break;
            rest = rest.substr(start);
            double value = 0.0;
            const auto [end, error] = std::from_chars(rest.data(), rest.data() + rest.size(), value);
            const std::size_t used = static_cast<std::size_t>(end - rest.data());
            if (error != std::errc() || !std::isfinite(value) || (used < rest.size() && rest[used] != ' ' && rest[used] != '\t')) {
                fail(entry.line, "\"" + key + "\": expected numbers, got " + shown_value(entry.value));
            }
            values.push_back(value);
            if (values.size() > count) break;
            rest = rest.substr(used);
        }
        if (values.size() != count) {
            fail(entry.line,
                 "\"" + key + "\": expected " + std::to_string(count) + " numbers, got " + shown_value(entry.value));
        }
        return values;
    }
    Vec3 vector(const std::string& key) const {
        const std::vector<double> v = numbers(key, 3);
        return {v[0], v[1], v[2]};
    }
    [[noreturn]] void fail(int line, const std::string& what) const {
        throw FileError(source_ + ": line " + std::to_string(line) + ": " + what);
    }
    const std::string& source() const { return source_; }

private:
    std::map<std::string, Entry> entries_;
    const std::string& source_;
};

// mrcal's way of keeping an OpenCV lens in a CAHV file.
struct OpenCvKey {
    const char* key;
    LensType type;
};
constexpr OpenCvKey kOpenCvKeys[] = {{"LENSMODEL_OPENCV12", LensType::OpenCv12},
                                     {"LENSMODEL_OPENCV8", LensType::OpenCv8},
                                     {"LENSMODEL_OPENCV5", LensType::OpenCv5},
                                     {"LENSMODEL_OPENCV4", LensType::OpenCv4}};

// "CAHVORE3,<linearity> = general": the linearity, else nullopt.
std::optional<double> cahvore_linearity(const CahvorFile& file) {
    if (!file.has("Model")) return std::nullopt;
    const Entry& model = file.at("Model");
    if (!model.value.starts_with("CAHVORE3,")) return std::nullopt;
    const std::string_view rest = std::string_view(model.value).substr(9);
    double linearity = 0.0;
    const auto [end, error] = std::from_chars(rest.data(), rest.data() + rest.size(), linearity);
    if (error != std::errc() || !std::isfinite(linearity)) {
        file.fail(model.line, "\"Model\": expected CAHVORE3,<linearity>, got " + shown_value(model.value));
    }
    return linearity;
}

}  // namespace

std::vector<NamedCamera> parse_cahvor(std::string_view text, const std::string& source) {
    const CahvorFile file(text, source);
    const std::vector<double> dimensions = file.numbers("Dimensions", 2);
    for (const double side : dimensions) {
        if (side != std::floor(side) || side < 1 || side > static_cast<double>(kMaxImageSide)) {
            file.fail(file.at("Dimensions").line, "\"Dimensions\": expected two whole numbers in [1, " +
                                                      std::to_string(kMaxImageSide) + "], got " +
                                                      shown_value(file.at("Dimensions").value));
        }
    }
    const Vec3 C = file.vector("C");
    const Vec3 A = file.vector("A");
    const Vec3 H = file.vector("H");
    const Vec3 V = file.vector("V");
    // H = fx H' + cx A, V = fy V' + cy A, with H', V', A the camera's axes.
    const double cx = H.dot(A);
    const double cy = V.dot(A);
    const Vec3 h = H - cx * A;
    const Vec3 v = V - cy * A;
    const double fx = h.norm();
    const double fy = v.norm();
    if (!(fx > 0) || !(fy > 0)) throw FileError(source + ": \"H\", \"V\": parallel to \"A\": no focal length");
    Mat3 camera_to_reference;
    camera_to_reference << h / fx, v / fy, A;

    Camera camera;
    camera.size = {static_cast<long>(dimensions[0]), static_cast<long>(dimensions[1])};
    camera.intrinsics = {fx, fy, cx, cy, 0.0};
    Pose placement{nearest_rotation_if_rounded(camera_to_reference), C};
    camera.pose = placement.inverse();

    const std::optional<double> linearity = cahvore_linearity(file);
    const OpenCvKey* opencv = nullptr;
    for (const OpenCvKey& key : kOpenCvKeys) {
        if (file.has(key.key)) {
            opencv = &key;
            break;
        }
    }
    if (opencv != nullptr) {
        const int count = lens_info(opencv->type).num_coefficients;
        camera.lens = {opencv->type, file.numbers(opencv->key, static_cast<std::size_t>(count))};
    } else if (!linearity && (!file.has("R") || file.vector("R").norm() < 1e-8)) {
        camera.lens = {LensType::Pinhole, {}};
    } else {
        // alpha and beta: O's direction in the camera frame.
        double alpha = 0.0;
        double beta = 0.0;
        if (file.has("O")) {
            const Vec3 o = camera_to_reference.transpose() * file.vector("O");
            alpha = std::atan2(o.x(), o.z());
            beta = std::asin(std::clamp(o.y(), -1.0, 1.0));
        }
        const Vec3 R = file.vector("R");
        if (linearity) {
            const Vec3 E = file.vector("E");
            camera.lens = {LensType::Cahvore, {alpha, beta, R.x(), R.y(), R.z(), E.x(), E.y(), E.z(), *linearity}};
        } else {
            if (file.has("E")) file.fail(file.at("E").line, "\"E\": a CAHVOR model has no E (CAHVORE's Model line is missing)");
            camera.lens = {LensType::Cahvor, {alpha, beta, R.x(), R.y(), R.z()}};
        }
    }
    return {{std::string(), {validated_camera(std::move(camera), source), std::nullopt}}};
}

}  // namespace libcam
