// Camera files with libcam::io alone (this program links neither libcam::interop nor
// OpenCV nor mrcal): libcam JSON and gl JSON are read and written; the formats that
// libcam::interop plugs in fail loudly, naming what to link and what to call, and
// write nothing, unless the program set a loader that fills them on demand.

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/format_table.hpp"
#include "libcam/io/detail/format_row.hpp"
#include "libcam/io/detail/json_format.hpp"
#include "error_message.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using libcam::test::file_error_of;
namespace fs = std::filesystem;

namespace {

Camera wide_camera() {
    Camera camera;
    camera.size = {1600, 1200};
    camera.intrinsics = {900.0, 910.0, 812.5, 592.5, 0.0};
    camera.lens = {LensType::OpenCv5, {0.03, -0.01, -1e-4, 2e-4, 0.002}};
    camera.pose = Pose::from_rvec({0.1, -0.2, 0.3}, {1, 2, 3});
    return camera;
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

TEST_CASE("io alone: every format's row reads and writes, or says why not") {
    for (const detail::FormatRow& row : detail::format_rows()) {
        INFO(row.name);
        const bool filled_later = !row.installer.empty();
        // Its own reader, or the library that fills it named.
        CHECK((row.read != nullptr || filled_later));
        // A writer exactly when it is not read only (a row filled later gets both).
        if (!filled_later) CHECK(row.read_only == (row.write == nullptr));
        CHECK_FALSE((filled_later && row.read_only));
        CHECK_FALSE((row.read_only && row.write_only));
        CHECK_FALSE(row.name.empty());
        CHECK_FALSE(row.title.empty());
        CHECK_FALSE(row.description.empty());
        CHECK(row.content != 0u);
        CHECK_FALSE(row.lenses.empty());
    }
}

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
        CHECK(camera.lens.type == LensType::OpenCv4);
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

TEST_CASE("io alone: rig files, with every camera, their names, and poses worked by hand") {
    // A Kalibr camchain without an IMU: cam0 is the rig's frame; cam1 sits 0.1 to cam0's
    // right (X_cam1 = X_cam0 + (-0.1, 0, 0)), a UCM camera (Kalibr's omni-none: xi first).
    const std::string chain = R"(cam0:
  camera_model: pinhole
  distortion_model: radtan
  intrinsics: [400, 401, 320, 240]
  distortion_coeffs: [-0.1, 0.01, 0.001, -0.002]
  resolution: [640, 480]
cam1:
  T_cn_cnm1:
  - [1, 0, 0, -0.1]
  - [0, 1, 0, 0]
  - [0, 0, 1, 0]
  - [0, 0, 0, 1]
  camera_model: omni
  distortion_model: none
  intrinsics: [0.9, 700, 701, 321, 241]
  resolution: [640, 480]
)";
    const CameraSet set = parse_camera_set(chain, CameraFormat::Kalibr, "chain.yaml");
    REQUIRE(set.cameras.size() == 2);
    CHECK(set.cameras[0].name == "cam0");
    CHECK(set.cameras[0].file.camera.lens.type == LensType::OpenCv4);
    CHECK(set.cameras[0].file.camera.pose.t == Vec3::Zero());
    const Camera& cam1 = set.cameras[1].file.camera;
    CHECK(cam1.lens.type == LensType::Ucm);
    CHECK(cam1.lens.coefficients == std::vector<double>{0.9});
    CHECK(cam1.intrinsics.fx == 700);
    CHECK(cam1.intrinsics.cy == 241);
    CHECK(cam1.pose.t == Vec3(-0.1, 0, 0));
    CHECK(select_camera(set, "1", "chain.yaml").name == "cam1");

    // basalt: T_imu_cam is the camera in the IMU frame; a half turn about z (qz = 1) at
    // (1, 2, 3): R = diag(-1, -1, 1) both ways, t = -R (1, 2, 3) = (1, 2, -3). basalt's
    // ucm alpha = 0.5 is libcam's UCM with xi = 1 and twice the focal lengths.
    const std::string basalt = R"({"value0": {
  "T_imu_cam": [{"px": 1, "py": 2, "pz": 3, "qx": 0, "qy": 0, "qz": 1, "qw": 0}],
  "intrinsics": [{"camera_type": "ucm", "intrinsics": {"fx": 200, "fy": 201, "cx": 320, "cy": 240, "alpha": 0.5}}],
  "resolution": [[640, 480]]}})";
    const Camera ucm = parse_camera(basalt, CameraFormat::Basalt, "calib.json").camera;
    CHECK(ucm.lens.type == LensType::Ucm);
    CHECK(ucm.lens.coefficients[0] == 1.0);
    CHECK(ucm.intrinsics.fx == 400);
    CHECK(ucm.intrinsics.fy == 402);
    CHECK((ucm.pose.t - Vec3(1, 2, -3)).norm() < 1e-15);

    // camodocal's KANNALA_BRANDT: k2..k5 are OpenCV fisheye's k1..k4, mu mv its fx fy.
    const std::string camodocal = R"(%YAML:1.0
