// libFuzzer target for one camera-file reader (chosen at compile time by
// LIBCAM_FUZZ_FORMAT). Properties checked on every input:
//   - the reader returns a camera or throws a libcam::Error; anything else (a crash, a
//     sanitizer report, another exception type, a leak) fails the run;
//   - a camera it returns is valid, and writing it in the same format and reading that
//     back gives the same camera.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "libcam/error.hpp"
#include "libcam/interop/formats.hpp"
#include "libcam/io/camera_file.hpp"

namespace {

bool same_camera(const libcam::Camera& a, const libcam::Camera& b) {
    return a.size == b.size && a.lens == b.lens && a.intrinsics.K().isApprox(b.intrinsics.K(), 1e-12) &&
           a.pose.R.isApprox(b.pose.R, 1e-9) && (a.pose.t - b.pose.t).norm() <= 1e-9 * (1 + a.pose.t.norm());
}

}  // namespace

// Once, before the first input: the OpenCV and mrcal formats, as the `libcam` program
// registers them.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    libcam::register_interop_formats();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace libcam;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const CameraFormat format = LIBCAM_FUZZ_FORMAT;
    CameraFile file;
    try {
        file = parse_camera(text, format, "fuzz input");
    } catch (const Error&) {
        return 0;  // refused with a message: the expected outcome for most inputs
    }
    file.camera.validate();  // a camera that was accepted must be valid (throws otherwise)
    std::string written;
    try {
        written = format_camera(file.camera, format);
    } catch (const NotRepresentable&) {
        return 0;  // e.g. a model this format reads but cannot write back
    }
    if (!same_camera(parse_camera(written, format, "fuzz output").camera, file.camera)) std::abort();
    return 0;
}
