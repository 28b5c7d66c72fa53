// libFuzzer target for one camera-file reader (chosen at compile time by
// LIBCAM_FUZZ_FORMAT, the format's name as `libcam formats` lists it). Properties checked on every input:
//   - the reader returns its cameras or throws a libcam::Error; anything else (a crash, a
//     sanitizer report, another exception type, a leak) fails the run;
//   - every camera it returns is valid, and writing the first in the same format (where
//     libcam writes it) and reading that back gives the same camera.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/interop/formats.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/lens/lens_model.hpp"

namespace {

// The same lens, or the same in a model that nests it (ROS's plumb_bob writes OPENCV4 with
// k3 = 0, which reads back as OPENCV5).
bool same_lens(const libcam::Lens& a, const libcam::Lens& b) {
    if (libcam::lens_info(a.type).family != libcam::lens_info(b.type).family) return false;
    std::vector<double> shorter = a.coefficients.size() < b.coefficients.size() ? a.coefficients : b.coefficients;
    const std::vector<double>& longer = a.coefficients.size() < b.coefficients.size() ? b.coefficients : a.coefficients;
    shorter.resize(longer.size(), 0.0);
    return shorter == longer;
}

// basalt writes UCM in its own parametrisation (alpha = xi / (1 + xi), the focal lengths
// divided by 1 + xi) and reads it back through the inverse, which need not give xi's last
// bit back (not every xi is alpha / (1 - alpha) of a double alpha): that one coefficient
// to 1e-12, as K is compared; every other lens and format bit for bit.
bool same_reparametrised_ucm(const libcam::Lens& a, const libcam::Lens& b, libcam::CameraFormat format) {
    return format == libcam::CameraFormat::Basalt && a.type == libcam::LensType::Ucm && b.type == a.type &&
           std::abs(a.coefficients[0] - b.coefficients[0]) <= 1e-12 * std::abs(b.coefficients[0]);
}

// DriveWorks' rig holds the F-theta polynomial in pixels (b_i = k_i / f^i, and c, d
// carrying fx != fy) and reading it multiplies back: each coefficient to 1e-12 of itself,
// as K is compared.
bool same_rescaled_polynomial(const libcam::Lens& a, const libcam::Lens& b, libcam::CameraFormat format) {
    if (format != libcam::CameraFormat::DriveworksRig || a.type != b.type || a.coefficients.size() != b.coefficients.size()) {
        return false;
    }
    for (std::size_t i = 0; i < a.coefficients.size(); ++i) {
        const double x = a.coefficients[i], y = b.coefficients[i];
        if (!(std::abs(x - y) <= 1e-12 * std::max(std::abs(x), std::abs(y)))) return false;
    }
    return true;
}

bool same_camera(const libcam::Camera& a, const libcam::Camera& b, libcam::CameraFormat format) {
    return a.size == b.size &&
           (same_lens(a.lens, b.lens) || same_reparametrised_ucm(a.lens, b.lens, format) ||
            same_rescaled_polynomial(a.lens, b.lens, format)) &&
           a.intrinsics.K().isApprox(b.intrinsics.K(), 1e-12) &&
           a.pose.R.isApprox(b.pose.R, 1e-9) && (a.pose.t - b.pose.t).norm() <= 1e-9 * (1 + a.pose.t.norm());
}

}  // namespace

// Once, before the first input: the OpenCV and mrcal formats, as the `libcam` program
// registers them.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    libcam::register_interop_formats();
    return 0;
}

namespace {

const libcam::CameraFormat kFormat = libcam::camera_format_from_string(LIBCAM_FUZZ_FORMAT);

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace libcam;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const CameraFormat format = kFormat;
    CameraSet set;
    try {
        // VisualSfM's and Bundler's files store no image size: the reader is given one.
        ReadOptions options;
        if (format == CameraFormat::Nvm || format == CameraFormat::Bundler) options.size = ImageSize{640, 480};
#ifdef LIBCAM_FUZZ_LENS_DATABASE
        // A lens database describes no image: the reader needs a size and a focal length.
        options.size = ImageSize{1500, 1000};
        options.focal_mm = 30.0;
#endif
#ifdef LIBCAM_FUZZ_IMAGE_WIDTH
        // A format that stores no image size, read as --image-size reads it.
        options.size = ImageSize{LIBCAM_FUZZ_IMAGE_WIDTH, LIBCAM_FUZZ_IMAGE_HEIGHT};
#endif
        set = parse_camera_set(text, format, "fuzz input", options);
    } catch (const Error&) {
        return 0;  // refused with a message: the expected outcome for most inputs
    }
    if (set.cameras.empty()) std::abort();
    // Every camera that was accepted must be valid (throws otherwise).
    for (const NamedCamera& camera : set.cameras) camera.file.camera.validate();
    const CameraFile& file = set.cameras.front().file;
    std::vector<CameraFileText> written;
    try {
        written = format_camera_files(file.camera, format);
    } catch (const NotRepresentable&) {
        return 0;  // e.g. a model this format reads but cannot write back
    }
    // A format written into a folder (COLMAP) is read back from its first file, which
    // holds the intrinsics; the pose is in another file.
    Camera back = parse_camera(written.front().text, format, "fuzz output").camera;
    if (camera_format_writes_folder(format)) back.pose = file.camera.pose;
    if (!same_camera(back, file.camera, format)) std::abort();
    return 0;
}
