#include "libcam/io/detail/observation_table.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

// One row, as the table wrote it, with where it is for messages ("row 3 (line 5)", "[2]").
struct Row {
    std::string where;
    std::optional<std::string> view;
    std::string camera;
    Vec3 point = Vec3::Zero();
    Vec2 pixel = Vec2::Zero();
};

[[noreturn]] void fail(const std::string& source, const std::string& where, std::string_view column,
                       const std::string& what) {
    throw FileError(source + ": " + where + ": column \"" + std::string(column) + "\": " + what);
}

// ---- CSV ----

// The fields of one line: split at commas outside double quotes, blanks around each
// trimmed, "" inside quotes a quote. Returns nothing for an unclosed quote.
std::optional<std::vector<std::string>> csv_fields(std::string_view line) {
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
            fields.back() += '"';
            ++i;
        } else if (c == '"') {
            quoted = !quoted;
        } else if (c == ',' && !quoted) {
            fields.emplace_back();
        } else {
            fields.back() += c;
        }
    }
    if (quoted) return std::nullopt;
    for (std::string& field : fields) {
        const std::size_t first = field.find_first_not_of(" \t");
        const std::size_t last = field.find_last_not_of(" \t");
        field = first == std::string::npos ? std::string() : field.substr(first, last - first + 1);
    }
    return fields;
}

double csv_number(const std::string& text, const std::string& source, const std::string& where, std::string_view column) {
    std::string_view word = text;
    if (word.starts_with('+')) word.remove_prefix(1);
    double value = 0.0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (word.empty() || end != word.data() + word.size() || error == std::errc::invalid_argument) {
        fail(source, where, column, "expected a number, got " + shown_value(text));
    }
    if (error == std::errc::result_out_of_range || !std::isfinite(value)) {
        fail(source, where, column, "must be finite, got " + shown_value(text));
    }
    return value;
}

struct Columns {
    std::optional<std::size_t> view;
    std::size_t camera = 0, X = 0, Y = 0, Z = 0, x = 0, y = 0;
};

Columns header_columns(const std::vector<std::string>& names, const std::string& source, int line) {
    const auto position = [&](std::string_view name) -> std::optional<std::size_t> {
        const auto found = std::find(names.begin(), names.end(), name);
        if (found == names.end()) return std::nullopt;
        if (std::find(found + 1, names.end(), name) != names.end()) {
            throw FileError(source + ": line " + std::to_string(line) + ": the header names column \"" +
                            std::string(name) + "\" twice");
        }
        return static_cast<std::size_t>(found - names.begin());
    };
    const auto required = [&](std::string_view name) {
        const std::optional<std::size_t> at = position(name);
        if (!at) {
            throw FileError(source + ": line " + std::to_string(line) + ": the header has no column \"" +
                            std::string(name) + "\" (it needs camera, X, Y, Z, x, y and may have view)");
        }
        return *at;
    };
    Columns columns;
    columns.view = position("view");
    columns.camera = required("camera");
    columns.X = required("X");
    columns.Y = required("Y");
    columns.Z = required("Z");
    columns.x = required("x");
    columns.y = required("y");
    return columns;
}

std::vector<Row> csv_rows(std::string_view text, const std::string& source) {
    std::optional<Columns> columns;
    std::size_t width = 0;
    std::vector<Row> rows;
    int line_number = 0;
    for (std::size_t start = 0; start < text.size();) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        std::string_view line = text.substr(start, end - start);
        start = end + 1;
        ++line_number;
        if (line.ends_with('\r')) line.remove_suffix(1);
        if (line.find_first_not_of(" \t") == std::string_view::npos || line.front() == '#') continue;
        const std::optional<std::vector<std::string>> fields = csv_fields(line);
        if (!fields) throw FileError(source + ": line " + std::to_string(line_number) + ": a quote is not closed");
        if (!columns) {
            columns = header_columns(*fields, source, line_number);
            width = fields->size();
            continue;
        }
        Row row;
        row.where = "row " + std::to_string(rows.size() + 1) + " (line " + std::to_string(line_number) + ")";
        if (fields->size() != width) {
            throw FileError(source + ": " + row.where + ": " + std::to_string(fields->size()) +
                            " fields, but the header names " + std::to_string(width) + " columns");
        }
        const auto number = [&](std::size_t at, std::string_view name) { return csv_number((*fields)[at], source, row.where, name); };
        if (columns->view) row.view = (*fields)[*columns->view];
        row.camera = (*fields)[columns->camera];
        if (row.camera.empty()) fail(source, row.where, "camera", "empty");
        row.point = Vec3(number(columns->X, "X"), number(columns->Y, "Y"), number(columns->Z, "Z"));
        row.pixel = Vec2(number(columns->x, "x"), number(columns->y, "y"));
        rows.push_back(std::move(row));
    }
    if (!columns) throw FileError(source + ": empty: expected a header line (view,camera,X,Y,Z,x,y) and rows");
    return rows;
}

