#pragma once
// The camera flags shared by `convert` and `rays`: a look-at camera given by flags, or a
// camera file given by --from.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "libcam/io/camera_file.hpp"

namespace libcam::cli {

// Which camera of a file, and in which format: --camera NAME|INDEX and --from-format;
// and what the file may leave out: --image-size and --nerf-principal-point.
struct FileSelection {
    std::string camera;
    std::string format;
    std::string image_size;
    std::string nerf_principal_point = "centre";
    // Lens databases (lensfun's XML): which lens, at which focal length and crop factor.
    std::string lens;
    std::string focal;
    std::string crop_factor;
    bool projection_only = false;

    void add_to(CLI::App& command);
    std::optional<CameraFormat> chosen_format() const;  // throws UsageError for an unknown name
    ReadOptions read_options() const;                  // throws UsageError for malformed flags
    CameraFile read(const std::string& path) const;
    NamedCamera read_named(const std::string& path) const;  // with the file's name for it, and whether it is posed
    CameraSet read_set(const std::string& path) const;
};

struct CameraOptions {
    FileSelection selection;
    std::string from;
    std::string fov;
    std::string fov_axis = "both";
    std::string size;
    std::string eye = "0,0,0";
    std::string target;
    std::string gaze;
    std::string up = "0,1,0";
    std::string pixel_origin = "top-left";

    void add_to(CLI::App& command);

    // The camera the flags describe; throws UsageError for malformed flags and
    // libcam::Error for values out of range or unreadable files.
    CameraFile camera() const;
    PixelOrigin origin() const;
};

// Every format libcam writes, from the table of formats, for a flag's help: "json
// (libcam JSON), ..., colmap (COLMAP model, into a folder), ...".
std::string written_formats_help();

}  // namespace libcam::cli
