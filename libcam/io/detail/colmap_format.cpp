#include "libcam/io/detail/colmap_format.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>

#include "libcam/convert/colmap_models.hpp"
#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

namespace {

// A camera from a model's parameters (COLMAP's table: convert/colmap_models.hpp), checked
// as a file's camera.
Camera camera_from_parameters(const ColmapModel& model, ImageSize size, const std::vector<double>& parameters,
                              const std::string& where) {
    try {
        return camera_from_colmap(model.name, parameters, size);
    } catch (const InvalidArgument& error) {
        throw FileError(where + ": " + error.what());
    }
}

// COLMAP's pose: the quaternion (w first) and translation of world-to-camera.
Pose pose_from(const Eigen::Vector4d& q_wxyz, const Vec3& t, const std::string& where) {
    const Eigen::Quaterniond q(q_wxyz(0), q_wxyz(1), q_wxyz(2), q_wxyz(3));
    if (!(std::abs(q.norm() - 1.0) <= 1e-6)) {
        throw FileError(where + ": the quaternion's norm is " + format_number(q.norm()) + ", not 1");
    }
    Pose pose{q.normalized().toRotationMatrix(), t};
    try {
        pose.validate("pose");
    } catch (const InvalidArgument& error) {
        throw FileError(where + ": " + error.what());
    }
    return pose;
}

// ---- text --------------------------------------------------------------------------------

// The words of one line of a COLMAP text file, with the line's number for messages.
class TextLine {
public:
    TextLine(std::string_view line, int number, const std::string& source) : number_(number), source_(source) {
        std::size_t at = 0;
        while (true) {
            at = line.find_first_not_of(" \t\r", at);
            if (at == std::string_view::npos) break;
            const std::size_t end = std::min(line.find_first_of(" \t\r", at), line.size());
            std::string_view word = line.substr(at, end - at);
            at = end;
            // kapture writes ", " between fields; COLMAP's own reader (std::stold, std::stoul
            // on each space-separated word) ignores the comma, and so does this one.
            if (word.back() == ',') word.remove_suffix(1);
            if (!word.empty()) words_.push_back(word);
        }
    }

    std::size_t size() const { return words_.size(); }
    std::string_view word(std::size_t i) const { return words_[i]; }
    std::string where() const { return source_ + ": line " + std::to_string(number_); }

    [[noreturn]] void fail(const std::string& field, const std::string& what) const {
        throw FileError(where() + ": " + field + ": " + what);
    }

    double number(std::size_t i, const std::string& field) const {
        const std::string_view text = words_[i];
        double value = 0.0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
            fail(field, "expected a finite number, got " + shown_value(text));
        }
        return value;
    }

    std::uint64_t integer(std::size_t i, const std::string& field, std::uint64_t min, std::uint64_t max) const {
        const std::string_view text = words_[i];
        std::uint64_t value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error != std::errc() || end != text.data() + text.size() || value < min || value > max) {
            fail(field, "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                            "], got " + shown_value(text));
        }
        return value;
    }

private:
    std::vector<std::string_view> words_;
    int number_;
    const std::string& source_;
};

constexpr std::uint64_t kMaxId = 0xFFFFFFFFu;  // COLMAP's ids are 32-bit

// Calls `each(line, following, its number)` with every line that is not blank or a
// comment and the raw line after it (empty at the end of the file); `each` returns whether
// that following line belongs to it (images.txt's line of points) and is to be skipped.
template <class Each>
void for_each_line(std::string_view text, const std::string& source, Each&& each) {
    std::size_t at = 0;
    int number = 0;
    const auto next_line = [&] {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        const std::string_view line = text.substr(at, end - at);
        at = end + 1;
        ++number;
        return line;
    };
    while (at < text.size()) {
        const std::string_view line = next_line();
        const auto start = line.find_first_not_of(" \t\r");
        if (start == std::string_view::npos || line[start] == '#') continue;
        const int line_number = number;
        const std::string_view following =
            at < text.size() ? text.substr(at, std::min(text.find('\n', at), text.size()) - at) : std::string_view();
        if (each(TextLine(line, line_number, source), following, line_number + 1) && at < text.size()) next_line();
    }
}

// The words of a line of numbers (POINTS2D), separated by spaces, tabs, '\r' or commas,
// without TextLine's vector of words: these lines hold most of a model.
class NumberWords {
public:
    explicit NumberWords(std::string_view line) : line_(line) {}

