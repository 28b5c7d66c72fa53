// libFuzzer target for the observation readers of OpenSfM (reconstruction.json with
// tracks.csv) and OpenMVG (sfm_data.json). An input is a JSON file, optionally followed by
// a line "--tracks.csv--" and the tracks.csv to put beside it. Property checked: the reader
// returns a set that passes check_observations and can be reprojected, or throws a
// libcam::Error; anything else (a crash, a sanitizer report, another exception) fails.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/io/observations.hpp"

namespace {

void write(const std::filesystem::path& path, std::string_view text) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

// One folder per fuzzing process, reused for every input.
const std::filesystem::path& folder() {
    static const std::filesystem::path path = [] {
        const std::filesystem::path made =
            std::filesystem::temp_directory_path() / ("libcam_fuzz_sfm_" + std::to_string(::getpid()));
        std::filesystem::create_directories(made);
        return made;
    }();
    return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    constexpr std::string_view kSeparator = "\n--tracks.csv--\n";
    const std::size_t split = input.find(kSeparator);
    const std::filesystem::path json = folder() / "reconstruction.json";
    const std::filesystem::path tracks = folder() / "tracks.csv";
    write(json, input.substr(0, split));
    std::error_code ignored;
    std::filesystem::remove(tracks, ignored);
    if (split != std::string_view::npos) write(tracks, input.substr(split + kSeparator.size()));
    libcam::ObservationSet set;
    try {
        set = libcam::read_observations(json);
    } catch (const libcam::Error&) {
        return 0;  // refused with a message
    }
    libcam::check_observations(set);  // throws (an uncaught libcam::Error: a failure) if the reader broke its promise
    libcam::reproject(set);
    return 0;
}
