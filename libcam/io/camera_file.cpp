#include "libcam/io/camera_file.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_formats.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/shown_value.hpp"
#include "libcam/text/utf8.hpp"

namespace libcam {

namespace {

using detail::FormatRow;
using detail::format_rows;

// The readers and writers a library other than libcam::io fills in at run time
// (install_camera_format), by format. constinit: ready before any code runs, so a
// registration made from another file's static initialiser cannot find them unready.
constinit std::array<std::atomic<CameraReader>, kCameraFormatCount> installed_readers{};
constinit std::array<std::atomic<CameraWriter>, kCameraFormatCount> installed_writers{};

const FormatRow& row_of(CameraFormat format) {
    const auto index = static_cast<std::size_t>(format);
    if (index >= format_rows().size()) throw InvalidArgument("format: unknown");
    return format_rows()[index];
}

// "<where>: reading mrcal .cameramodel needs libcam::interop (link it and call
// libcam::register_interop_formats() first)".
[[noreturn]] void throw_not_installed(const FormatRow& row, std::string_view doing, const std::string& where) {
    throw FileError(where + ": " + std::string(doing) + " " + std::string(row.title) + " needs " +
                    std::string(row.library) + " (link it and call " + std::string(row.installer) + " first)");
}

// The program's loader of rows filled at run time (set_camera_format_loader), or none.
constinit std::atomic<CameraFormatLoader> format_loader = nullptr;

// Whether the row can read and write now: its own functions, or ones installed.
bool has_reader(const FormatRow& row) {
    return row.read != nullptr ||
           installed_readers[static_cast<std::size_t>(row.format)].load(std::memory_order_acquire) != nullptr;
}

bool has_writer(const FormatRow& row) {
    return row.write != nullptr ||
           installed_writers[static_cast<std::size_t>(row.format)].load(std::memory_order_acquire) != nullptr;
}

bool installed_now(const FormatRow& row) { return has_reader(row) && (row.read_only || has_writer(row)); }

// Asks the program's loader, if it set one, to fill a row that lacks its reader or writer
// (set_camera_format_loader); the loader fills it or throws its own error.
void ask_loader(const FormatRow& row) {
    if (installed_now(row)) return;
    const CameraFormatLoader load = format_loader.load(std::memory_order_acquire);
    if (load != nullptr) load(row.format);
}

// Every camera of a file of the row's format, through its own reader or the one installed.
std::vector<NamedCamera> read_with(const FormatRow& row, std::string_view text, const ReadContext& context) {
    if (row.read != nullptr) return row.read(text, context);
    ask_loader(row);
    const CameraReader reader = installed_readers[static_cast<std::size_t>(row.format)].load(std::memory_order_acquire);
    if (reader == nullptr) throw_not_installed(row, "reading", context.source);
    return {{std::string(), reader(text, context.source)}};
}

std::vector<CameraFileText> write_with(const FormatRow& row, const Camera& camera, const WriteOptions& options,
                                       const std::string& destination) {
    if (row.write != nullptr) return row.write(camera, options);
    const CameraWriter writer = installed_writers[static_cast<std::size_t>(row.format)].load(std::memory_order_acquire);
    if (writer == nullptr) throw_not_installed(row, "writing", destination);
    return {{std::string(), writer(camera, options)}};
}

// The names of the formats libcam writes, for messages.
std::string written_format_names() {
    std::string names;
    for (const FormatRow& row : format_rows()) {
        if (!row.read_only) names += (names.empty() ? "" : ", ") + std::string(row.name);
    }
    return names;
}

// Every file of the format holding the camera (validated first).
std::vector<CameraFileText> format_files(const Camera& camera, CameraFormat format, const WriteOptions& options,
                                         const std::string& destination) {
    const FormatRow& row = row_of(format);
    if (row.read_only) {
        throw NotRepresentable(destination + ": libcam reads " + std::string(row.title) +
                               " files but does not write them (it writes " + written_format_names() + ")");
    }
    if (!has_writer(row)) ask_loader(row);
    if (!has_writer(row)) throw_not_installed(row, "writing", destination);
    camera.validate();
    const auto write = [&](const Camera& held) { return write_with(row, held, options, destination); };
    try {
        return write(camera);
    } catch (const NotRepresentable&) {
        // A format that lacks the model may still hold the lens as a smaller one when the
        // terms between are exactly 0 (an OPENCV8 read from basalt's pinhole-radtan8 with
        // k3..k6 = 0, written to Kalibr as radtan). Nothing is dropped; otherwise the
        // refusal stands as the writer said it.
        const Lens simplest = simplest_equal_lens(camera.lens);
        if (simplest.type == camera.lens.type) throw;
        Camera smaller = camera;
        smaller.lens = simplest;
        try {
            return write(smaller);
        } catch (const NotRepresentable&) {
        }
        throw;
    }
}

}  // namespace

void install_camera_format(CameraFormat format, CameraReader reader, CameraWriter writer) {
    const auto index = static_cast<std::size_t>(row_of(format).format);
    installed_readers[index].store(reader, std::memory_order_release);
    installed_writers[index].store(writer, std::memory_order_release);
}

void set_camera_format_loader(CameraFormatLoader loader) { format_loader.store(loader, std::memory_order_release); }

bool camera_format_installed(CameraFormat format) {
    const FormatRow& row = row_of(format);
    if (installed_now(row)) return true;
    try {
        ask_loader(row);
    } catch (const Error&) {
        return false;  // the loader could not fill it
    }
    return installed_now(row);
}

std::vector<CameraFormatInfo> camera_formats() {
    std::vector<CameraFormatInfo> formats;
    for (const FormatRow& row : format_rows()) {
        std::vector<std::string_view> extensions;
        for (const std::string_view extension : row.extensions) {
            if (!extension.empty()) extensions.push_back(extension);
        }
        std::vector<FilesBesideInfo> beside;
        for (const detail::FileBeside& files : row.files_beside) beside.push_back({files.files, files.limit.max_bytes});
        CameraFormatInfo info{.format = row.format,
                              .name = row.name,
                              .title = row.title,
                              .description = row.description,
                              .extensions = std::move(extensions),
                              .reads = !row.write_only,
                              .writes = !row.read_only,
                              .writes_folder = row.writes_folder,
                              .observations = row.read_observations != nullptr,
                              .lenses = {row.lenses.begin(), row.lenses.end()},
                              .lens_names = row.lens_names,
                              .refuses = row.refuses,
                              .camera_names = row.camera_names,
                              .library = row.library,
                              .largest_file = row.largest_file,
                              .files_beside = std::move(beside),
                              // Without asking a loader, which may load a library; where one
                              // is set, it fills the row on first use.
                              .available = installed_now(row) ||
                                           format_loader.load(std::memory_order_acquire) != nullptr};
        formats.push_back(std::move(info));
    }
    return formats;
}

std::string_view to_string(CameraFormat format) {
    for (const FormatRow& row : format_rows()) {
        if (row.format == format) return row.name;
    }
    return "?";
}

std::string camera_format_names() {
    std::string names;
    for (const FormatRow& row : format_rows()) names += (names.empty() ? "" : ", ") + std::string(row.name);
    return names;
}

CameraFormat camera_format_from_string(std::string_view text) {
    for (const FormatRow& row : format_rows()) {
        if (row.name == text) return row.format;
    }
    throw InvalidArgument("format: must be one of " + camera_format_names() + "; got " + shown_value(text));
}

namespace {

bool has_extension(const FormatRow& row, std::string_view extension) {
    return !extension.empty() && std::find(row.extensions.begin(), row.extensions.end(), extension) != row.extensions.end();
}

}  // namespace

std::optional<CameraFormat> camera_format_from_path(const std::filesystem::path& path) {
    // The row that writes one file of that ending and is its default (claims nothing).
    const std::string extension = path.extension().string();
    for (const FormatRow& row : format_rows()) {
        if (has_extension(row, extension) && row.claims == nullptr && !row.read_only && !row.writes_folder) return row.format;
    }
    return std::nullopt;
}

std::string format_camera(const Camera& camera, CameraFormat format, const WriteOptions& options) {
    const std::string destination = "format " + std::string(to_string(format));
    if (row_of(format).writes_folder) {
        throw NotRepresentable(destination + ": written as several files into a folder: give the folder");
    }
    return format_files(camera, format, options, destination).front().text;
}

std::vector<CameraFileText> format_camera_files(const Camera& camera, CameraFormat format,
                                                const WriteOptions& options) {
    return format_files(camera, format, options, "format " + std::string(to_string(format)));
}

bool camera_format_writes_folder(CameraFormat format) { return row_of(format).writes_folder; }

Camera validated_camera(Camera camera, const std::string& where) {
    try {
        camera.validate();
    } catch (const InvalidArgument& error) {
        throw FileError(where + ": " + error.what());
    }
    return camera;
}

namespace {

// Where the run of ASCII bytes other than NUL from `i` ends, read eight bytes at a time.
std::size_t ascii_run_end(std::string_view text, std::size_t i) {
    constexpr std::uint64_t kHigh = 0x8080808080808080u, kOnes = 0x0101010101010101u;
    for (std::uint64_t word = 0; i + 8 <= text.size(); i += 8) {
        std::memcpy(&word, text.data() + i, 8);
        if ((word & kHigh) != 0 || ((word - kOnes) & ~word & kHigh) != 0) break;  // a byte >= 0x80, or a 0
    }
    while (i < text.size() && text[i] != 0 && static_cast<unsigned char>(text[i]) < 0x80) ++i;
    return i;
}

}  // namespace

// Camera files are text: UTF-8 without NUL bytes. Checked before any parser sees the
// bytes, because OpenCV's XML parser and libmrcal's parser crash on some binary input
// (found by fuzzing).
void check_text(std::string_view text, const std::string& source) {
    detail::refuse_wide_text(text, source);
    for (std::size_t i = 0; i < text.size();) {
        if (text[i] != '\0' && static_cast<unsigned char>(text[i]) < 0x80) {  // ASCII, most of any camera file
            i = ascii_run_end(text, i + 1);
            continue;
        }
        // Built only for a refused byte: one built for every byte held reading to a few MB/s.
        const auto fail = [&](const std::string& what) {
            throw FileError(source + ": byte " + std::to_string(i) + ": " + what);
        };
        if (text[i] == '\0') fail("NUL byte: not a text file");
        const Utf8Character character = utf8_character_at(text, i);
        if (character.length == 0) fail("not UTF-8");
        i += character.length;
    }
}

namespace {

CameraSet parse_in_context(std::string_view text, CameraFormat format, const ReadContext& context) {
    const FormatRow& row = row_of(format);
    if (!row.binary) check_text(text, context.source);
    return {format, read_with(row, text, context)};
}

}  // namespace

CameraSet parse_camera_set(std::string_view text, CameraFormat format, const std::string& source,
                           const ReadOptions& options) {
    return parse_in_context(text, format, {source, {}, options});
}

bool is_opencv_stereo_extrinsics(std::string_view text) {
    const auto has_key = [&](const std::string& key) {
        return text.starts_with(key + ":") || text.find("\n" + key + ":") != std::string_view::npos;
    };
    return has_key("R") && has_key("T") && !has_key("M1") && !has_key("K1") && !has_key("camera_matrix");
}

namespace {

// The text with its YAML header ("%YAML:1.0", "---") blanked where it opens the text: the
// second file's keys can follow the first's in one document, each line where it was.
std::string without_yaml_header(std::string_view text) {
    std::string body(text);
    for (const std::string_view header : {"%YAML:1.0", "%YAML 1.0", "---"}) {
        const std::size_t at = body.find(header);
        if (at != std::string::npos && body.find_first_not_of(" \t\r\n") == at) body.replace(at, header.size(), header.size(), ' ');
    }
    return body;
}

// A message "JOINED: line N: ..." about the joined document, said of the file line N is in.
std::string said_of_its_file(const std::string& message, const std::string& joined, std::size_t first_lines,
                             const std::string& first, const std::string& second) {
    const std::string prefix = joined + ": line ";
    if (!message.starts_with(prefix)) return message;
    std::size_t end = prefix.size();
    std::size_t line = 0;
    while (end < message.size() && end - prefix.size() < 9 && message[end] >= '0' && message[end] <= '9')
        line = 10 * line + static_cast<std::size_t>(message[end++] - '0');
    if (end == prefix.size() || line == 0) return message;
    const std::string rest = message.substr(end);
    return line <= first_lines ? first + ": line " + std::to_string(line) + rest
                               : second + ": line " + std::to_string(line - first_lines) + rest;
}

}  // namespace

CameraSet parse_opencv_stereo_files(std::string_view intrinsics, const std::string& intrinsics_source,
                                    std::string_view extrinsics, const std::string& extrinsics_source,
                                    const ReadOptions& options) {
    std::string joined(intrinsics);
    if (!joined.empty() && !joined.ends_with('\n')) joined += '\n';
    const auto first_lines = static_cast<std::size_t>(std::count(joined.begin(), joined.end(), '\n'));
    joined += without_yaml_header(extrinsics);
    const std::string source = intrinsics_source + " with " + extrinsics_source;
    try {
        return parse_camera_set(joined, CameraFormat::OpenCvYaml, source, options);
    } catch (const FileError& error) {
        throw FileError(said_of_its_file(error.what(), source, first_lines, intrinsics_source, extrinsics_source));
    }
}

CameraFile parse_camera(std::string_view text, CameraFormat format, const std::string& source,
                        const ReadOptions& options) {
    return parse_camera_set(text, format, source, options).cameras.front().file;
}

namespace {

// The last part of a camera's name that is a path ("D:/photos/a.jpg", "images\\a.jpg"):
// the image's file name; empty for a name that is no path.
std::string_view image_file_name(std::string_view name) {
    const std::size_t slash = name.find_last_of("/\\");
    return slash == std::string_view::npos ? std::string_view() : name.substr(slash + 1);
}

// "3 (D:/a/x.jpg), 7 (D:/b/x.jpg)": cameras by position and name.
std::string listed(const CameraSet& set, const std::vector<std::size_t>& positions) {
    std::string names;
    for (const std::size_t i : positions) {
        const std::string& name = set.cameras[i].name;
        names += (names.empty() ? "" : ", ") + std::to_string(i) + (name.empty() ? "" : " (" + printable_text(name, kShownValueLength) + ")");
    }
    return names;
}

// The camera whose image has the file name `selector`, where exactly one has; throws
// InvalidArgument naming them where several have.
const NamedCamera* by_image_file_name(const CameraSet& set, std::string_view selector, const std::string& source) {
    std::vector<std::size_t> matches;
    for (std::size_t i = 0; i < set.cameras.size(); ++i) {
        if (image_file_name(set.cameras[i].name) == selector) matches.push_back(i);
    }
    if (matches.empty()) return nullptr;
    if (matches.size() == 1) return &set.cameras[matches.front()];
    throw InvalidArgument(source + ": the image file name '" + std::string(selector) + "' names " +
                          std::to_string(matches.size()) + " cameras: " + listed(set, matches) +
                          "; give one's whole name or its position");
}

}  // namespace

const NamedCamera& select_camera(const CameraSet& set, std::string_view selector, const std::string& source) {
    if (selector.empty()) return set.cameras.front();
    for (const NamedCamera& camera : set.cameras) {
        if (!camera.name.empty() && camera.name == selector) return camera;
    }
    if (const NamedCamera* camera = by_image_file_name(set, selector, source)) return *camera;
    for (const NamedCamera& camera : set.cameras) {
        if (!camera.intrinsics_name.empty() && camera.intrinsics_name == selector) return camera;
    }
    const bool digits = std::all_of(selector.begin(), selector.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (digits && selector.size() <= 6) {
        const std::size_t index = std::stoul(std::string(selector));
        if (index < set.cameras.size()) return set.cameras[index];
    }
    std::vector<std::size_t> every(set.cameras.size());
    for (std::size_t i = 0; i < every.size(); ++i) every[i] = i;
    throw InvalidArgument(source + ": no camera '" + std::string(selector) + "'; it holds " +
                          std::to_string(set.cameras.size()) + (set.cameras.size() == 1 ? " camera: " : " cameras: ") +
                          listed(set, every));
}

CameraSet read_camera_set(const std::filesystem::path& path, std::optional<CameraFormat> format,
                          const ReadOptions& options) {
    const detail::LocatedFile located = detail::locate_camera_file(path, format);
    const std::filesystem::path& file = located.file;
    const ReadContext context{file.string(), file.parent_path().empty() ? "." : file.parent_path(), options};
    // The text was checked when it was located.
    return detail::reading_as(located, [&] {
        return CameraSet{located.format, read_with(row_of(located.format), located.text, context)};
    });
}

CameraFile read_camera_file(const std::filesystem::path& path, std::string_view camera,
                            std::optional<CameraFormat> format, const ReadOptions& options) {
    const CameraSet set = read_camera_set(path, format, options);
    return select_camera(set, camera, path.string()).file;
}

void write_camera_file(const std::filesystem::path& path, const Camera& camera, CameraFormat format,
                       const WriteOptions& options) {
    std::vector<CameraFileText> files;
    try {
        files = format_files(camera, format, options, path.string());
    } catch (const NotRepresentable& error) {
        // A refusal names the file it was for, whether or not the format's writer did.
        const std::string what = error.what();
        if (what.starts_with(path.string() + ": ")) throw;
        throw NotRepresentable(path.string() + ": " + what);
    }
    if (!camera_format_writes_folder(format)) {
        write_file_atomically(path, files.front().text);
        return;
    }
    // The folder: the path itself, or the folder of one of the format's files named in it.
    std::filesystem::path folder = path;
    for (const CameraFileText& file : files) {
        if (path.filename() == file.name) folder = path.parent_path();
    }
    if (folder.empty()) folder = ".";
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error) throw FileError(folder.string() + ": cannot create the folder: " + error.message());
    for (const CameraFileText& file : files) write_file_atomically(folder / file.name, file.text);
}

}  // namespace libcam
