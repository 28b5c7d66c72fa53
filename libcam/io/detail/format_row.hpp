#pragma once
// One row per camera-file format: everything libcam knows about the format is here, and
// every place that lists formats (detection, `convert --to`, `libcam formats`, the
// round-trip tests, the fuzz targets, the docs' table) reads it from these rows. Each
// format's row is declared in its own header beside its reader and writer; the table
// (format_rows.cpp) lists the rows and fails the build unless every CameraFormat has
// exactly one. Adding a format: docs/adding-a-file-format.md.

#include <array>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/io/observations.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam::detail {

// What a format's files look like inside, for a file whose extension does not say which
// format it is: each kind is recognised by its first characters (camera_file.cpp).
enum class Content : unsigned {
    Json = 1u << 0,        // '{' and "double-quoted" keys
    Yaml = 1u << 1,        // %YAML, ---, or "key:" first
    Xml = 1u << 2,         // <?xml, <opencv_storage>, or Metashape's <document> or <calibration>
    PythonDict = 1u << 3,  // mrcal's text: a Python dict, # comments first
    KeyValue = 1u << 4,    // "key = value" lines (JPL's cahvor)
    Table = 1u << 5,       // lines of numbers and words (COLMAP's cameras.txt)
    Binary = 1u << 6,      // bytes that are not text (COLMAP's cameras.bin)
    Python = 1u << 7,      // a Python script (written only)
    OcamText = 1u << 8,    // OCamCalib's calib_results.txt: its comment on the DIRECT mapping first
};

constexpr unsigned operator|(Content a, Content b) { return static_cast<unsigned>(a) | static_cast<unsigned>(b); }
constexpr unsigned operator|(unsigned a, Content b) { return a | static_cast<unsigned>(b); }

// Files a format's reader reads beside the one given (COLMAP's images and points3D), and
// the most it reads of each.
struct FileBeside {
    std::string_view files;  // "images and points3D (.bin or .txt)"
    ReadLimit limit;
};

struct FormatRow {
    CameraFormat format;
    std::string_view name;         // what --to, --from-format and camera_format_from_string take
    std::string_view title;        // for messages: "COLMAP model"
    std::string_view description;  // one line for `libcam formats`: what the files are and who writes them
    // File name endings that may hold this format (".json"); where several rows share one,
    // `claims` decides, and a row without it is that content's default.
    std::array<std::string_view, 3> extensions{};
    unsigned content = 0;  // the Content kinds its files may be (a mask)
    // Whether a parsed file of a shared extension is this format, by its keys; nullptr:
    // the default for its content when no other row claims the file.
    bool (*claims)(const DocumentNode& root) = nullptr;
    // Keys its files have and the others of its extension do not (at the top, or in the
    // first entry of the top list or map): a file that no row claims but has one of
    // them is read as this format rather than the default, so that a broken file is told
    // what it is broken as. Where several rows have some, the one with the most.
    std::array<std::string_view, 4> telling_keys{};
    // Every camera a file holds, from its bytes (checked to be UTF-8 text first unless the
    // row says it has a binary form); every file holding one camera. nullptr: filled at
    // run time by the library named below (install_camera_format).
    CameraSetReader read = nullptr;
    CameraFilesWriter write = nullptr;
    bool read_only = false;      // libcam reads these files but does not write them
    bool write_only = false;     // written, not read back (its reader takes another format's files, or none)
    bool writes_folder = false;  // written as several files into a folder
    bool binary = false;         // has a binary form: its reader checks the text itself
    // The most libcam reads of one of its files (larger ones are refused, io/atomic_write.hpp),
    // and the files its reader reads beside it.
    std::uint64_t largest_file = kCameraFileLimit.max_bytes;
    std::span<const FileBeside> files_beside = {};
    // The file of this format in a folder given as the path (COLMAP's sparse/0, or sparse/ holding
    // one model), or empty; throws FileError for a folder that holds several.
    std::filesystem::path (*file_in_folder)(const std::filesystem::path& folder) = nullptr;
    // The file this format reads for another file of the same model given as the path
    // (COLMAP's images.bin: the cameras.bin beside it), or empty when the path is not one.
    std::filesystem::path (*file_for_part)(const std::filesystem::path& part) = nullptr;
    // The observations its files hold (io/observations.hpp), from the file detection chose
    // (COLMAP: its cameras file, beside the rest of the model) and the text detection read
    // of it, not read again; nullptr: it holds none.
    ObservationSet (*read_observations)(const std::filesystem::path& file, std::string_view text,
                                        const ObservationReadOptions& options) = nullptr;
    // The lens models its files hold exactly, whatever their coefficients.
    std::span<const LensType> lenses = {};
    // In words: the peer's own names for them, and what it cannot hold (skew, a pose...).
    std::string_view lens_names = {};
    std::string_view refuses = {};
    // The library that reads and writes it: "libcam::io", or the one that fills the row.
    std::string_view library = "libcam::io";
    std::string_view installer = {};  // the call that fills the row, for that library
    // Which names `--camera` (select_camera) takes for a camera of its files, besides the
    // camera's position: "each view's path, or its image's file name alone"; "one camera"
    // where its files hold one.
    std::string_view camera_names = {};
};

