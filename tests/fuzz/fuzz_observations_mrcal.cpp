// libFuzzer target for mrcal's observations (a .cameramodel's optimization_inputs) as
// `libcam reproject` reads them: the file's own camera through libmrcal's parser as
// `libcam info` reads it, then the observations. The input is a whole .cameramodel's
// text. Properties:
//   - a file `libcam info`'s reader refuses, the observation reader refuses with the same
//     message;
//   - the reader returns a set that passes check_observations and can be reprojected, or
//     throws a libcam::Error;
//   anything else (a crash, a sanitizer report, another exception type, a leak) fails the run.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/formats.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/detail/mrcal_observations.hpp"
#include "refusal_of.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    libcam::register_interop_formats();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const std::string source = "fuzz.cameramodel";
    using libcam::fuzz::refusal_of;
    const std::string info =
        refusal_of([&] { (void)libcam::parse_camera_set(text, libcam::CameraFormat::Cameramodel, source); });
    libcam::ObservationSet set;
    const std::string reproject = refusal_of([&] { set = libcam::detail::read_mrcal_observations(source, text, {}); });
    if (!info.empty() && info != reproject) std::abort();
    if (!reproject.empty()) return 0;
    libcam::check_observations(set);
    (void)libcam::reproject(set);
    return 0;
}
