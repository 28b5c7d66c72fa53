// libFuzzer target for the COLMAP model reader (io/detail/colmap_model.hpp), which
// `libcam reproject` (the observations), `libcam dataset` (the whole model) and `libcam
// info` (the cameras) share. A model is three files, so the input is images.txt (or,
// after a first NUL byte, images.bin), then, after a line "--points3D--", points3D of
// the same kind; they are written into a folder beside a small fixed cameras file (and a
// fixed points3D where the input has none). Properties:
//   - the three readers agree: each returns, or each throws a libcam::Error with the
//     same message;
//   - read_observations returns a set that check_observations accepts and reproject
//     takes;
//   anything else (a crash, a sanitizer report, another exception, a hang) fails the run.

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
#include "libcam/io/camera_file.hpp"
#include "libcam/io/detail/colmap_model.hpp"
#include "libcam/io/observations.hpp"
#include "refusal_of.hpp"

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

constexpr std::string_view kPointsMarker = "\n--points3D--\n";

std::string default_text_points;
std::string default_binary_points;

}  // namespace

// Once: the fixed files. Text: two cameras, and two points seen by images 1 and 2 (the
// seed text_model.txt's). Binary: one PINHOLE camera (id 1) and one point (id 1) seen by
// image 1's first 2-D point.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    text_model = fresh_folder();
    write_file(text_model / "cameras.txt", "1 SIMPLE_RADIAL 640 480 500 320 240 0.01\n2 PINHOLE 100 100 50 50 50 50\n");
    default_text_points = "1 0 0 2 0 0 0 0.5 1 0 2 1\n2 0.1 0.2 3 0 0 0 -1 1 1 2 0\n";
    binary_model = fresh_folder();
    std::string cameras;
    put<std::uint64_t>(cameras, 1);
    put<std::uint32_t>(cameras, 1);
    put<std::int32_t>(cameras, 1);  // PINHOLE
    put<std::uint64_t>(cameras, 100);
    put<std::uint64_t>(cameras, 100);
    for (const double p : {50.0, 50.0, 50.0, 50.0}) put(cameras, p);
    write_file(binary_model / "cameras.bin", cameras);
    put<std::uint64_t>(default_binary_points, 1);
    put<std::uint64_t>(default_binary_points, 1);
    for (const double p : {0.0, 0.0, 2.0}) put(default_binary_points, p);
    default_binary_points.append(3, '\0');
    put(default_binary_points, 0.5);
    put<std::uint64_t>(default_binary_points, 1);
    put<std::uint32_t>(default_binary_points, 1);
    put<std::uint32_t>(default_binary_points, 0);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string_view input(reinterpret_cast<const char*>(data), size);
    const bool binary = !input.empty() && input.front() == '\0';
    if (binary) input.remove_prefix(1);
    std::string_view images = input;
    std::string_view points = binary ? default_binary_points : default_text_points;
    if (const std::size_t marker = input.find(kPointsMarker); marker != std::string_view::npos) {
        images = input.substr(0, marker);
        points = input.substr(marker + kPointsMarker.size());
    }
    const std::filesystem::path folder = binary ? binary_model : text_model;
    const std::string extension = binary ? ".bin" : ".txt";
    write_file(folder / ("images" + extension), images);
    write_file(folder / ("points3D" + extension), points);
    // libcam dataset's reader, libcam info's and libcam reproject's.
    using libcam::fuzz::refusal_of;
    const std::string dataset = refusal_of([&] { (void)libcam::read_whole_colmap_model(folder); });
    const std::string info = refusal_of([&] { (void)libcam::read_camera_set(folder); });
    libcam::ObservationSet set;
    const std::string reproject = refusal_of([&] { set = libcam::read_observations(folder); });
    if (dataset != info || dataset != reproject) std::abort();
    if (!reproject.empty()) return 0;
    libcam::check_observations(set);
    const libcam::Reprojection r = libcam::reproject(set);
    if (r.residuals.size() != set.observations.size()) std::abort();
    return 0;
}