    bool next(std::string_view& word) {
        constexpr std::string_view kSeparators = " \t\r,";
        at_ = line_.find_first_not_of(kSeparators, at_);
        if (at_ == std::string_view::npos) return false;
        const std::size_t end = std::min(line_.find_first_of(kSeparators, at_), line_.size());
        word = line_.substr(at_, end - at_);
        at_ = end;
        return true;
    }

private:
    std::string_view line_;
    std::size_t at_ = 0;
};

bool parse_double(std::string_view word, double& value) {
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    return error == std::errc() && end == word.data() + word.size() && std::isfinite(value);
}

const ColmapModel& model_named(const TextLine& line) {
    const std::string_view name = line.word(1);
    if (const ColmapModel* model = colmap_model(name)) return *model;
    line.fail("MODEL", "must be one of " + colmap_model_names() + ", got " + shown_value(name));
}

std::vector<ColmapCameraRecord> read_cameras_text(std::string_view text, const std::string& source) {
    std::vector<ColmapCameraRecord> cameras;
    for_each_line(text, source, [&](const TextLine& line, std::string_view, int) {
        if (line.size() < 4) line.fail("CAMERA_ID MODEL WIDTH HEIGHT PARAMS", "expected at least 4 words");
        const std::uint64_t id = line.integer(0, "CAMERA_ID", 0, kMaxId);
        const ColmapModel& model = model_named(line);
        const ImageSize size{static_cast<long>(line.integer(2, "WIDTH", 1, kMaxImageSide)),
                             static_cast<long>(line.integer(3, "HEIGHT", 1, kMaxImageSide))};
        const std::size_t count = static_cast<std::size_t>(model.num_params());
        if (line.size() != 4 + count) {
            line.fail("PARAMS", std::string(model.name) + " has " + std::to_string(count) + " parameters, got " +
                                    std::to_string(line.size() - 4));
        }
        std::vector<double> parameters;
        for (std::size_t i = 0; i < count; ++i) parameters.push_back(line.number(4 + i, "PARAMS[" + std::to_string(i) + "]"));
        const std::string where = line.where() + ": camera " + std::to_string(id);
        cameras.push_back({id, validated_camera(camera_from_parameters(model, size, parameters, where), where), model.name});
        return false;
    });
    return cameras;
}

// An image's line of POINTS2D: X Y POINT3D_ID triples, -1 for a 2-D point of no 3-D point.
std::vector<ColmapPoint2D> points2d_from_text(std::string_view line, int number, const std::string& source) {
    const auto fail = [&](std::size_t index, const char* field, const std::string& what) {
        throw FileError(source + ": line " + std::to_string(number) + ": POINTS2D[" + std::to_string(index) + "]: " +
                        field + ": " + what);
    };
    std::vector<ColmapPoint2D> points;
    points.reserve(line.size() / 24);
    NumberWords words(line);
    std::string_view word;
    while (words.next(word)) {
        const std::size_t index = points.size();
        ColmapPoint2D point{};
        if (!parse_double(word, point.x)) fail(index, "X", "expected a finite number, got " + shown_value(word));
        if (!words.next(word)) fail(index, "Y", "the line ends before it");
        if (!parse_double(word, point.y)) fail(index, "Y", "expected a finite number, got " + shown_value(word));
        if (!words.next(word)) fail(index, "POINT3D_ID", "the line ends before it");
        if (word == "-1") {
            point.point3d_id = kColmapNoPoint3D;
        } else {
            const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), point.point3d_id);
            if (error != std::errc() || end != word.data() + word.size() || point.point3d_id == kColmapNoPoint3D) {
                fail(index, "POINT3D_ID", "expected -1 or a point's id, got " + shown_value(word));
            }
        }
        points.push_back(point);
    }
    return points;
}

