#include "libcam/io/camera_file.hpp"

#include <array>
#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdint>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/io/json_format.hpp"
#include "libcam/io/opencv_storage.hpp"
#include "libcam/io/rig_formats.hpp"

namespace libcam {

namespace {

// libcam::io's own writers, in the table's form.
std::string write_json(const Camera& camera, const WriteOptions& options) {
    return format_json(camera, options.fov_camera);
}

std::string write_gl_json(const Camera& camera, const WriteOptions& options) {
    return format_gl_json(to_opengl(camera, options.gl_near, options.gl_far, options.gl_depth_range), camera.size);
}

// OpenCV's files record no FOV camera and take no options.
CameraFile read_opencv_storage(std::string_view text, const std::string& source) {
    return {parse_opencv_storage(text, source), std::nullopt};
}

std::string write_opencv_yaml(const Camera& camera, const WriteOptions&) {
    return format_opencv_storage(camera, OpenCvStorage::Yaml);
}

std::string write_opencv_xml(const Camera& camera, const WriteOptions&) {
    return format_opencv_storage(camera, OpenCvStorage::Xml);
}

// One row per format (io/format_table.hpp). The rows of the formats io implements
// are filled here; the others start empty until `library` fills them (`installer`).
// A format whose files hold several cameras has a set reader instead; one libcam
// reads but does not write has no writer and says so.
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
};

constexpr std::string_view kInterop = "libcam::interop";
constexpr std::string_view kRegisterInterop = "libcam::register_interop_formats()";

// libcam JSON and gl JSON share a reader: the keys tell which (io/json_format.hpp);
// OpenCV's YAML and XML share one too (io/opencv_storage.hpp).
// constinit: filled before any code runs, so a registration made from another file's
// static initialiser cannot find it unready.
constinit std::array<FormatRow, 8> format_table = {{
    {CameraFormat::Json, "json", "libcam JSON", "libcam::io", "", parse_json_camera, write_json},
    {CameraFormat::OpenCvYaml, "opencv-yaml", "OpenCV YAML", "libcam::io", "", read_opencv_storage, write_opencv_yaml},
    {CameraFormat::OpenCvXml, "opencv-xml", "OpenCV XML", "libcam::io", "", read_opencv_storage, write_opencv_xml},
    {CameraFormat::Cameramodel, "cameramodel", "mrcal .cameramodel", kInterop, kRegisterInterop, nullptr, nullptr},
    {CameraFormat::Gl, "gl", "gl JSON", "libcam::io", "", parse_json_camera, write_gl_json},
    {CameraFormat::Kalibr, "kalibr", "Kalibr camchain YAML", "libcam::io", "", nullptr, nullptr, parse_kalibr_camchain,
     true},
    {CameraFormat::Basalt, "basalt", "basalt calibration JSON", "libcam::io", "", nullptr, nullptr,
     parse_basalt_calibration, true},
    {CameraFormat::Camodocal, "camodocal", "camodocal YAML", "libcam::io", "", nullptr, nullptr, parse_camodocal, true},
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

CameraReader reader_for(CameraFormat format, const std::string& source) {
    const FormatRow& row = row_of(format);
    const CameraReader reader = row.reader.load(std::memory_order_acquire);
    if (reader == nullptr) throw_not_installed(row, "reading", source);
    return reader;
}

CameraWriter writer_for(CameraFormat format, const std::string& destination) {
    const FormatRow& row = row_of(format);
    if (row.read_only) {
        throw NotRepresentable(destination + ": libcam reads " + std::string(row.title) +
                               " files but does not write them (it writes json, opencv-yaml, opencv-xml, cameramodel "
                               "and gl)");
    }
    const CameraWriter writer = row.writer.load(std::memory_order_acquire);
    if (writer == nullptr) throw_not_installed(row, "writing", destination);
    return writer;
}

std::string format_camera_with(CameraWriter writer, const Camera& camera, const WriteOptions& options) {
    camera.validate();
    return writer(camera, options);
}

}  // namespace

void install_camera_format(CameraFormat format, CameraReader reader, CameraWriter writer) {
    FormatRow& row = row_of(format);
    row.reader.store(reader, std::memory_order_release);
    row.writer.store(writer, std::memory_order_release);
}

bool camera_format_installed(CameraFormat format) {
    const FormatRow& row = row_of(format);
    return row.reader.load(std::memory_order_acquire) != nullptr && row.writer.load(std::memory_order_acquire) != nullptr;
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
    return std::nullopt;
}

std::string format_camera(const Camera& camera, CameraFormat format, const WriteOptions& options) {
    return format_camera_with(writer_for(format, "format " + std::string(to_string(format))), camera, options);
}

namespace {

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

}  // namespace

CameraSet parse_camera_set(std::string_view text, CameraFormat format, const std::string& source) {
    const FormatRow& row = row_of(format);
    if (row.set_reader != nullptr) {
        check_text(text, source);
        return {format, row.set_reader(text, source)};
    }
    const CameraReader reader = reader_for(format, source);
    check_text(text, source);
    return {format, {{std::string(), reader(text, source)}}};
}

CameraFile parse_camera(std::string_view text, CameraFormat format, const std::string& source) {
    return parse_camera_set(text, format, source).cameras.front().file;
}

const NamedCamera& select_camera(const CameraSet& set, std::string_view selector, const std::string& source) {
    if (selector.empty()) return set.cameras.front();
    for (const NamedCamera& camera : set.cameras) {
        if (!camera.name.empty() && camera.name == selector) return camera;
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

// For a file without a known extension: JSON starts with '{' and quotes its keys,
// OpenCV's YAML starts with %YAML and its XML with <?xml; mrcal's text is a Python dict;
// other YAML starts with a key and a colon (Kalibr's camchains: "cam0:").
CameraFormat sniff_format(std::string_view text, const std::string& source) {
    const auto start = text.find_first_not_of(" \t\r\n");
    if (start == std::string_view::npos) throw FileError(source + ": file is empty");
    const std::string_view body = text.substr(start);
    if (body.starts_with("%YAML") || body.starts_with("---")) return CameraFormat::OpenCvYaml;
    if (body.starts_with("<?xml") || body.starts_with("<opencv_storage>")) return CameraFormat::OpenCvXml;
    if (body.starts_with("{")) {
        const auto quote = body.find_first_of("\"'");
        if (quote != std::string_view::npos && body[quote] == '"') return CameraFormat::Json;
        return CameraFormat::Cameramodel;
    }
    if (body.starts_with("#")) return CameraFormat::Cameramodel;  // mrcal writes comments first
    const std::string_view first_line = body.substr(0, body.find('\n'));
    const auto colon = first_line.find(':');
    const bool key_first = colon != std::string_view::npos && colon > 0 &&
                           std::all_of(first_line.begin(), first_line.begin() + static_cast<long>(colon), [](char c) {
                               return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
                           });
    if (key_first) return CameraFormat::OpenCvYaml;
    throw FileError(source + ": unknown camera file format (expected JSON, YAML, OpenCV's XML or mrcal's .cameramodel; "
                    "--from-format names it: " + camera_format_names() + ")");
}

// The format of a file: by extension, else by its first characters; then, for the
// extensions several formats share, by its keys (a YAML file that does not parse is
// left to the OpenCV reader, which says where it is broken).
CameraFormat detect_format(std::string_view text, const std::filesystem::path& path, const std::string& source) {
    const CameraFormat by_look = camera_format_from_path(path).value_or(sniff_format(text, source));
    if (by_look == CameraFormat::Json) return rig_format_of_json(text).value_or(CameraFormat::Json);
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

CameraSet read_camera_set(const std::filesystem::path& path, std::optional<CameraFormat> format) {
    const std::string text = read_text_file(path);
    const std::string source = path.string();
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw FileError(source + ": file is empty");
    return parse_camera_set(text, format ? *format : detect_format(text, path, source), source);
}

CameraFile read_camera_file(const std::filesystem::path& path, std::string_view camera,
                            std::optional<CameraFormat> format) {
    const CameraSet set = read_camera_set(path, format);
    return select_camera(set, camera, path.string()).file;
}

void write_camera_file(const std::filesystem::path& path, const Camera& camera, CameraFormat format,
                       const WriteOptions& options) {
    write_file_atomically(path, format_camera_with(writer_for(format, path.string()), camera, options));
}

}  // namespace libcam