// ---- JSON ----

std::vector<Row> json_rows(std::string_view text, const std::string& source) {
    const DocumentNode tree = parse_json_tree(text, source);
    const Field list(tree, "", source);
    if (tree.kind != DocumentNode::Kind::Sequence) {
        list.fail("expected a list of observations ({\"camera\", \"X\", \"Y\", \"Z\", \"x\", \"y\"}), got " + list.shown());
    }
    std::vector<Row> rows;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const Field item = list.item(i);
        if (item.node().kind != DocumentNode::Kind::Map) item.fail("expected an object, got " + item.shown());
        Row row;
        row.where = "[" + std::to_string(i) + "]";
        if (const std::optional<Field> view = item.find({"view"})) {
            if (view->node().kind != DocumentNode::Kind::Scalar) view->fail("expected an image's name, got " + view->shown());
            row.view = view->node().text;
        }
        const Field camera = item.at({"camera"});
        if (camera.node().kind != DocumentNode::Kind::Scalar || camera.node().text.empty()) {
            camera.fail("expected a camera's name or position, got " + camera.shown());
        }
        row.camera = camera.node().text;
        row.point = Vec3(item.at({"X"}).number(), item.at({"Y"}).number(), item.at({"Z"}).number());
        row.pixel = Vec2(item.at({"x"}).number(), item.at({"y"}).number());
        rows.push_back(std::move(row));
    }
    return rows;
}

bool is_json(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    return extension == ".json";
}

// The cameras the rows name, each once, with the camera file's pose taken off: each view
// carries its camera's pose.
struct UsedCameras {
    std::vector<ObservedCamera> cameras;
    std::vector<Pose> poses;
    std::map<std::size_t, int> index_of;  // position in the camera file -> index in `cameras`
};

int used_camera(UsedCameras& used, const CameraSet& file_cameras, const std::string& camera_source, const Row& row,
                const std::string& source) {
    std::size_t position = 0;
    try {
        position = static_cast<std::size_t>(&select_camera(file_cameras, row.camera, camera_source) - file_cameras.cameras.data());
    } catch (const InvalidArgument& error) {
        fail(source, row.where, "camera", shown_value(row.camera) + " is not a camera of " + error.what());
    }
    const auto [found, added] = used.index_of.emplace(position, static_cast<int>(used.cameras.size()));
    if (added) {
        const NamedCamera& named = file_cameras.cameras[position];
        Camera camera = named.file.camera;
        used.poses.push_back(camera.pose);
        camera.pose = Pose{};
        used.cameras.push_back({named.name.empty() ? std::to_string(position) : named.name, camera});
    }
    return found->second;
}

}  // namespace

ObservationSet read_observation_table(const std::filesystem::path& table, const std::filesystem::path& camera_file) {
    const std::string source = table.string();
    const std::string text = read_text_file(table, kReconstructionLimit);
    const std::vector<Row> rows = is_json(table) ? json_rows(text, source) : csv_rows(text, source);
    if (rows.empty()) throw FileError(source + ": no observations in it");
    const CameraSet file_cameras = read_camera_set(camera_file);

    ObservationSet set;
    set.tool = ObservationTool::Table;
    set.source = source;
    UsedCameras used;
    std::map<std::string, int> view_index;  // a view's name -> index in set.views
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Row& row = rows[i];
        const int camera = used_camera(used, file_cameras, camera_file.string(), row, source);
        const std::string view_name = row.view.value_or(used.cameras[static_cast<std::size_t>(camera)].name);
        const auto [found, added] = view_index.emplace(view_name, static_cast<int>(set.views.size()));
        if (added) {
            set.views.push_back({view_name, camera, used.poses[static_cast<std::size_t>(camera)]});
        } else if (const int first = set.views[static_cast<std::size_t>(found->second)].camera; first != camera) {
            fail(source, row.where, "camera",
                 shown_value(row.camera) + ", but view " + shown_value(view_name) + " was taken by camera " +
                     shown_value(used.cameras[static_cast<std::size_t>(first)].name) +
                     " (a view is one image of one camera)");
        }
        set.points.push_back(row.point);
        set.point_ids.push_back(static_cast<std::int64_t>(i + 1));
        set.observations.push_back({found->second, static_cast<int>(i), row.pixel});
    }
    set.cameras = std::move(used.cameras);
    return set;
}

}  // namespace libcam