std::vector<ColmapImage> read_images_text(std::string_view text, const std::string& source, bool with_points) {
    std::vector<ColmapImage> images;
    for_each_line(text, source, [&](const TextLine& line, std::string_view following, int following_number) {
        if (line.size() < 10) {
            line.fail("IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME", "expected 10 words, got " + std::to_string(line.size()));
        }
        ColmapImage image;
        image.id = line.integer(0, "IMAGE_ID", 0, kMaxId);
        const char* const kNames[] = {"QW", "QX", "QY", "QZ", "TX", "TY", "TZ"};
        double values[7];
        for (std::size_t i = 0; i < 7; ++i) values[i] = line.number(1 + i, kNames[i]);
        image.camera_id = line.integer(8, "CAMERA_ID", 0, kMaxId);
        // The name is the rest of the line (COLMAP 3.8 stops at a space; later versions do not).
        const std::string_view first = line.word(9);
        const std::string_view last = line.word(line.size() - 1);
        image.name = std::string(first.data(), static_cast<std::size_t>(last.data() + last.size() - first.data()));
        image.where = line.where() + ": image " + std::to_string(image.id);
        image.pose = pose_from({values[0], values[1], values[2], values[3]}, {values[4], values[5], values[6]}, image.where);
        // The next line holds its 2-D points; where the file ends first, it has none (COLMAP
        // drops such an image; its own writer never ends so).
        if (with_points) image.points = points2d_from_text(following, following_number, source);
        images.push_back(std::move(image));
        return true;
    });
    return images;
}

// ---- binary ------------------------------------------------------------------------------

// Little-endian records of a .bin file, each read checked against the bytes left.
class BinaryReader {
public:
    BinaryReader(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}

