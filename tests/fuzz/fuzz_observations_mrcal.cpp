// libFuzzer target for mrcal's observations (a .cameramodel's optimization_inputs): the
// input is a whole .cameramodel's text. Property: the reader returns a set that passes
// check_observations and can be reprojected, or throws a libcam::Error; anything else
// (a crash, a sanitizer report, another exception type, a leak) fails the run.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/io/detail/mrcal_observations.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const libcam::ObservationSet set = libcam::detail::parse_mrcal_observations(text, "fuzz.cameramodel");
        libcam::check_observations(set);
        libcam::reproject(set);
    } catch (const libcam::Error&) {
        // refused with a message: allowed
    }
    return 0;
}