---
model_type: KANNALA_BRANDT
camera_name: left
image_width: 640
image_height: 480
projection_parameters:
   k2: 0.01
   k3: -0.002
   k4: 0.0003
   k5: -0.00004
   mu: 300
   mv: 301
   u0: 320
   v0: 240
)";
    const CameraSet single = parse_camera_set(camodocal, CameraFormat::Camodocal, "left.yaml");
    CHECK(single.cameras[0].name == "left");
    CHECK(single.cameras[0].file.camera.lens.type == LensType::Fisheye);
    CHECK(single.cameras[0].file.camera.lens.coefficients == std::vector<double>{0.01, -0.002, 0.0003, -0.00004});
    CHECK(single.cameras[0].file.camera.intrinsics.fy == 301);
}

TEST_CASE("io alone: rig files that are wrong are refused, naming the file, line and key") {
    const auto error = [](const std::string& text, CameraFormat format) {
        try {
            (void)parse_camera_set(text, format, "rig.yaml");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THAT(error("cam0:\n  camera_model: fisheye\n", CameraFormat::Kalibr),
               Catch::Contains("rig.yaml: line 2: \"cam0.camera_model\": must be pinhole, omni, ds or eucm, got 'fisheye'"));
    CHECK_THAT(error("cam0:\n  camera_model: pinhole\n  distortion_model: radtan\n  intrinsics: [1, 2, 3]\n"
                     "  resolution: [640, 480]\n",
                     CameraFormat::Kalibr),
               Catch::Contains("\"cam0.intrinsics\": a pinhole camera has 4 numbers, got 3"));
    CHECK_THAT(error("cam0:\n  camera_model: ds\n  distortion_model: radtan\n  intrinsics: [0.1, 0.5, 1, 2, 3, 4]\n",
                     CameraFormat::Kalibr),
               Catch::Contains("libcam has no model for Kalibr's ds camera with radtan distortion"));
    CHECK_THAT(error("cam1:\n  camera_model: pinhole\n  distortion_model: none\n  intrinsics: [400, 400, 320, 240]\n"
                     "  resolution: [640, 480]\n  T_cam_imu:\n  - [1, 0, 0, 0]\n  - [0, 2, 0, 0]\n  - [0, 0, 1, 0]\n"
                     "  - [0, 0, 0, 1]\n",
                     CameraFormat::Kalibr),
               Catch::Contains("not a rotation matrix"));
    CHECK_THAT(error("model_type: SCARAMUZZA\nimage_width: 10\nimage_height: 10\nprojection_parameters:\n  a: 1\n",
                     CameraFormat::Camodocal),
               Catch::Contains("\"poly_parameters\": missing"));
    CHECK_THAT(error("model_type: SPHERE\nimage_width: 10\nimage_height: 10\n", CameraFormat::Camodocal),
               Catch::Contains("must be PINHOLE, MEI, KANNALA_BRANDT or SCARAMUZZA (libcam has no model for 'SPHERE')"));
    CHECK_THAT(error(R"({"value0": {"intrinsics": [{"camera_type": "kb4", "intrinsics": {"fx": 1}}], "resolution": [[4, 4]]}})",
                     CameraFormat::Basalt),
               Catch::Contains("\"value0.intrinsics[0].intrinsics.fy\": missing"));
    // A key given twice: yaml-cpp keeps one without a word, and which one a reader sees
    // differs between readers, so the file is refused, naming both lines.
    CHECK_THAT(error("cam0:\n  camera_model: pinhole\n  intrinsics: [400, 400, 320, 240]\n"
                     "  camera_model: omni\n",
                     CameraFormat::Kalibr),
               Catch::Contains("rig.yaml: line 4: the key \"camera_model\" appears twice (first on line 2)"));
    CHECK_THAT(error("<?xml version=\"1.0\"?>\n<opencv_storage>\n<image_width>640</image_width>\n"
                     "<image_width>320</image_width>\n</opencv_storage>\n",
                     CameraFormat::OpenCvXml),
               Catch::Contains("rig.yaml: line 4: the element <image_width> appears twice (first on line 3)"));
    // A quote never closed: yaml-cpp alone would read it to the end of the file.
    CHECK_THAT(error("cam0:\n  camera_model: pinhole\n  intrinsics: [400, 400, 320, 240]\n"
                     "  resolution: [640, 480]\n  distortion_model: \"none\n",
                     CameraFormat::Kalibr),
               Catch::Contains("rig.yaml: line 5: a value opened with \" and never closed"));
    CHECK_THAT(error("cam0:\n  camera_model: 'pinhole''s\n", CameraFormat::Kalibr),
               Catch::Contains("rig.yaml: line 2: a value opened with ' and never closed"));
    // Written: libcam reads these formats but does not write them.
    Camera camera;
    camera.size = {4, 4};
    camera.intrinsics = {2, 2, 1.5, 1.5, 0};
    CHECK_THROWS_WITH(format_camera(camera, CameraFormat::Camodocal), Catch::Contains("does not write them"));
}

TEST_CASE("io alone: JSON files read through the one tree: errors name the file and key, JSON's types are kept") {
    const auto error_of = [](const std::string& text, CameraFormat format) {
        return file_error_of([&] { (void)parse_camera_set(text, format, "c.json"); });
    };
    const std::string nerf_size = R"("w": 640, "h": 480)";
    // JSON records no lines: the message has none (never "line 0").
    CHECK(error_of("{\"fl_x\": 500, \"w\": 640.5, \"h\": 480}", CameraFormat::Nerf) ==
          "c.json: \"w\": expected a whole number in [1, 1000000], got 640.5");
    // A string that holds a number is still a string.
    CHECK(error_of("{\"fl_x\": \"500\", " + nerf_size + "}", CameraFormat::Nerf) == "c.json: \"fl_x\": expected a number, got \"500\"");
    CHECK(error_of(R"({"value0": {"intrinsics": [{"camera_type": "pinhole", "intrinsics": {"fx": 1, "fy": 1, "cx": 2, "cy": 2}}],
                                     "resolution": [["4", 4]]}})",
                   CameraFormat::Basalt) == "c.json: \"value0.resolution[0][0]\": expected an integer, got \"4\"");
    // A number or boolean where text belongs is refused, and a boolean is no number.
    CHECK(error_of("{\"fl_x\": 500, " + nerf_size + ", \"camera_model\": 7}", CameraFormat::Nerf) ==
          "c.json: \"camera_model\": expected a string, got 7");
    CHECK(error_of("{\"fl_x\": true, " + nerf_size + "}", CameraFormat::Nerf) == "c.json: \"fl_x\": expected a number, got true");
    // instant-ngp's flags: false is no special lens; anything else is one.
    CHECK(parse_camera_set("{\"fl_x\": 500, " + nerf_size + ", \"is_fisheye\": false}", CameraFormat::Nerf, "c.json")
              .cameras.size() == 1);
    CHECK(error_of("{\"fl_x\": 500, " + nerf_size + ", \"is_fisheye\": \"false\"}", CameraFormat::Nerf) ==
          "c.json: \"is_fisheye\": expected true or false, got \"false\"");
    // null is a value the writer did not have: an optional key's default, a required key missing.
    CHECK(parse_camera("{\"fl_x\": 500, " + nerf_size + ", \"k1\": null}", CameraFormat::Nerf, "c.json").camera.lens.type ==
          LensType::Pinhole);
    CHECK(error_of(R"({"value0": {"intrinsics": [{"camera_type": "kb4", "intrinsics": {"fx": 1, "fy": null}}], "resolution": [[4, 4]]}})",
                   CameraFormat::Basalt) == "c.json: \"value0.intrinsics[0].intrinsics.fy\": missing");
    // A key given twice: its last value, as JSON libraries read it.
    CHECK(parse_camera("{\"fl_x\": 400, " + nerf_size + ", \"fl_x\": 500}", CameraFormat::Nerf, "c.json").camera.intrinsics.fx ==
          500.0);
    // Parse errors and numbers past a double's range name the key they stopped in.
    CHECK(error_of("{\"fl_x\": 1e999, " + nerf_size + "}", CameraFormat::Nerf) == "c.json: \"fl_x\": must be finite, got 1e999");
    CHECK_THAT(error_of(R"({"value0": {"intrinsics": [{"camera_type": "kb4", )", CameraFormat::Basalt),
               Catch::StartsWith("c.json: \"value0.intrinsics[0]\": not valid JSON: "));
    // Nested past the depth limit: refused before anything recurses through it.
    CHECK_THAT(error_of(std::string(40, '[') + std::string(40, ']'), CameraFormat::Open3d),
               Catch::EndsWith(": nested more than 32 levels deep"));
}

