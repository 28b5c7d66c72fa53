// Camera files with libcam::io alone (this program links neither libcam::interop nor
// OpenCV nor mrcal): libcam JSON and gl JSON are read and written; the formats that
// libcam::interop plugs in fail loudly, naming what to link and what to call, and
// write nothing.

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/format_table.hpp"
#include "temp_dir.hpp"

using namespace libcam;
namespace fs = std::filesystem;

namespace {

Camera wide_camera() {
    Camera camera;
    camera.size = {1600, 1200};
    camera.intrinsics = {900.0, 910.0, 812.5, 592.5, 0.0};
    camera.lens = {LensType::Opencv5, {0.03, -0.01, -1e-4, 2e-4, 0.002}};
    camera.pose = Pose::from_rvec({0.1, -0.2, 0.3}, {1, 2, 3});
    return camera;
}

// The FileError message of `read`, which must throw one.
template <class Read>
std::string file_error_of(Read&& read) {
    try {
        read();
    } catch (const FileError& error) {
        return error.what();
    }
    FAIL("no FileError");
    return {};
}

// What the message of an uninstalled format says: the file, what was asked, the format,
// the library to link and the function to call.
void check_names_the_fix(const std::string& message, const std::string& where, const std::string& doing,
                         const std::string& format) {
    INFO(message);
    CHECK(message.starts_with(where + ": "));
    CHECK(message.find(doing + " " + format + " needs libcam::interop") != std::string::npos);
    CHECK(message.find("libcam::register_interop_formats()") != std::string::npos);
}

}  // namespace

TEST_CASE("io alone: JSON, gl and OpenCV's YAML and XML are installed, mrcal's format is not") {
    CHECK(camera_format_installed(CameraFormat::Json));
    CHECK(camera_format_installed(CameraFormat::Gl));
    CHECK(camera_format_installed(CameraFormat::OpenCvYaml));
    CHECK(camera_format_installed(CameraFormat::OpenCvXml));
    CHECK_FALSE(camera_format_installed(CameraFormat::Cameramodel));
}

TEST_CASE("io alone: an OpenCV YAML and XML camera is read, with the numbers written in it") {
    // The calibration sample's layout, K and coefficients written by hand.
    const std::string yaml =
        "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\ncamera_matrix: !!opencv-matrix\n   rows: 3\n"
        "   cols: 3\n   dt: d\n   data: [ 500., 0., 319.5, 0., 510., 239.5, 0., 0., 1. ]\n"
        "distortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 4\n   dt: d\n   data: [ -0.25, 0.5, 0., 0. ]\n";
    const std::string xml =
        "<?xml version=\"1.0\"?>\n<opencv_storage>\n<image_width>640</image_width>\n<image_height>480</image_height>\n"
        "<camera_matrix type_id=\"opencv-matrix\"><rows>3</rows><cols>3</cols><dt>d</dt>\n"
        "<data>500. 0. 319.5 0. 510. 239.5 0. 0. 1.</data></camera_matrix>\n"
        "<distortion_coefficients type_id=\"opencv-matrix\"><rows>1</rows><cols>4</cols><dt>d</dt>\n"
        "<data>-0.25 0.5 0. 0.</data></distortion_coefficients>\n</opencv_storage>\n";
    for (const auto& [text, format] : {std::pair{yaml, CameraFormat::OpenCvYaml}, std::pair{xml, CameraFormat::OpenCvXml}}) {
        CAPTURE(text);
        const Camera camera = parse_camera(text, format, "cam").camera;
        CHECK(camera.size == ImageSize{640, 480});
        CHECK(camera.intrinsics.fx == 500.0);
        CHECK(camera.intrinsics.fy == 510.0);
        CHECK(camera.intrinsics.cx == 319.5);
        CHECK(camera.intrinsics.cy == 239.5);
        CHECK(camera.lens.type == LensType::Opencv4);
        CHECK(camera.lens.coefficients == std::vector<double>{-0.25, 0.5, 0.0, 0.0});
        CHECK(camera.pose.R == Mat3::Identity());
    }
}

TEST_CASE("io alone: a JSON camera is written and read back, from text and from a file") {
    const Camera camera = wide_camera();
    const CameraFile parsed = parse_camera(format_camera(camera, CameraFormat::Json), CameraFormat::Json, "text");
    CHECK(parsed.camera.lens == camera.lens);
    CHECK(parsed.camera.intrinsics.K() == camera.intrinsics.K());
    CHECK(parsed.camera.pose.R.isApprox(camera.pose.R, 1e-15));

    const test::TempDir dir;
    write_camera_file(dir / "camera.json", camera, CameraFormat::Json);
    CHECK(read_camera_file(dir / "camera.json").camera.lens == camera.lens);

    Camera pinhole = camera;
    pinhole.lens = Lens{};
    write_camera_file(dir / "camera.gl", pinhole, CameraFormat::Gl);
    const Camera gl = parse_camera(read_text_file(dir / "camera.gl"), CameraFormat::Gl, "camera.gl").camera;
    CHECK(gl.intrinsics.K().isApprox(pinhole.intrinsics.K(), 1e-12));
}

TEST_CASE("io alone: reading an mrcal file says to link libcam::interop and register its formats") {
    const test::TempDir dir;
    check_names_the_fix(file_error_of([&] { parse_camera("{ 'lensmodel': 'LENSMODEL_PINHOLE' }", CameraFormat::Cameramodel, "cam.cameramodel"); }),
                        "cam.cameramodel", "reading", "mrcal .cameramodel");

    // By extension, and by contents for a file without one.
    const fs::path model = dir / "camera.cameramodel";
    write_file_atomically(model, "{ 'lensmodel': 'LENSMODEL_PINHOLE' }\n");
    check_names_the_fix(file_error_of([&] { read_camera_file(model); }), model.string(), "reading", "mrcal .cameramodel");
    const fs::path sniffed = dir / "camera";
    write_file_atomically(sniffed, "# written by mrcal\n{ 'lensmodel': 'LENSMODEL_PINHOLE' }\n");
    check_names_the_fix(file_error_of([&] { read_camera_file(sniffed); }), sniffed.string(), "reading", "mrcal .cameramodel");
}

TEST_CASE("io alone: writing an mrcal file fails the same way and leaves no file") {
    const test::TempDir dir;
    const Camera camera = wide_camera();
    const fs::path path = dir / "camera.cameramodel";
    check_names_the_fix(file_error_of([&] { write_camera_file(path, camera, CameraFormat::Cameramodel); }), path.string(),
                        "writing", "mrcal .cameramodel");
    CHECK_FALSE(fs::exists(path));
    check_names_the_fix(file_error_of([&] { format_camera(camera, CameraFormat::Cameramodel); }), "format cameramodel",
                        "writing", "mrcal .cameramodel");
    CHECK(fs::is_empty(dir.path()));
}
