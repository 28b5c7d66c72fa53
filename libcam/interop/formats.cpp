#include "libcam/interop/formats.hpp"

#include <optional>

#include "libcam/interop/mrcal.hpp"
#include "libcam/interop/opencv.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

namespace {

// The bridges' readers and writers in the table's form. None of these formats records
// a FOV camera, and none has options.

CameraFile read_opencv_storage(std::string_view text, const std::string& source) {
    return {parse_opencv_storage(text, source), std::nullopt};
}

std::string write_opencv_yaml(const Camera& camera, const WriteOptions&) {
    return format_opencv_storage(camera, OpenCvStorage::Yaml);
}

std::string write_opencv_xml(const Camera& camera, const WriteOptions&) {
    return format_opencv_storage(camera, OpenCvStorage::Xml);
}

CameraFile read_cameramodel(std::string_view text, const std::string& source) {
    return {parse_cameramodel(text, source), std::nullopt};
}

std::string write_cameramodel(const Camera& camera, const WriteOptions&) { return format_cameramodel(camera); }

}  // namespace

void register_interop_formats() {
    install_camera_format(CameraFormat::OpenCvYaml, read_opencv_storage, write_opencv_yaml);
    install_camera_format(CameraFormat::OpenCvXml, read_opencv_storage, write_opencv_xml);
    install_camera_format(CameraFormat::Cameramodel, read_cameramodel, write_cameramodel);
}

}  // namespace libcam
