// libFuzzer target for the command line's number parsing (tools/libcam/parse.cpp):
// every input is either parsed into finite numbers of the right count or refused with
// a UsageError; nothing else.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "libcam/parse.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace libcam::cli;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        if (!std::isfinite(parse_number("--fov", text))) std::abort();
    } catch (const UsageError&) {
    }
    try {
        const libcam::Vec3 v = parse_vec3("--eye", text);
        if (!v.allFinite()) std::abort();
    } catch (const UsageError&) {
    }
    try {
        const libcam::ImageSize s = parse_size("--size", text);
        if (s.width < 1 || s.height < 1 || s.width > libcam::kMaxImageSide || s.height > libcam::kMaxImageSide) {
            std::abort();
        }
    } catch (const UsageError&) {
    }
    return 0;
}