    template <class T>
    T read(const std::string& what) {
        T value;
        need(sizeof(T), what);
        std::memcpy(&value, bytes_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return value;
    }

    // A count of records of at least `record_bytes` each, no more than the bytes left hold.
    std::uint64_t count(const std::string& what, std::size_t record_bytes) {
        const auto n = read<std::uint64_t>(what);
        if (n > remaining() / record_bytes) {
            fail(what + " is " + std::to_string(n) + ", " + more_than_left(record_bytes));
        }
        return n;
    }

    std::string text(const std::string& what) {
        const std::size_t end = bytes_.find('\0', at_);
        if (end == std::string_view::npos) fail(what + ": the file ends inside it");
        std::string value(bytes_.substr(at_, end - at_));
        at_ = end + 1;
        return value;
    }

    // The next `bytes` bytes, for a block of records read with load().
    const char* take(std::uint64_t bytes, const std::string& what) {
        need(bytes, what);
        const char* block = bytes_.data() + at_;
        at_ += static_cast<std::size_t>(bytes);
        return block;
    }

    std::size_t remaining() const { return bytes_.size() - at_; }
    // "more than the 100 bytes left of the file's 124 can hold (at least 24 bytes each)".
    std::string more_than_left(std::size_t record_bytes) const {
        return "more than the " + std::to_string(remaining()) + " bytes left of the file's " +
               std::to_string(bytes_.size()) + " can hold (at least " + std::to_string(record_bytes) + " bytes each)";
    }
    std::string where() const { return source_ + ": byte " + std::to_string(at_); }
    [[noreturn]] void fail(const std::string& what) const { throw FileError(where() + ": " + what); }

private:
    void need(std::uint64_t bytes, const std::string& what) const {
        if (bytes > remaining()) fail(what + ": the file ends inside it");
    }

    std::string_view bytes_;
    const std::string& source_;
    std::size_t at_ = 0;
};

static_assert(std::endian::native == std::endian::little, "COLMAP's .bin files are little-endian");

std::vector<ColmapCameraRecord> read_cameras_binary(std::string_view bytes, const std::string& source) {
    BinaryReader in(bytes, source);
    // The fewest parameters a model takes (EQUIRECTANGULAR's two: w, h).
    int fewest_params = std::numeric_limits<int>::max();
    for (const ColmapModel& model : colmap_models()) fewest_params = std::min(fewest_params, model.num_params());
    const std::size_t smallest_record = 4 + 4 + 8 + 8 + 8 * static_cast<std::size_t>(fewest_params);
    const std::uint64_t count = in.count("the number of cameras", smallest_record);
    std::vector<ColmapCameraRecord> cameras;
    for (std::uint64_t i = 0; i < count; ++i) {
        const std::string what = "camera " + std::to_string(i);
        const std::string where = in.where() + ": " + what;
        const auto id = in.read<std::uint32_t>(what + " id");
        const auto model_id = in.read<std::int32_t>(what + " model");
        const ColmapModel* found = colmap_model_by_id(model_id);
        if (found == nullptr) {
            throw FileError(where + ": model id " + std::to_string(model_id) + " is not one of COLMAP's models that libcam holds (" +
                            colmap_model_ids() + ")");
        }
        const auto width = in.read<std::uint64_t>(what + " width");
        const auto height = in.read<std::uint64_t>(what + " height");
        for (const std::uint64_t side : {width, height}) {
            if (side < 1 || side > static_cast<std::uint64_t>(kMaxImageSide)) {
                throw FileError(where + ": image side " + std::to_string(side) + " is not in [1, " +
                                std::to_string(kMaxImageSide) + "]");
            }
        }
        std::vector<double> parameters;
        for (int k = 0; k < found->num_params(); ++k) {
            const auto value = in.read<double>(what + " parameter " + std::to_string(k));
            if (!std::isfinite(value)) {
                throw FileError(where + ": parameter " + std::to_string(k) + " is " + format_number(value));
            }
            parameters.push_back(value);
        }
        const ImageSize size{static_cast<long>(width), static_cast<long>(height)};
        cameras.push_back({id, validated_camera(camera_from_parameters(*found, size, parameters, where), where), found->name});
    }
    if (in.remaining() != 0) in.fail("bytes after the last camera");
    return cameras;
}

// A little-endian value at `at`, which then moves past it.
template <class T>
T load(const char*& at) {
    T value;
    std::memcpy(&value, at, sizeof(T));
    at += sizeof(T);
    return value;
}

std::vector<ColmapImage> read_images_binary(std::string_view bytes, const std::string& source, bool with_points) {
    BinaryReader in(bytes, source);
    constexpr std::size_t kSmallestRecord = 4 + 7 * 8 + 4 + 1 + 8;
    const std::uint64_t count = in.count("the number of images", kSmallestRecord);
    std::vector<ColmapImage> images;
    images.reserve(static_cast<std::size_t>(count));
    for (std::uint64_t i = 0; i < count; ++i) {
        const std::string what = "image " + std::to_string(i);
        const std::string at = in.where();
        ColmapImage image;
        image.id = in.read<std::uint32_t>(what + " id");
        image.where = at + ": image " + std::to_string(image.id);
        double values[7];
        for (double& value : values) {
            value = in.read<double>(what + " pose");
            if (!std::isfinite(value)) throw FileError(image.where + ": a pose number is " + format_number(value));
        }
        image.camera_id = in.read<std::uint32_t>(what + " camera id");
        image.name = in.text(what + " name");
        const std::uint64_t points = in.count(what + " number of points", 24);
        const char* block = in.take(points * 24, what + " points");
        if (with_points) {
            image.points.resize(static_cast<std::size_t>(points));
            for (std::size_t k = 0; k < image.points.size(); ++k) {
                ColmapPoint2D& point = image.points[k];
                point.x = load<double>(block);
                point.y = load<double>(block);
                point.point3d_id = load<std::uint64_t>(block);
                if (!std::isfinite(point.x) || !std::isfinite(point.y)) {
                    throw FileError(image.where + ": POINTS2D[" + std::to_string(k) + "]: the pixel (" +
                                    format_number(point.x) + ", " + format_number(point.y) + ") is not finite");
                }
            }
        }
        image.pose = pose_from({values[0], values[1], values[2], values[3]}, {values[4], values[5], values[6]}, image.where);
        images.push_back(std::move(image));
    }
    if (in.remaining() != 0) in.fail("bytes after the last image");
    return images;
}

// ---- points3D ----------------------------------------------------------------------------

ColmapPoints3D read_points3d_text(std::string_view text, const std::string& source) {
    ColmapPoints3D points;
    for_each_line(text, source, [&](const TextLine& line, std::string_view, int) {
        if (line.size() < 8) {
            line.fail("POINT3D_ID X Y Z R G B ERROR TRACK", "expected at least 8 words, got " + std::to_string(line.size()));
        }
        if ((line.size() - 8) % 2 != 0) line.fail("TRACK", "expected (IMAGE_ID, POINT2D_IDX) pairs, got an odd count");
        points.ids.push_back(line.integer(0, "POINT3D_ID", 0, kColmapNoPoint3D - 1));
        points.xyz.emplace_back(line.number(1, "X"), line.number(2, "Y"), line.number(3, "Z"));
        const char* const kColour[] = {"R", "G", "B"};
        std::array<std::uint8_t, 3> colour{};
        for (std::size_t i = 0; i < 3; ++i) colour[i] = static_cast<std::uint8_t>(line.integer(4 + i, kColour[i], 0, 255));
        points.colours.push_back(colour);
        points.errors.push_back(line.number(7, "ERROR"));
        for (std::size_t i = 8; i < line.size(); i += 2) {
            points.track.push_back({static_cast<std::uint32_t>(line.integer(i, "TRACK IMAGE_ID", 0, kMaxId)),
                                    static_cast<std::uint32_t>(line.integer(i + 1, "TRACK POINT2D_IDX", 0, kMaxId))});
        }
        points.track_begin.push_back(points.track.size());
        return false;
    });
    return points;
}

ColmapPoints3D read_points3d_binary(std::string_view bytes, const std::string& source) {
    BinaryReader in(bytes, source);
    // id, X Y Z, R G B, ERROR, track length
    constexpr std::size_t kRecord = 8 + 3 * 8 + 3 + 8 + 8;
    const std::uint64_t count = in.count("the number of points", kRecord);
    ColmapPoints3D points;
    const auto n = static_cast<std::size_t>(count);
    points.ids.reserve(n);
    points.xyz.reserve(n);
    points.errors.reserve(n);
    points.colours.reserve(n);
    points.track_begin.reserve(n + 1);
    for (std::size_t i = 0; i < n; ++i) {
        if (in.remaining() < kRecord) in.fail("point " + std::to_string(i) + ": the file ends inside it");
        // Messages are built only on failure: a model holds hundreds of thousands of points.
        const char* at = in.take(kRecord, "a point");
        const auto id = load<std::uint64_t>(at);
        const Vec3 xyz{load<double>(at), load<double>(at), load<double>(at)};
        const std::array<std::uint8_t, 3> colour{static_cast<std::uint8_t>(at[0]), static_cast<std::uint8_t>(at[1]),
                                                 static_cast<std::uint8_t>(at[2])};
        at += 3;
        const auto error = load<double>(at);
        const auto length = load<std::uint64_t>(at);
        if (id == kColmapNoPoint3D) in.fail("point " + std::to_string(i) + ": POINT3D_ID is -1, which names no point");
        if (!std::isfinite(xyz.x()) || !std::isfinite(xyz.y()) || !std::isfinite(xyz.z()) || !std::isfinite(error)) {
            throw FileError(source + ": point " + std::to_string(id) + ": XYZ or ERROR is not finite");
        }
        if (length > in.remaining() / 8) {
            in.fail("point " + std::to_string(id) + ": the track length " + std::to_string(length) + " is " +
                    in.more_than_left(8));
        }
        const char* block = in.take(length * 8, "a track");
        for (std::uint64_t k = 0; k < length; ++k) {
            const auto image_id = load<std::uint32_t>(block);
            points.track.push_back({image_id, load<std::uint32_t>(block)});
        }
        points.ids.push_back(id);
        points.xyz.push_back(xyz);
        points.errors.push_back(error);
        points.colours.push_back(colour);
        points.track_begin.push_back(points.track.size());
    }
    if (in.remaining() != 0) in.fail("bytes after the last point");
    return points;
}

}  // namespace

