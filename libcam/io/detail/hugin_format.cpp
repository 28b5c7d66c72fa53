#include "libcam/io/detail/hugin_format.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <string>

#include "libcam/error.hpp"
#include "libcam/geometry/image_size.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

// One image line's values by their names (one letter, or TrX TrY TrZ), as written: a
// number, or "=N".
struct ImageLine {
    int line = 0;
    std::map<std::string, std::string, std::less<>> values;
    std::string name;
};

// The lens variables an image may take from another ("v=0").
constexpr std::string_view kLinkable = "vabcdegt";
// The one-letter variables libcam reads: the lens's, and the orientation's y p r.
constexpr std::string_view kRead = "whfvabcdegtrpy";
// The camera's translation (Hugin's mosaic mode).
constexpr std::array<std::string_view, 3> kTranslation = {"TrX", "TrY", "TrZ"};

std::string where_of(const std::string& source, int line) { return source + ": line " + std::to_string(line); }

ImageLine parse_image_line(std::string_view text, int line, const std::string& source) {
    ImageLine out;
    out.line = line;
    std::size_t at = 1;  // past "i"
    while (at < text.size()) {
        while (at < text.size() && (text[at] == ' ' || text[at] == '\t' || text[at] == '\r')) ++at;
        if (at >= text.size()) break;
        if (text.substr(at, 2) == "n\"") {
            const auto close = text.find('"', at + 2);
            if (close == std::string_view::npos) throw FileError(where_of(source, line) + ": n\": the name has no closing quote");
            out.name = std::string(text.substr(at + 2, close - at - 2));
            at = close + 1;
            continue;
        }
        auto end = text.find_first_of(" \t\r", at);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view token = text.substr(at, end - at);
        at = end;
        // One letter then its value: a variable libcam reads; or the translation's TrX
        // TrY TrZ. The other longer names (Ra, Eev, Vm, Tpy, ...) are photometric
        // variables or the mosaic plane's, not the camera's.
        if (token.size() >= 2 && kRead.find(token[0]) != std::string_view::npos &&
            !std::isalpha(static_cast<unsigned char>(token[1]))) {
            out.values[std::string(1, token[0])] = std::string(token.substr(1));
        }
        for (const std::string_view name : kTranslation) {
            if (token.size() > name.size() && token.starts_with(name)) {
                out.values[std::string(name)] = std::string(token.substr(name.size()));
            }
        }
    }
    return out;
}

double number(const std::string& text, const std::string& where, std::string_view key) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
        throw FileError(where + ": " + std::string(key) + ": must be a finite number, got " + shown_value(text));
    }
    return value;
}

// The value of `key` for image `index`, following "=N" to the image it names (once: Hugin
// writes links to the image that holds the value).
double value_of(const std::vector<ImageLine>& images, std::size_t index, std::string_view key, std::optional<double> fallback,
                const std::string& source) {
    const ImageLine& image = images[index];
    const std::string where = where_of(source, image.line);
    const auto found = image.values.find(key);
    if (found == image.values.end()) {
        if (fallback) return *fallback;
        throw FileError(where + ": the image line has no " + std::string(key));
    }
    const std::string& text = found->second;
    if (!text.empty() && text.front() == '=') {
        if (key.size() != 1 || kLinkable.find(key[0]) == std::string_view::npos) {
            throw FileError(where + ": " + std::string(key) + ": cannot be linked, got " + shown_value(text));
        }
        const double target = number(text.substr(1), where, key);
        if (!(target >= 0.0 && target < static_cast<double>(images.size())) || target != std::floor(target) ||
            static_cast<std::size_t>(target) == index) {
            throw FileError(where + ": " + std::string(key) + ": links to no other image, got " + shown_value(text));
        }
        const ImageLine& linked = images[static_cast<std::size_t>(target)];
        const auto value = linked.values.find(key);
        if (value == linked.values.end()) {
            if (fallback) return *fallback;
            throw FileError(where_of(source, linked.line) + ": the image line has no " + std::string(key));
        }
        if (!value->second.empty() && value->second.front() == '=') {
            throw FileError(where + ": " + std::string(key) + ": links to image " + text.substr(1) +
                            ", which links on again");
        }
        return number(value->second, where_of(source, linked.line), key);
    }
    return number(text, where, key);
}

long side(double value, const std::string& where, char key) {
    if (!(value >= 1.0 && value <= static_cast<double>(kMaxImageSide)) || value != std::floor(value)) {
        throw FileError(where + ": " + std::string(1, key) + ": must be a whole number of pixels in [1, " +
                        std::to_string(kMaxImageSide) + "], got " + format_number(value));
    }
    return static_cast<long>(value);
}

// The projection's focal length in pixels from the field of view across the width, and
// its libcam model (the header's table).
struct Projection {
    LensType type;
    double focal;
    bool distorted;  // whether a b c have a libcam model on it
};

Projection projection(int f, double width, double v_deg, const std::string& where) {
    const double v = v_deg * std::numbers::pi / 180.0;
    const auto need = [&](double most) {
        if (!(v_deg > 0.0 && v_deg < most)) {
            throw FileError(where + ": v: the field of view must be in (0, " + format_number(most) + ") degrees for f" +
                            std::to_string(f) + ", got " + format_number(v_deg));
        }
    };
    switch (f) {
        case 0: need(180.0); return {LensType::OpenCv4, width / 2.0 / std::tan(v / 2.0), true};
        case 1: need(360.0); return {LensType::Cylindrical, width / v, false};
        case 2:
        case 3: need(360.0); return {LensType::Fisheye, width / v, true};
        case 4: need(360.0); return {LensType::Lonlat, width / v, false};
        case 10: need(360.0); return {LensType::Stereographic, width / 2.0 / (2.0 * std::tan(v / 4.0)), true};
        case 21: need(360.0); return {LensType::Equisolid, width / 2.0 / (2.0 * std::sin(v / 4.0)), true};
        default:
            throw NotRepresentable(where + ": f" + std::to_string(f) + ": projection has no libcam model (libcam reads "
                                   "f0 rectilinear, f1 cylindrical, f2 and f3 fisheye, f4 equirectangular, f10 "
                                   "stereographic, f21 equisolid)");
    }
}

