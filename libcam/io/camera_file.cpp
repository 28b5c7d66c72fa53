#include "libcam/io/camera_file.hpp"

#include <array>
#include <cstdint>
#include <utility>

#include "libcam/error.hpp"
#include "libcam/interop/mrcal.hpp"
#include "libcam/interop/opencv.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/json_format.hpp"

namespace libcam {

namespace {
constexpr std::array<std::pair<CameraFormat, std::string_view>, 5> kFormatNames = {{
    {CameraFormat::Json, "json"},
    {CameraFormat::OpenCvYaml, "opencv-yaml"},
    {CameraFormat::OpenCvXml, "opencv-xml"},
    {CameraFormat::Cameramodel, "cameramodel"},
    {CameraFormat::Gl, "gl"},
}};
}  // namespace

std::string_view to_string(CameraFormat format) {
    for (const auto& [value, name] : kFormatNames) {
        if (value == format) return name;
    }
    return "?";
}

CameraFormat camera_format_from_string(std::string_view text) {
    for (const auto& [value, name] : kFormatNames) {
        if (name == text) return value;
    }
    throw InvalidArgument("format: must be json, opencv-yaml, opencv-xml, cameramodel or gl, got '" +
                          std::string(text) + "'");
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
    camera.validate();
    switch (format) {
        case CameraFormat::Json: return format_json(camera, options.fov_camera);
        case CameraFormat::OpenCvYaml: return format_opencv_storage(camera, OpenCvStorage::Yaml);
        case CameraFormat::OpenCvXml: return format_opencv_storage(camera, OpenCvStorage::Xml);
        case CameraFormat::Cameramodel: return format_cameramodel(camera);
        case CameraFormat::Gl:
            return format_gl_json(to_opengl(camera, options.gl_near, options.gl_far, options.gl_depth_range),
                                  camera.size);
    }
    throw InvalidArgument("format: unknown");
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

CameraFile parse_camera(std::string_view text, CameraFormat format, const std::string& source) {
    check_text(text, source);
    switch (format) {
        case CameraFormat::Json:
        case CameraFormat::Gl: return parse_json_camera(text, source);  // the keys tell which
        case CameraFormat::OpenCvYaml:
        case CameraFormat::OpenCvXml: return {parse_opencv_storage(text, source), std::nullopt};
        case CameraFormat::Cameramodel: return {parse_cameramodel(text, source), std::nullopt};
    }
    throw InvalidArgument("format: unknown");
}

namespace {

// For a file without a known extension: JSON starts with '{' and quotes its keys,
// OpenCV's YAML starts with %YAML and its XML with <?xml; mrcal's text is a Python dict.
CameraFormat sniff_format(std::string_view text, const std::string& source) {
    const auto start = text.find_first_not_of(" \t\r\n");
    if (start == std::string_view::npos) throw FileError(source + ": file is empty");
    const std::string_view body = text.substr(start);
    if (body.starts_with("%YAML")) return CameraFormat::OpenCvYaml;
    if (body.starts_with("<?xml") || body.starts_with("<opencv_storage>")) return CameraFormat::OpenCvXml;
    if (body.starts_with("{")) {
        const auto quote = body.find_first_of("\"'");
        if (quote != std::string_view::npos && body[quote] == '"') return CameraFormat::Json;
        return CameraFormat::Cameramodel;
    }
    if (body.starts_with("#")) return CameraFormat::Cameramodel;  // mrcal writes comments first
    throw FileError(source + ": unknown camera file format (expected .json, .yaml, .yml, .xml or .cameramodel)");
}

}  // namespace

CameraFile read_camera_file(const std::filesystem::path& path) {
    const std::string text = read_text_file(path);
    const std::string source = path.string();
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw FileError(source + ": file is empty");
    const std::optional<CameraFormat> by_extension = camera_format_from_path(path);
    return parse_camera(text, by_extension ? *by_extension : sniff_format(text, source), source);
}

void write_camera_file(const std::filesystem::path& path, const Camera& camera, CameraFormat format,
                       const WriteOptions& options) {
    write_file_atomically(path, format_camera(camera, format, options));
}

}  // namespace libcam
