#include "libcam/io/camera_file.hpp"

#include <array>
#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/io/json_format.hpp"
#include "libcam/io/opencv_storage.hpp"
#include "libcam/io/cahvor_format.hpp"
#include "libcam/io/colmap_format.hpp"
#include "libcam/io/nerf_transforms.hpp"
#include "libcam/io/blender_format.hpp"
#include "libcam/io/open3d_format.hpp"
#include "libcam/io/openicc_format.hpp"
#include "libcam/io/rig_formats.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam {

namespace {

// libcam::io's own writers, in the table's form.
std::string write_json(const Camera& camera, const WriteOptions& options) {
    return format_json(camera, options.fov_camera);
}

std::string write_gl_json(const Camera& camera, const WriteOptions& options) {
    // A projection matrix is linear: it holds a pinhole, nothing more.
    if (camera.lens.type != LensType::Pinhole) {
        throw NotRepresentable("gl holds a pinhole camera only (an OpenGL projection matrix has no distortion); this "
                               "camera's lens is " + std::string(lens_info(camera.lens.type).name));
    }
    return format_gl_json(to_opengl(camera, options.gl_near, options.gl_far, options.gl_depth_range), camera.size);
}

// OpenCV's files (one camera, a stereo pair, ORB-SLAM's settings) record no FOV camera.
std::vector<NamedCamera> read_opencv_storage(std::string_view text, const ReadContext& context) {
    return parse_opencv_storage_set(text, context.source, context.options);
}

// A Blender script is Python, which libcam does not run: the JSON of the same settings
// (--from-format blender names it too) is what it reads.
std::vector<NamedCamera> read_blender_script(std::string_view text, const ReadContext& context) {
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    if (first != std::string_view::npos && text[first] == '{') return parse_blender_cameras(text, context.source);
    throw FileError(context.source + ": a Blender script is not read back; read the same settings as JSON (convert "
                    "--to blender-json), or export a .blend's cameras with tools/blender/export_cameras.py");
}

std::string write_ros_camera_info(const Camera& camera, const WriteOptions& options) {
    return format_ros_camera_info(camera, options);
}

std::string write_opencv_yaml(const Camera& camera, const WriteOptions&) {
    return format_opencv_storage(camera, OpenCvStorage::Yaml);
}

std::string write_opencv_xml(const Camera& camera, const WriteOptions&) {
    return format_opencv_storage(camera, OpenCvStorage::Xml);
}

// One row per format (io/format_table.hpp). The rows of the formats io implements
// are filled here; the others start empty until `library` fills them (`installer`).
// A format whose files hold several cameras has a set reader instead; one written as
// several files into a folder has a files writer; one libcam reads but does not write
// has no writer and says so.
struct FormatRow {
    CameraFormat format;
    std::string_view name;   // what --to and camera_format_from_string take
    std::string_view title;  // for messages
    std::string_view library;
    std::string_view installer;
    std::atomic<CameraReader> reader;
    std::atomic<CameraWriter> writer;
    CameraSetReader set_reader = nullptr;
    bool read_only = false;
    CameraFilesWriter files_writer = nullptr;
    bool binary = false;  // also has a binary form: its reader checks the text itself
};

constexpr std::string_view kInterop = "libcam::interop";
constexpr std::string_view kRegisterInterop = "libcam::register_interop_formats()";

// The rig readers take only the file's name from the context.
template <std::vector<NamedCamera> (*parse)(std::string_view, const std::string&)>
std::vector<NamedCamera> read_with_source(std::string_view text, const ReadContext& context) {
    return parse(text, context.source);
}

// libcam JSON and gl JSON share a reader: the keys tell which (io/json_format.hpp);
// OpenCV's YAML and XML share one too (io/opencv_storage.hpp).
// constinit: filled before any code runs, so a registration made from another file's
// static initialiser cannot find it unready.
constinit std::array<FormatRow, 17> format_table = {{
    {CameraFormat::Json, "json", "libcam JSON", "libcam::io", "", parse_json_camera, write_json},
    {CameraFormat::OpenCvYaml, "opencv-yaml", "OpenCV YAML", "libcam::io", "", nullptr, write_opencv_yaml,
     read_opencv_storage},
    {CameraFormat::OpenCvXml, "opencv-xml", "OpenCV XML", "libcam::io", "", nullptr, write_opencv_xml, read_opencv_storage},
    {CameraFormat::Cameramodel, "cameramodel", "mrcal .cameramodel", kInterop, kRegisterInterop, nullptr, nullptr},
    {CameraFormat::Gl, "gl", "gl JSON", "libcam::io", "", parse_json_camera, write_gl_json},
    {CameraFormat::Kalibr, "kalibr", "Kalibr camchain YAML", "libcam::io", "", nullptr, format_kalibr_camchain,
     read_with_source<parse_kalibr_camchain>},
    {CameraFormat::Basalt, "basalt", "basalt calibration JSON", "libcam::io", "", nullptr, format_basalt_calibration,
     read_with_source<parse_basalt_calibration>},
    {CameraFormat::Camodocal, "camodocal", "camodocal YAML", "libcam::io", "", nullptr, nullptr,
     read_with_source<parse_camodocal>, true},
    {CameraFormat::Colmap, "colmap", "COLMAP model", "libcam::io", "", nullptr, nullptr, read_colmap_model, false,
     write_colmap_model, true},
    {CameraFormat::Nerf, "nerf", "NeRF transforms.json", "libcam::io", "", nullptr, write_nerf_transforms,
     read_nerf_transforms},
    {CameraFormat::Cahvor, "cahvor", "JPL .cahvor", "libcam::io", "", nullptr, nullptr, read_with_source<parse_cahvor>,
     true},
    {CameraFormat::Ros, "ros", "ROS camera_info YAML", "libcam::io", "", nullptr, write_ros_camera_info,
     read_with_source<parse_ros_camera_info>},
    {CameraFormat::Open3d, "open3d", "Open3D camera JSON", "libcam::io", "", nullptr, format_open3d_camera,
     read_with_source<parse_open3d_camera>},
    {CameraFormat::Euroc, "euroc", "EuRoC sensor.yaml", "libcam::io", "", nullptr, nullptr,
     read_with_source<parse_euroc_sensor>, true},
    {CameraFormat::Openicc, "openicc", "OpenImuCameraCalibrator JSON", "libcam::io", "", nullptr, nullptr,
     read_with_source<parse_openicc_camera>, true},
    {CameraFormat::Blender, "blender", "Blender camera script", "libcam::io", "", nullptr, format_blender_script,
     read_blender_script},
    {CameraFormat::BlenderJson, "blender-json", "Blender camera JSON", "libcam::io", "", nullptr, format_blender_json,
     read_with_source<parse_blender_cameras>},
}};

FormatRow& row_of(CameraFormat format) {
    for (FormatRow& row : format_table) {
        if (row.format == format) return row;
    }
    throw InvalidArgument("format: unknown");
}

// "<where>: reading mrcal .cameramodel needs libcam::interop (link it and call
// libcam::register_interop_formats() first)".
[[noreturn]] void throw_not_installed(const FormatRow& row, std::string_view doing, const std::string& where) {
    throw FileError(where + ": " + std::string(doing) + " " + std::string(row.title) + " needs " +
                    std::string(row.library) + " (link it and call " + std::string(row.installer) + " first)");
}

constinit std::atomic<CameraFormatLoader> format_loader = nullptr;

// Asks the program's loader, if it set one, to fill an empty row (set_camera_format_loader).
void ask_loader(const FormatRow& row) {
    const CameraFormatLoader load = format_loader.load(std::memory_order_acquire);
    if (load != nullptr) load(row.format);
}

CameraReader reader_for(CameraFormat format, const std::string& source) {
    const FormatRow& row = row_of(format);
    if (row.reader.load(std::memory_order_acquire) == nullptr) ask_loader(row);
    const CameraReader reader = row.reader.load(std::memory_order_acquire);
    if (reader == nullptr) throw_not_installed(row, "reading", source);
    return reader;
}

// The names of the formats libcam writes, for messages.
std::string written_format_names() {
    std::string names;
    for (const FormatRow& row : format_table) {
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
    if (row.files_writer == nullptr && row.writer.load(std::memory_order_acquire) == nullptr) ask_loader(row);
    const CameraWriter writer = row.writer.load(std::memory_order_acquire);
    if (row.files_writer == nullptr && writer == nullptr) throw_not_installed(row, "writing", destination);
    camera.validate();
    const auto write = [&](const Camera& held) -> std::vector<CameraFileText> {
        if (row.files_writer != nullptr) return row.files_writer(held, options);
        return {{std::string(), writer(held, options)}};
    };
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
    FormatRow& row = row_of(format);
    row.reader.store(reader, std::memory_order_release);
    row.writer.store(writer, std::memory_order_release);
}

void set_camera_format_loader(CameraFormatLoader loader) { format_loader.store(loader, std::memory_order_release); }

bool camera_format_installed(CameraFormat format) {
    const FormatRow& row = row_of(format);
    const auto installed = [&row] {
        const bool reads = row.set_reader != nullptr || row.reader.load(std::memory_order_acquire) != nullptr;
        const bool writes =
            row.read_only || row.files_writer != nullptr || row.writer.load(std::memory_order_acquire) != nullptr;
        return reads && writes;
    };
    if (installed()) return true;
    try {
        ask_loader(row);
    } catch (const Error&) {
        return false;  // the loader could not fill it
    }
    return installed();
}

std::string_view to_string(CameraFormat format) {
    for (const FormatRow& row : format_table) {
        if (row.format == format) return row.name;
    }
    return "?";
}

std::string camera_format_names() {
    std::string names;
    for (const FormatRow& row : format_table) names += (names.empty() ? "" : ", ") + std::string(row.name);
    return names;
}

CameraFormat camera_format_from_string(std::string_view text) {
    for (const FormatRow& row : format_table) {
        if (row.name == text) return row.format;
    }
    throw InvalidArgument("format: must be one of " + camera_format_names() + "; got '" + std::string(text) + "'");
}

std::optional<CameraFormat> camera_format_from_path(const std::filesystem::path& path) {
    const std::string extension = path.extension().string();
    if (extension == ".json") return CameraFormat::Json;
    if (extension == ".yaml" || extension == ".yml") return CameraFormat::OpenCvYaml;
    if (extension == ".xml") return CameraFormat::OpenCvXml;
    if (extension == ".cameramodel") return CameraFormat::Cameramodel;
    if (extension == ".py") return CameraFormat::Blender;
    return std::nullopt;
}

std::string format_camera(const Camera& camera, CameraFormat format, const WriteOptions& options) {
    const std::string destination = "format " + std::string(to_string(format));
    if (row_of(format).files_writer != nullptr) {
        throw NotRepresentable(destination + ": written as several files into a folder: give the folder");
    }
    return format_files(camera, format, options, destination).front().text;
}

std::vector<CameraFileText> format_camera_files(const Camera& camera, CameraFormat format,
                                                const WriteOptions& options) {
    return format_files(camera, format, options, "format " + std::string(to_string(format)));
}

bool camera_format_writes_folder(CameraFormat format) { return row_of(format).files_writer != nullptr; }

Camera validated_camera(Camera camera, const std::string& where) {
    try {
        camera.validate();
    } catch (const InvalidArgument& error) {
        throw FileError(where + ": " + error.what());
    }
    return camera;
}

// Camera files are text: UTF-8 without NUL bytes. Checked before any parser sees the
// bytes, because OpenCV's XML parser and libmrcal's parser crash on some binary input
// (found by fuzzing).
void check_text(std::string_view text, const std::string& source) {
    std::size_t i = 0;
    while (i < text.size()) {
        const auto byte = static_cast<unsigned char>(text[i]);
        const std::string where = source + ": byte " + std::to_string(i) + ": ";
        if (byte == 0) throw FileError(where + "NUL byte: not a text file");
        // The length of the UTF-8 sequence this byte starts, and its smallest code point
        // (so overlong encodings are refused too).
        const int length = byte < 0x80 ? 1 : (byte >> 5) == 0x6 ? 2 : (byte >> 4) == 0xE ? 3 : (byte >> 3) == 0x1E ? 4 : 0;
        if (length == 0 || i + static_cast<std::size_t>(length) > text.size()) throw FileError(where + "not UTF-8");
        std::uint32_t code = length == 1 ? byte : byte & (0x7F >> length);
        for (int k = 1; k < length; ++k) {
            const auto next = static_cast<unsigned char>(text[i + static_cast<std::size_t>(k)]);
            if ((next >> 6) != 0x2) throw FileError(where + "not UTF-8");
            code = (code << 6) | (next & 0x3F);
        }
        constexpr std::uint32_t kSmallest[] = {0, 0, 0x80, 0x800, 0x10000};
        if (code < kSmallest[length] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) {
            throw FileError(where + "not UTF-8");
        }
        i += static_cast<std::size_t>(length);
    }
}

namespace {

CameraSet parse_in_context(std::string_view text, CameraFormat format, const ReadContext& context) {
    const FormatRow& row = row_of(format);
    if (row.set_reader != nullptr) {
        if (!row.binary) check_text(text, context.source);
        return {format, row.set_reader(text, context)};
    }
    const CameraReader reader = reader_for(format, context.source);
    check_text(text, context.source);
    return {format, {{std::string(), reader(text, context.source)}}};
}

}  // namespace

CameraSet parse_camera_set(std::string_view text, CameraFormat format, const std::string& source,
                           const ReadOptions& options) {
    return parse_in_context(text, format, {source, {}, options});
}

CameraFile parse_camera(std::string_view text, CameraFormat format, const std::string& source,
                        const ReadOptions& options) {
    return parse_camera_set(text, format, source, options).cameras.front().file;
}

const NamedCamera& select_camera(const CameraSet& set, std::string_view selector, const std::string& source) {
    if (selector.empty()) return set.cameras.front();
    for (const NamedCamera& camera : set.cameras) {
        if (!camera.name.empty() && camera.name == selector) return camera;
    }
    for (const NamedCamera& camera : set.cameras) {
        if (!camera.intrinsics_name.empty() && camera.intrinsics_name == selector) return camera;
    }
    const bool digits = std::all_of(selector.begin(), selector.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (digits && selector.size() <= 6) {
        const std::size_t index = std::stoul(std::string(selector));
        if (index < set.cameras.size()) return set.cameras[index];
    }
    std::string names;
    for (std::size_t i = 0; i < set.cameras.size(); ++i) {
        const std::string& name = set.cameras[i].name;
        names += (i == 0 ? "" : ", ") + std::to_string(i) + (name.empty() ? "" : " (" + name + ")");
    }
    throw InvalidArgument(source + ": no camera '" + std::string(selector) + "'; it holds " +
                          std::to_string(set.cameras.size()) + (set.cameras.size() == 1 ? " camera: " : " cameras: ") +
                          names);
}

namespace {

// The first line that is not blank and not a # comment (mrcal and COLMAP write comments
// first), without its leading blanks.
std::string_view first_content_line(std::string_view text) {
    std::size_t at = 0;
    while (at < text.size()) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        std::string_view line = text.substr(at, end - at);
        const auto start = line.find_first_not_of(" \t\r");
        if (start != std::string_view::npos && line[start] != '#') return line.substr(start);
        at = end + 1;
    }
    return {};
}

bool starts_with_word_then(std::string_view line, char separator) {
    const auto end = line.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_.");
    if (end == 0 || end == std::string_view::npos) return false;
    const auto next = line.find_first_not_of(" \t", end);
    return next != std::string_view::npos && line[next] == separator && (separator != ':' || next == end);
}

// For a file without a known extension: JSON starts with '{' and quotes its keys,
// OpenCV's YAML starts with %YAML and its XML with <?xml; mrcal's text is a Python dict;
// other YAML starts with a key and a colon (Kalibr's camchains: "cam0:"); JPL's cahvor
// with "key = value"; COLMAP's cameras.txt with a camera id and a model name, and its
// cameras.bin is binary.
CameraFormat sniff_format(std::string_view text, const std::string& source) {
    if (text.find('\0') != std::string_view::npos) return CameraFormat::Colmap;
    const std::string_view body = first_content_line(text);
    if (body.empty()) {
        if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) throw FileError(source + ": file is empty");
        return CameraFormat::Cameramodel;  // only comments: mrcal's parser says what is missing
    }
    if (body.starts_with("%YAML") || body.starts_with("---")) return CameraFormat::OpenCvYaml;
    if (body.starts_with("<?xml") || body.starts_with("<opencv_storage>")) return CameraFormat::OpenCvXml;
    if (body.starts_with("{")) {
        // JSON has no comments and quotes its keys with '"'; mrcal writes comments and ''.
        const bool commented = body.data() != text.data() + text.find_first_not_of(" \t\r\n");
        const std::string_view rest = text.substr(static_cast<std::size_t>(body.data() - text.data()));
        const auto quote = rest.find_first_of("\"'");
        const bool double_quoted = quote != std::string_view::npos && rest[quote] == '"';
        return !commented && double_quoted ? CameraFormat::Json : CameraFormat::Cameramodel;
    }
    if (starts_with_word_then(body, '=')) return CameraFormat::Cahvor;
    if (starts_with_word_then(body, ':')) return CameraFormat::OpenCvYaml;
    if (body.front() >= '0' && body.front() <= '9') return CameraFormat::Colmap;
    throw FileError(source + ": unknown camera file format (not JSON, YAML, XML, mrcal's .cameramodel or .cahvor, or "
                    "COLMAP's cameras.txt; --from-format names it: " + camera_format_names() + ")");
}

// The formats an extension names; nullopt for the extensions several formats share in
// ways only the contents tell (.txt), or none.
std::optional<CameraFormat> format_of_extension(const std::filesystem::path& path) {
    const std::string extension = path.extension().string();
    if (extension == ".bin") return CameraFormat::Colmap;
    if (extension == ".cahvor" || extension == ".cahvore") return CameraFormat::Cahvor;
    return camera_format_from_path(path);
}

// What a JSON file's keys say it is: basalt's (value0), NeRF's (frames, camera_angle_x,
// fl_x), or else libcam's or gl.
std::optional<CameraFormat> json_format_of(std::string_view text) {
    // Parsed once here, without throwing: a file that does not parse is left to the
    // reader its extension names, which says where it is broken.
    const nlohmann::json root = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
    if (const std::optional<CameraFormat> rig = rig_format_of_json(root)) return rig;
    if (is_nerf_transforms(root)) return CameraFormat::Nerf;
    if (is_open3d_camera(root)) return CameraFormat::Open3d;
    if (is_openicc_camera(root)) return CameraFormat::Openicc;
    if (is_blender_cameras(root)) return CameraFormat::BlenderJson;
    return std::nullopt;
}

// The format of a file: by extension, else by its first characters; then, for the
// extensions several formats share, by its keys (a YAML file that does not parse is
// left to the OpenCV reader, which says where it is broken).
CameraFormat detect_format(std::string_view text, const std::filesystem::path& path, const std::string& source) {
    // (Not value_or: the contents are looked at only when the extension does not say.)
    const std::optional<CameraFormat> by_extension = format_of_extension(path);
    const CameraFormat by_look = by_extension ? *by_extension : sniff_format(text, source);
    if (by_look == CameraFormat::Json) return json_format_of(text).value_or(CameraFormat::Json);
    if (by_look == CameraFormat::OpenCvYaml) {
        try {
            check_text(text, source);
            if (const std::optional<CameraFormat> rig = rig_format_of_yaml(text, source)) return *rig;
        } catch (const FileError&) {
        }
    }
    return by_look;
}

}  // namespace

CameraSet read_camera_set(const std::filesystem::path& path, std::optional<CameraFormat> format,
                          const ReadOptions& options) {
    const std::string source = path.string();
    std::filesystem::path file = path;
    std::error_code error;
    if (std::filesystem::is_directory(path, error)) {
        // A COLMAP model's folder (sparse/0): its cameras file, binary first as COLMAP writes.
        file = colmap_cameras_file_in(path);
        if (file.empty()) {
            throw FileError(source + ": a folder, and not a COLMAP model (it has no cameras.bin or cameras.txt)");
        }
        if (!format) format = CameraFormat::Colmap;
    }
    const std::string text = read_text_file(file);
    const std::string file_source = file.string();
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw FileError(file_source + ": file is empty");
    const CameraFormat chosen = format ? *format : detect_format(text, file, file_source);
    return parse_in_context(text, chosen, {file_source, file.parent_path().empty() ? "." : file.parent_path(), options});
}

CameraFile read_camera_file(const std::filesystem::path& path, std::string_view camera,
                            std::optional<CameraFormat> format, const ReadOptions& options) {
    const CameraSet set = read_camera_set(path, format, options);
    return select_camera(set, camera, path.string()).file;
}

void write_camera_file(const std::filesystem::path& path, const Camera& camera, CameraFormat format,
                       const WriteOptions& options) {
    const std::vector<CameraFileText> files = format_files(camera, format, options, path.string());
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
