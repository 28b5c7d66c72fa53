// libFuzzer target for `--opencv-flags LIST` (calibrate/opencv_flags.cpp): every input is
// either a set of held parameters (fx = fy and coefficients among k1 ... k6, p1, p2, each
// once) or refused with one line of InvalidArgument; nothing else.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "libcam/calibrate/opencv_flags.hpp"
#include "libcam/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const libcam::HeldParameters held = libcam::held_by_opencv_flags(text);
        // (An accepted list may hold nothing: "0" is OpenCV's number for no flags.)
        for (const std::string& name : held.zero_coefficients) {
            const bool known = name == "p1" || name == "p2" || (name.size() == 2 && name[0] == 'k' && name[1] >= '1' && name[1] <= '6');
            if (!known || std::count(held.zero_coefficients.begin(), held.zero_coefficients.end(), name) != 1) std::abort();
        }
    } catch (const libcam::InvalidArgument& error) {
        if (std::string(error.what()).find('\n') != std::string::npos) std::abort();
    }
    return 0;
}
