// libFuzzer target for OpenCV's stereo files read as a pair (`libcam rectify intrinsics.yml
// extrinsics.yml`; io/camera_file.hpp's parse_opencv_stereo_files). The input is the
// intrinsics file, then a line "--extrinsics--", then the extrinsics file; each input is read
// with a 640x480 image size, as `--size` gives one. Properties checked on every input:
//   - the reader returns at least one valid camera or throws a libcam::Error of one line;
//   - an error about a line names one of the two files and a line inside it.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <utility>

#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"

namespace {

constexpr std::string_view kIntrinsics = "intrinsics.yml";
constexpr std::string_view kExtrinsics = "extrinsics.yml";

std::size_t lines_of(std::string_view text) {
    return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
}

// "FILE: line N: ..." names FILE, one of the two, and N inside it; any other message names
// no line of the joined text ("intrinsics.yml with extrinsics.yml: line ..." would).
bool names_a_line_of_its_file(const std::string& message, std::string_view intrinsics, std::string_view extrinsics) {
    for (const auto& [name, text] : {std::pair{kIntrinsics, intrinsics}, std::pair{kExtrinsics, extrinsics}}) {
        const std::string prefix = std::string(name) + ": line ";
        if (!message.starts_with(prefix)) continue;
        const std::size_t line = std::strtoul(message.c_str() + prefix.size(), nullptr, 10);
        return line >= 1 && line <= lines_of(text);
    }
    return message.find(" with " + std::string(kExtrinsics) + ": line ") == std::string::npos;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    constexpr std::string_view kSeparator = "\n--extrinsics--\n";
    const std::size_t cut = input.find(kSeparator);
    const std::string_view intrinsics = input.substr(0, cut);
    const std::string_view extrinsics = cut == std::string_view::npos ? std::string_view{} : input.substr(cut + kSeparator.size());
    libcam::ReadOptions options;
    options.size = libcam::ImageSize{640, 480};
    libcam::CameraSet set;
    try {
        set = libcam::parse_opencv_stereo_files(intrinsics, std::string(kIntrinsics), extrinsics, std::string(kExtrinsics),
                                                options);
    } catch (const libcam::Error& error) {
        const std::string message = error.what();
        if (message.find('\n') != std::string::npos) std::abort();
        if (!names_a_line_of_its_file(message, intrinsics, extrinsics)) std::abort();
        return 0;
    }
    if (set.cameras.empty()) std::abort();
    // Outside the try: a camera returned invalid throws past the harness, which fails the run.
    for (const libcam::NamedCamera& camera : set.cameras) camera.file.camera.validate();
    return 0;
}