// The image's pose in the panorama's world (the header's axes): camera to world
// Ry(yaw) Rx(pitch) Rz(roll), its centre Hugin's translation with TrZ towards -z.
Pose pose_of(double yaw_deg, double pitch_deg, double roll_deg, const Vec3& translation) {
    constexpr double kDegree = std::numbers::pi / 180.0;
    const Mat3 camera_to_world = (Eigen::AngleAxisd(yaw_deg * kDegree, Vec3::UnitY()) *
                                  Eigen::AngleAxisd(pitch_deg * kDegree, Vec3::UnitX()) *
                                  Eigen::AngleAxisd(roll_deg * kDegree, Vec3::UnitZ()))
                                     .toRotationMatrix();
    return Pose::from_centre(camera_to_world.transpose(), Vec3(translation.x(), translation.y(), -translation.z()));
}

NamedCamera image_camera(const std::vector<ImageLine>& images, std::size_t index, const std::string& source) {
    const std::string where = where_of(source, images[index].line);
    const auto get = [&](std::string_view key, std::optional<double> fallback = std::nullopt) {
        return value_of(images, index, key, fallback, source);
    };
    Camera camera;
    camera.size = {side(get("w"), where, 'w'), side(get("h"), where, 'h')};
    const double f = get("f");
    if (f != std::floor(f) || !(f >= 0.0 && f < 100.0)) throw FileError(where + ": f: must be a projection number, got " + format_number(f));
    const Projection chosen = projection(static_cast<int>(f), static_cast<double>(camera.size.width), get("v"), where);
    const double a = get("a", 0.0), b = get("b", 0.0), c = get("c", 0.0);
    if (get("g", 0.0) != 0.0 || get("t", 0.0) != 0.0) {
        throw NotRepresentable(where + ": g and t (shear) have no libcam model, got g" + format_number(get("g", 0.0)) +
                               " t" + format_number(get("t", 0.0)));
    }
    const double scale = 1.0 - a - b - c;
    if (!(scale > 0.0)) throw FileError(where + ": 1 - a - b - c must be > 0, got " + format_number(scale));
    const double half_short_side = std::min(camera.size.width, camera.size.height) / 2.0;
    const double s = chosen.focal / half_short_side;
    const double a_ = a * s * s * s / scale, b_ = b * s * s / scale, c_ = c * s / scale;
    const bool odd = a != 0.0 || c != 0.0;
    if (!chosen.distorted && (odd || b != 0.0)) {
        throw NotRepresentable(where + ": a b c on a " + std::string(lens_info(chosen.type).name) +
                               " projection have no libcam model (it has no coefficients)");
    }
    // PanoTools distorts the source image's own projection: a fisheye's a b c act on its
    // projected radius (lens/fisheye_radial.hpp), as a rectilinear lens's on r = |(x/z, y/z)|.
    if (chosen.type == LensType::OpenCv4) {
        camera.lens = odd ? Lens{LensType::Ptlens, {a_, b_, c_}} : simplest_equal_lens({LensType::OpenCv4, {b_, 0.0, 0.0, 0.0}});
    } else if (chosen.type == LensType::Fisheye) {
        camera.lens = simplest_equal_lens({LensType::EquidistantRadial, {a_, b_, c_, 0.0}});
    } else if (chosen.type == LensType::Equisolid) {
        camera.lens = simplest_equal_lens({LensType::EquisolidRadial, {a_, b_, c_, 0.0}});
    } else if (chosen.type == LensType::Stereographic) {
        camera.lens = simplest_equal_lens({LensType::StereographicRadial, {a_, b_, c_, 0.0}});
    } else {
        camera.lens = {chosen.type, {}};
    }
    const double focal = chosen.focal * scale;
    camera.intrinsics = {focal, focal, (camera.size.width - 1.0) / 2.0 + get("d", 0.0),
                         (camera.size.height - 1.0) / 2.0 + get("e", 0.0), 0.0};
    camera.pose = pose_of(get("y", 0.0), get("p", 0.0), get("r", 0.0),
                          Vec3(get("TrX", 0.0), get("TrY", 0.0), get("TrZ", 0.0)));
    return {images[index].name, {validated_camera(camera, where), std::nullopt}};
}

}  // namespace

std::vector<NamedCamera> read_hugin_pto(std::string_view text, const ReadContext& context) {
    std::vector<ImageLine> images;
    int line = 0;
    std::size_t at = 0;
    while (at <= text.size()) {
        auto end = text.find('\n', at);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view row = text.substr(at, end - at);
        ++line;
        if (row.size() >= 2 && row[0] == 'i' && (row[1] == ' ' || row[1] == '\t')) {
            images.push_back(parse_image_line(row, line, context.source));
        }
        at = end + 1;
    }
    if (images.empty()) throw FileError(context.source + ": has no image line ('i ...')");
    std::vector<NamedCamera> cameras;
    for (std::size_t i = 0; i < images.size(); ++i) cameras.push_back(image_camera(images, i, context.source));
    return cameras;
}

}  // namespace libcam
