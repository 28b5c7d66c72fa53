#include "libcam/interop/formats.hpp"

#include <optional>

#include "libcam/interop/mrcal.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

namespace {

// The bridge's reader and writer in the table's form. The format records no look-at camera
// and has no options.

CameraFile read_cameramodel(std::string_view text, const std::string& source) {
    return {parse_cameramodel(text, source), std::nullopt};
}

std::string write_cameramodel(const Camera& camera, const WriteOptions&) { return format_cameramodel(camera); }

}  // namespace

void register_interop_formats() { register_interop_formats(install_camera_format); }

void register_interop_formats(CameraFormatInstaller install) {
    install(CameraFormat::Cameramodel, read_cameramodel, write_cameramodel);
}

}  // namespace libcam
