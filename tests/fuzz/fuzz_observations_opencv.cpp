// libFuzzer target for the observation readers of OpenCV's calibration sample's output
// (LIBCAM_FUZZ_TABLE undefined: the input is the .yml, or the .xml when it starts with
// '<') and of a table of observations (LIBCAM_FUZZ_TABLE defined: the input is the table,
// .json when it starts with '[', else .csv, read with a fixed hand-made camera file).
// Properties checked on every input:
//   - read_observations returns a set or throws a libcam::Error; anything else (a crash,
//     a sanitizer report, another exception type, a leak) fails the run;
//   - a set it returns passes check_observations and can be reprojected.
// read_observations takes a path: each input is written to a scratch file first.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <unistd.h>

#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/io/observations.hpp"

namespace {

const std::filesystem::path kScratch =
    std::filesystem::temp_directory_path() / ("libcam_fuzz_observations_" + std::to_string(::getpid()));

void write(const std::filesystem::path& path, std::string_view text) {
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(text.data(), static_cast<std::streamsize>(text.size()));
}

char first_character(std::string_view text) {
    const std::size_t first = text.find_first_not_of(" \t\r\n");
    return first == std::string_view::npos ? '\0' : text[first];
}

// Two 640x480 pinholes, the second 0.1 to the side: what a table's camera column names.
constexpr std::string_view kCameraFile =
    "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n"
    "M1: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ 500., 0., 320., 0., 500., 240., 0., 0., 1. ]\n"
    "D1: [ 0., 0., 0., 0., 0. ]\n"
    "M2: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ 500., 0., 320., 0., 500., 240., 0., 0., 1. ]\n"
    "D2: [ 0., 0., 0., 0., 0. ]\nR: [ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]\nT: [ -0.1, 0., 0. ]\n";

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    std::filesystem::create_directories(kScratch);
    std::atexit([] {
        std::error_code ignored;
        std::filesystem::remove_all(kScratch, ignored);
    });
    write(kScratch / "cameras.yml", kCameraFile);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace libcam;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    ObservationReadOptions options;
#ifdef LIBCAM_FUZZ_TABLE
    const std::filesystem::path input = kScratch / (first_character(text) == '[' ? "table.json" : "table.csv");
    options.camera_file = kScratch / "cameras.yml";
#else
    const std::filesystem::path input = kScratch / (first_character(text) == '<' ? "out_camera_data.xml" : "out_camera_data.yml");
#endif
    write(input, text);
    ObservationSet set;
    try {
        set = read_observations(input, options);
    } catch (const Error&) {
        return 0;  // refused with a message: the expected outcome for most inputs
    }
    check_observations(set);  // throws (uncaught: a failure) if the reader broke its promise
    const Reprojection reprojection = reproject(set);
    if (reprojection.residuals.size() != set.observations.size()) std::abort();
    return 0;
}