// Every row, in CameraFormat's order (format_rows.cpp).
std::span<const FormatRow> format_rows();

// What a writer says of a lens its format cannot hold, from the format's row: throws
// NotRepresentable "<title> has no model for a <NAME> lens (it holds PINHOLE, OPENCV4 and
// FISHEYE)". A writer names every LensType in its switch, with no default, so that the
// compiler asks it about a new model; those it refuses come here.
[[noreturn]] void refuse_lens(CameraFormat format, LensType type);

// The file a path names for reading (a folder's cameras file, for COLMAP's sparse/0), its
// format (`format`, or the one its extension and contents say) and its text, read up to
// the format's largest_file and checked to be UTF-8 for a format without a binary form;
// throws FileError for a folder of no format, an empty file, a file too large, and text
// in another encoding (camera_file.cpp).
struct LocatedFile {
    std::filesystem::path file;
    CameraFormat format;
    std::string text;
    // How detection chose the format among several, for messages ("by its extension .json
    // and its keys"); empty where the caller named the format, or its extension or folder
    // names only one.
    std::string how;
};
LocatedFile locate_camera_file(const std::filesystem::path& path, std::optional<CameraFormat> format);

// Throws FileError "<source>: UTF-16 text: libcam reads camera files as UTF-8; save it as
// UTF-8" for text in UTF-16 or UTF-32 (text/utf8.hpp), which would otherwise pass for binary.
void refuse_wide_text(std::string_view text, const std::string& source);

// Throws the error being handled again, of the same type, its message made printable
// (text/shown_value.hpp) and, for an error about the file (FileError, NotRepresentable),
// followed by what the file was read as where detection chose its format among several:
// "<message> (read as NeRF transforms.json, by its extension .json and its keys)". Call
// it only from a catch block.
[[noreturn]] void rethrow_read_as(const LocatedFile& located);

// `read()`, whose errors say what the located file was read as (rethrow_read_as).
template <class Read>
auto reading_as(const LocatedFile& located, Read&& read) -> decltype(read()) {
    try {
        return read();
    } catch (const Error&) {
        rethrow_read_as(located);
    }
}

// The cameras of a file that holds observations (OpenSfM, OpenMVG): each view as a camera
// with its pose, named after the view, its intrinsics named; then each of `unposed` (views
// the file lists without a pose, their `camera` an index into set.cameras), said to be
// unposed; the intrinsics alone where the file has no view. Throws FileError "<source>:
// <where>: no camera" for none (observations.cpp), and what check_observations refuses,
// in its words.
std::vector<NamedCamera> cameras_of_views(const ObservationSet& set, const std::string& source, std::string_view where,
                                          std::span<const ObservedView> unposed = {});

// A writer of one file in the table's form.
template <std::string (*write)(const Camera&, const WriteOptions&)>
std::vector<CameraFileText> one_file(const Camera& camera, const WriteOptions& options) {
    return {{std::string(), write(camera, options)}};
}

// A reader of one camera, or of several, that takes only the file's name from the context.
template <CameraFile (*parse)(std::string_view, const std::string&)>
std::vector<NamedCamera> one_camera(std::string_view text, const ReadContext& context) {
    return {{std::string(), parse(text, context.source)}};
}
template <std::vector<NamedCamera> (*parse)(std::string_view, const std::string&)>
std::vector<NamedCamera> with_source(std::string_view text, const ReadContext& context) {
    return parse(text, context.source);
}

}  // namespace libcam::detail