std::vector<ColmapCameraRecord> read_colmap_cameras(std::string_view bytes, const std::string& source, bool binary) {
    if (binary) return read_cameras_binary(bytes, source);
    check_text(bytes, source);
    return read_cameras_text(bytes, source);
}

std::vector<ColmapImage> read_colmap_images(std::string_view bytes, const std::string& source, bool binary,
                                            bool with_points) {
    if (binary) return read_images_binary(bytes, source, with_points);
    check_text(bytes, source);
    return read_images_text(bytes, source, with_points);
}

ColmapPoints3D read_colmap_points3d(std::string_view bytes, const std::string& source, bool binary) {
    if (binary) return read_points3d_binary(bytes, source);
    check_text(bytes, source);
    return read_points3d_text(bytes, source);
}

std::filesystem::path colmap_cameras_file_in(const std::filesystem::path& folder) {
    for (const char* name : {"cameras.bin", "cameras.txt"}) {
        if (regular_file_exists(folder / name)) return folder / name;
    }
    return {};
}

namespace {

// COLMAP numbers the models of a workspace's sparse/ 0, 1, 2, ...: in that order (10 after
// 9), then any other names.
bool before_in_colmap_order(const std::filesystem::path& a, const std::filesystem::path& b) {
    const std::string x = a.filename().string(), y = b.filename().string();
    const auto number = [](const std::string& name) {
        return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    if (number(x) != number(y)) return number(x);
    if (number(x) && x.size() != y.size()) return x.size() < y.size();
    return x < y;
}

// The folders directly inside `folder` that hold a COLMAP model, in COLMAP's order.
std::vector<std::filesystem::path> models_inside(const std::filesystem::path& folder) {
    std::vector<std::filesystem::path> models;
    std::error_code error;
    for (std::filesystem::directory_iterator entry(folder, error), end; !error && entry != end; entry.increment(error)) {
        std::error_code kind_error;
        if (entry->is_directory(kind_error) && !colmap_cameras_file_in(entry->path()).empty()) {
            models.push_back(entry->path());
        }
    }
    std::sort(models.begin(), models.end(), before_in_colmap_order);
    return models;
}

}  // namespace

std::filesystem::path colmap_model_folder(const std::filesystem::path& folder) {
    if (!colmap_cameras_file_in(folder).empty()) return folder;
    const std::vector<std::filesystem::path> models = models_inside(folder);
    if (models.size() == 1) return models.front();
    if (models.empty()) return {};
    std::string names;
    for (const std::filesystem::path& model : models) {
        names += (names.empty() ? "" : ", ") + printable_text(model.filename().string());
    }
    throw FileError(printable_text(folder.string()) + " holds " + std::to_string(models.size()) + " COLMAP models (" +
                    names + "): name one, e.g. " + printable_text((folder / models.front().filename()).string()));
}

std::filesystem::path colmap_cameras_file_named(const std::filesystem::path& folder) {
    const std::filesystem::path model = colmap_model_folder(folder);
    return model.empty() ? model : colmap_cameras_file_in(model);
}

std::filesystem::path colmap_cameras_file_for(const std::filesystem::path& part) {
    const std::string extension = part.extension().string();
    const std::string stem = part.stem().string();
    const bool model_part = (extension == ".txt" || extension == ".bin") &&
                            (stem == "images" || stem == "points3D" || stem == "frames" || stem == "rigs");
    if (!model_part) return {};
    const std::filesystem::path folder = part.parent_path().empty() ? "." : part.parent_path();
    const std::filesystem::path same_form = folder / ("cameras" + extension);
    if (regular_file_exists(same_form)) return same_form;
    return colmap_cameras_file_in(folder);
}

namespace {

std::string joined(const std::vector<double>& values) {
    std::string out;
    for (const double value : values) out += " " + format_number(value + 0.0);
    return out;
}

}  // namespace

std::vector<CameraFileText> write_colmap_model(const Camera& camera, const WriteOptions& options) {
    if (camera.intrinsics.skew != 0.0) {
        throw NotRepresentable("COLMAP's models have no skew; this camera's is " + format_number(camera.intrinsics.skew));
    }
    const ColmapCamera colmap = colmap_from_camera(camera);
    // COLMAP 3.8 reads a name up to its first space.
    if (options.image_name.empty() || options.image_name.find_first_of(" \t\r\n") != std::string::npos) {
        throw InvalidArgument("image name: must be one word without spaces, got " + shown_value(options.image_name));
    }
    std::string cameras = "# Camera list with one line of data per camera:\n"
                          "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
                          "# Number of cameras: 1\n";
    cameras += "1 " + std::string(colmap.model) + " " + std::to_string(camera.size.width) + " " +
               std::to_string(camera.size.height) + joined(colmap.params) + "\n";

    // The rotation as a unit quaternion with w >= 0 (q and -q are the same rotation).
    Eigen::Quaterniond q(camera.pose.R);
    q.normalize();
    if (q.w() < 0) q.coeffs() *= -1.0;
    std::string images = "# Image list with two lines of data per image:\n"
                         "#   IMAGE_ID, QW, QX, QY, QZ, TX, TY, TZ, CAMERA_ID, NAME\n"
                         "#   POINTS2D[] as (X, Y, POINT3D_ID)\n"
                         "# Number of images: 1, mean observations per image: 0\n";
    images += "1" + joined({q.w(), q.x(), q.y(), q.z(), camera.pose.t.x(), camera.pose.t.y(), camera.pose.t.z()}) +
              " 1 " + options.image_name + "\n\n";
    // COLMAP's programs load a model only with its (here empty) list of 3-D points.
    const std::string points = "# 3D point list with one line of data per point:\n"
                               "#   POINT3D_ID, X, Y, Z, R, G, B, ERROR, TRACK[] as (IMAGE_ID, POINT2D_IDX)\n"
                               "# Number of points: 0, mean track length: 0\n";
    return {{"cameras.txt", cameras}, {"images.txt", images}, {"points3D.txt", points}};
}

}  // namespace libcam