namespace {

// Stand-ins for a program's loader (set_camera_format_loader): one fills the cameramodel
// row with libcam JSON's reader and writer, the other cannot.
int loader_calls = 0;

void fill_with_json(CameraFormat format) {
    ++loader_calls;
    install_camera_format(format, parse_json_camera, [](const Camera& camera, const WriteOptions& options) {
        return format_camera(camera, CameraFormat::Json, options);
    });
}

void refuse(CameraFormat) { throw FileError("the stand-in module is missing"); }

// Empties the row and removes the loader whatever the case did: the cases above expect
// them so.
struct EmptyRowAfterwards {
    ~EmptyRowAfterwards() {
        install_camera_format(CameraFormat::Cameramodel, nullptr, nullptr);
        set_camera_format_loader(nullptr);
    }
};

}  // namespace

TEST_CASE("io alone: a program's loader fills an empty row when it is wanted, or says why it cannot") {
    const EmptyRowAfterwards restore;
    set_camera_format_loader(refuse);
    CHECK_FALSE(camera_format_installed(CameraFormat::Cameramodel));
    CHECK(file_error_of([] { parse_camera("{}", CameraFormat::Cameramodel, "cam"); }) == "the stand-in module is missing");

    set_camera_format_loader(fill_with_json);
    const std::string text = format_camera(wide_camera(), CameraFormat::Cameramodel);
    CHECK(parse_camera(text, CameraFormat::Cameramodel, "cam").camera.intrinsics.fx == 900.0);
    CHECK(camera_format_installed(CameraFormat::Cameramodel));
    CHECK(loader_calls == 1);  // once filled, the row is not asked for again
}
