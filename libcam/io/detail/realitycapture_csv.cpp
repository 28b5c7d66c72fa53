#include "libcam/io/detail/realitycapture_csv.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <optional>
#include <string>

#include "libcam/error.hpp"
#include "libcam/io/detail/realitycapture_format.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

// The columns libcam reads; the first eight are required.
constexpr std::array<std::string_view, 16> kColumns = {"name", "x",  "y",  "alt", "heading", "pitch", "roll", "f",
                                                       "px",   "py", "k1", "k2",  "k3",      "k4",    "t1",   "t2"};
constexpr std::size_t kRequired = 8;

std::string where_of(const std::string& source, int line) { return source + ": line " + std::to_string(line); }

std::string_view trimmed(std::string_view text) {
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    const auto last = text.find_last_not_of(" \t\r");
    return text.substr(first, last - first + 1);
}

std::vector<std::string_view> fields_of(std::string_view line) {
    std::vector<std::string_view> fields;
    std::size_t at = 0;
    while (true) {
        const auto comma = line.find(',', at);
        const std::size_t length = comma == std::string_view::npos ? std::string_view::npos : comma - at;
        fields.push_back(trimmed(line.substr(at, length)));
        if (comma == std::string_view::npos) return fields;
        at = comma + 1;
    }
}

// Where each column libcam reads is in a line, from the header's names.
struct Header {
    std::map<std::string_view, std::size_t> index;
    std::size_t width = 0;
};

Header parse_header(std::string_view line, const std::string& where) {
    std::string_view names = line;
    names.remove_prefix(1);  // the '#'
    Header header;
    const std::vector<std::string_view> fields = fields_of(names);
    header.width = fields.size();
    for (std::size_t i = 0; i < fields.size(); ++i) {
        const auto known = std::find(kColumns.begin(), kColumns.end(), fields[i]);
        if (known == kColumns.end()) {
            throw FileError(where + ": column " + shown_value(fields[i]) +
                            " is not one libcam reads (name, x, y, alt, heading, pitch, roll, f, px, py, k1..k4, t1, "
                            "t2)");
        }
        if (!header.index.emplace(*known, i).second) {
            throw FileError(where + ": column " + shown_value(fields[i]) + " twice");
        }
    }
    for (std::size_t i = 0; i < kRequired; ++i) {
        if (!header.index.contains(kColumns[i])) {
            throw FileError(where + ": the header has no column " + shown_value(kColumns[i]));
        }
    }
    return header;
}

struct Row {
    int line = 0;
    std::string name;
    std::map<std::string_view, double> values;

    double operator[](std::string_view column) const {
        const auto found = values.find(column);
        return found == values.end() ? 0.0 : found->second;
    }
};

Row parse_row(std::string_view line, int number, const Header& header, const std::string& source) {
    const std::string where = where_of(source, number);
    const std::vector<std::string_view> fields = fields_of(line);
    if (fields.size() != header.width) {
        throw FileError(where + ": expected " + std::to_string(header.width) + " values as the header names, got " +
                        std::to_string(fields.size()));
    }
    Row row;
    row.line = number;
    for (const auto& [column, index] : header.index) {
        const std::string_view text = fields[index];
        if (column == "name") {
            if (text.empty()) throw FileError(where + ": name: empty");
            row.name = std::string(text);
            continue;
        }
        double value = 0.0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
            throw FileError(where + ": " + std::string(column) + ": must be a finite number, got " + shown_value(text));
        }
        row.values[column] = value;
    }
    return row;
}

