#pragma once
// What the format table (io/detail/format_rows.cpp: one row per CameraFormat, holding
// everything about the format) shares with the libraries that plug a format into it and
// with the readers themselves.
//
// libcam::io reads and writes every format but one itself, and links neither OpenCV nor
// libmrcal. The row of cameramodel (libmrcal's parser) has no reader or writer of its
// own: libcam::interop fills it when the program calls libcam::register_interop_formats()
// (interop/formats.hpp). Such a row is never skipped silently: reading or writing its
// format throws FileError naming the library to link and the function to call.
//
// The rows are filled by an explicit call rather than by a static initialiser in
// libcam::interop: the linker drops an object file of a static library that nothing
// references, initialiser and all, and the formats would be missing without a word.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/camera_types.hpp"

namespace libcam {

// Parses a file's text; `source` names the file in error messages.
using CameraReader = CameraFile (*)(std::string_view text, const std::string& source);
// What a reader of a file that may hold several cameras is given besides the text.
struct ReadContext {
    std::string source;           // names the file in error messages
    std::filesystem::path folder;  // the file's folder, for the files beside it; empty: none
    ReadOptions options;
};

// Parses every camera of a file.
using CameraSetReader = std::vector<NamedCamera> (*)(std::string_view text, const ReadContext& context);
// The text of a file holding the camera (which format_camera has validated).
using CameraWriter = std::string (*)(const Camera& camera, const WriteOptions& options);
// Every file holding the camera: one unnamed file, or the named files of a folder.
using CameraFilesWriter = std::vector<CameraFileText> (*)(const Camera& camera, const WriteOptions& options);

// The camera a reader put together, validated (Camera::validate): a value out of range
// throws FileError "<where>: <what>", `where` naming the file and the line or key.
Camera validated_camera(Camera camera, const std::string& where);

// Throws FileError "<source>: byte N: ..." unless `text` is UTF-8 without NUL bytes.
void check_text(std::string_view text, const std::string& source);

// Fills the reader and writer of a row that has none of its own; filling it again with the
// same functions changes nothing.
// Safe to call while other threads read files.
void install_camera_format(CameraFormat format, CameraReader reader, CameraWriter writer);

// Whether the format's row has its reader and writer (after asking the loader, if any).
bool camera_format_installed(CameraFormat format);

// For a program that keeps libcam::interop in a library it loads only when needed: the
// function that fills an empty row on demand. It is asked whenever an empty row's reader
// or writer is wanted, before the error above, and either fills the row
// (install_camera_format) or throws an Error saying why it cannot. None by default.
using CameraFormatLoader = void (*)(CameraFormat format);
void set_camera_format_loader(CameraFormatLoader loader);

}  // namespace libcam
