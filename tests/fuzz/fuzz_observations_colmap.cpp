// libFuzzer target for the COLMAP model's observation reader. A model is three files, so
// the input is one of them: images.txt (or, after a first NUL byte, images.bin) written
// into a folder beside small fixed cameras and points3D files of the same kind. Properties:
//   - read_observations returns a set that check_observations accepts and reproject
//     takes, or throws a libcam::Error; anything else (a crash, a sanitizer report,
//     another exception, a hang) fails the run.

#include <stdlib.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/io/observations.hpp"

namespace {

std::filesystem::path text_model;
std::filesystem::path binary_model;

void write_file(const std::filesystem::path& path, std::string_view bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

template <class T>
void put(std::string& bytes, T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes.append(raw, sizeof(T));
}

std::filesystem::path fresh_folder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "libcam_fuzz_colmap_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) std::abort();
    return pattern;
}

}  // namespace

// Once: the fixed files. Text: two cameras and two points seen by images 1 and 2. Binary:
// one PINHOLE camera (id 1) and one point (id 1) with an empty track.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    text_model = fresh_folder();
    write_file(text_model / "cameras.txt", "1 SIMPLE_RADIAL 640 480 500 320 240 0.01\n2 PINHOLE 100 100 50 50 50 50\n");
    write_file(text_model / "points3D.txt", "1 0 0 2 0 0 0 0.5 1 0\n2 0.1 0.2 3 0 0 0 -1 1 1 2 0\n");
    binary_model = fresh_folder();
    std::string cameras;
    put<std::uint64_t>(cameras, 1);
    put<std::uint32_t>(cameras, 1);
    put<std::int32_t>(cameras, 1);  // PINHOLE
    put<std::uint64_t>(cameras, 100);
    put<std::uint64_t>(cameras, 100);
    for (const double p : {50.0, 50.0, 50.0, 50.0}) put(cameras, p);
    write_file(binary_model / "cameras.bin", cameras);
    std::string points;
    put<std::uint64_t>(points, 1);
    put<std::uint64_t>(points, 1);
    for (const double p : {0.0, 0.0, 2.0}) put(points, p);
    points.append(3, '\0');
    put(points, 0.5);
    put<std::uint64_t>(points, 0);
    write_file(binary_model / "points3D.bin", points);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string_view input(reinterpret_cast<const char*>(data), size);
    const bool binary = !input.empty() && input.front() == '\0';
    if (binary) input.remove_prefix(1);
    const std::filesystem::path folder = binary ? binary_model : text_model;
    write_file(folder / (binary ? "images.bin" : "images.txt"), input);
    try {
        const libcam::ObservationSet set = libcam::read_observations(folder);
        libcam::check_observations(set);
        const libcam::Reprojection r = libcam::reproject(set);
        if (r.residuals.size() != set.observations.size()) std::abort();
    } catch (const libcam::Error&) {
        // refused with a message: the expected outcome for most inputs
    }
    return 0;
}