// A geographic export: several cameras whose x and y could be longitude and latitude, close
// together in them and far apart in alt's metres (the header says why).
void refuse_geographic(const std::vector<Row>& rows, const std::string& source) {
    if (rows.size() < 2) return;
    double x_low = rows[0]["x"], x_high = x_low, y_low = rows[0]["y"], y_high = y_low, alt_most = 0.0;
    for (const Row& row : rows) {
        if (std::abs(row["x"]) > 180.0 || std::abs(row["y"]) > 90.0) return;
        x_low = std::min(x_low, row["x"]), x_high = std::max(x_high, row["x"]);
        y_low = std::min(y_low, row["y"]), y_high = std::max(y_high, row["y"]);
        alt_most = std::max(alt_most, std::abs(row["alt"]));
    }
    const double spread = std::max(x_high - x_low, y_high - y_low);
    // Cameras at one x and y (a vertical rig) are not a sign of degrees.
    if (spread > 0.0 && spread < 0.01 && alt_most > 1000.0 * spread) {
        char within[32];
        // A difference of coordinates: its digits past the third are noise.
        std::snprintf(within, sizeof within, "%.3g", spread);
        throw NotRepresentable(source + ": x, y: the cameras lie within " + std::string(within) +
                               " of each other in x and y while alt reaches " + format_number(alt_most) +
                               ": longitude and latitude in degrees (an export in a geographic coordinate system), "
                               "which libcam cannot place in a metric world; export in a projected or local one");
    }
}

Camera camera_of(const Row& row, ImageSize size, const std::string& source) {
    const std::string where = where_of(source, row.line);
    if (row["py"] != 0.0) {
        throw NotRepresentable(where + ": py = " + format_number(row["py"]) +
                               ": the sign of RealityCapture's CSV py is not documented and its readers disagree; "
                               "read the same calibration from its XMP sidecars (Export > Registration > Metadata (XMP))");
    }
    if (!(row["f"] > 0.0)) throw FileError(where + ": f: must be > 0, got " + format_number(row["f"]));
    Camera camera;
    camera.size = size;
    camera.intrinsics = realitycapture_intrinsics(row["f"], 1.0, row["px"], 0.0, size);
    camera.lens = realitycapture_brown_lens(row["k1"], row["k2"], row["k3"], row["k4"], row["t1"], row["t2"]);
    camera.pose = Pose::from_centre(realitycapture_rotation(row["heading"], row["pitch"], row["roll"]),
                                    Vec3(row["x"], row["y"], row["alt"]));
    return validated_camera(camera, where);
}

}  // namespace

Mat3 realitycapture_rotation(double heading_deg, double pitch_deg, double roll_deg) {
    constexpr double kDegree = std::numbers::pi / 180.0;
    const Mat3 camera_to_world = (Eigen::AngleAxisd(-heading_deg * kDegree, Vec3::UnitZ()) *
                                  Eigen::AngleAxisd(pitch_deg * kDegree, Vec3::UnitX()) *
                                  Eigen::AngleAxisd(roll_deg * kDegree, Vec3::UnitY()))
                                     .toRotationMatrix() *
                                 Vec3(1.0, -1.0, -1.0).asDiagonal();
    return camera_to_world.transpose();
}

std::vector<NamedCamera> read_realitycapture_csv(std::string_view text, const ReadContext& context) {
    std::optional<Header> header;
    std::vector<Row> rows;
    int number = 0;
    std::size_t at = 0;
    while (at < text.size()) {
        auto end = text.find('\n', at);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = trimmed(text.substr(at, end - at));
        at = end + 1;
        ++number;
        if (line.empty() || line.starts_with("#cameras")) continue;
        if (!header) {
            if (!line.starts_with('#')) {
                throw FileError(where_of(context.source, number) + ": expected the header ('#name,x,y,alt,heading,"
                                "pitch,roll,f,...') before the cameras");
            }
            header = parse_header(line, where_of(context.source, number));
            continue;
        }
        if (line.starts_with('#')) continue;
        rows.push_back(parse_row(line, number, *header, context.source));
    }
    if (!header) throw FileError(context.source + ": has no header ('#name,x,y,alt,heading,pitch,roll,f,...')");
    if (rows.empty()) throw FileError(context.source + ": has no camera under its header");
    if (!context.options.size) {
        throw FileError(context.source + ": RealityCapture's CSV does not hold the image size, which its focal length "
                                         "and principal point are relative to: give it (--image-size WxH)");
    }
    refuse_geographic(rows, context.source);
    std::vector<NamedCamera> cameras;
    cameras.reserve(rows.size());
    for (const Row& row : rows) {
        cameras.push_back({row.name, {camera_of(row, *context.options.size, context.source), std::nullopt}});
    }
    return cameras;
}

}  // namespace libcam
