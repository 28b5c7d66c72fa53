#pragma once
// What libcam knows about each camera-file format, for programs that list them (`libcam
// formats`, the docs' table, a GUI's file dialog): read from the one table of formats.

#include <cstdint>
#include <string_view>
#include <vector>

#include "libcam/io/camera_file.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam {

// Files a format's reader reads beside the one given, and the most it reads of each.
struct FilesBesideInfo {
    std::string_view files;  // "tracks.csv"
    std::uint64_t largest = 0;
};

struct CameraFormatInfo {
    CameraFormat format;
    std::string_view name;         // what --to and camera_format_from_string take
    std::string_view title;        // "COLMAP model"
    std::string_view description;  // what the files are, who writes them
    std::vector<std::string_view> extensions;  // file name endings that may hold it (".json")
    bool reads = true;
    bool writes = true;
    bool writes_folder = false;    // written as several files into a folder
    bool observations = false;     // its files may hold observations (read_observations, io/observations.hpp)
    std::vector<LensType> lenses;  // the lens models its files hold exactly
    std::string_view lens_names;   // the format's own names for them, in words
    std::string_view refuses;      // what it cannot hold besides other lens models (skew, a pose)
    std::string_view camera_names; // the names that select one of its cameras (select_camera), besides its position
    std::string_view library;      // the library that reads and writes it ("libcam::io")
    std::uint64_t largest_file = 0;  // the most libcam reads of one of its files: larger ones are refused
    std::vector<FilesBesideInfo> files_beside;
    bool available = true;         // its reader is in this program (see camera_file.hpp)
};

// Every format, in CameraFormat's order.
std::vector<CameraFormatInfo> camera_formats();

}  // namespace libcam
