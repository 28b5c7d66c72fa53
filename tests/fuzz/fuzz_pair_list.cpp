// libFuzzer target for `libcam calibrate --pairs FILE` (calibrate/pair_list.cpp): every
// input is either a list with as many left as right images, at least one of each, or
// refused with one line of FileError; nothing else.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "libcam/calibrate/pair_list.hpp"
#include "libcam/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const libcam::PairList list = libcam::parse_pair_list(text, "fuzz/list.xml");
        if (list.left.empty() || list.left.size() != list.right.size()) std::abort();
    } catch (const libcam::FileError& error) {
        if (std::string(error.what()).find('\n') != std::string::npos) std::abort();
    }
    return 0;
}
