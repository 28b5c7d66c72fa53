// OCamCalib's files: every calib_results.txt of real-data/ocamcalib (SOURCES.md section 3)
// against real-data/vectors/ocamcalib-computed.json, values worked out without libcam with
// the formulas of the toolbox's C functions cam2world and world2cam (ocam_functions.cpp);
// py-OCamCalib's JSON against py-OCamCalib's own cam2world formula, worked here; and
// small files of our own for CRLF, a malformed line and a written file read back.

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <numbers>
#include <nlohmann/json.hpp>
#include <string>

#include "error_message.hpp"
#include "libcam/camera/camera.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/ocamcalib.hpp"
#include "ocamcalib_reference.hpp"
#include "real_cameras.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using libcam::test::file_error_of;

namespace {

using test::toolbox_axes;

// One real file against its computed values.
void check_toolbox_file(const std::string& name) {
    const std::filesystem::path path = test::real_data_path("ocamcalib/" + name);
    const std::filesystem::path vectors_path = test::real_data_path("vectors/ocamcalib-computed.json");
    if (!test::real_data_present(path) || !test::real_data_present(vectors_path)) {
        WARN("real data absent: " << path);
        return;
    }
    const nlohmann::json expected = nlohmann::json::parse(std::ifstream(vectors_path))["files"]["ocamcalib/" + name];
    INFO(name);
    const CameraSet set = read_camera_set(path);
    REQUIRE(set.format == CameraFormat::OcamCalib);  // not COLMAP's cameras.txt
    const Camera& camera = set.cameras.at(0).file.camera;
    CHECK(camera.size.width == expected["width"].get<long>());
    CHECK(camera.size.height == expected["height"].get<long>());
    CHECK(camera.lens.type == LensType::OcamCalib);
    const OcamCalibInverse inverse = read_ocamcalib_inverse(path).value();
    CHECK(inverse.coefficients.size() == expected["len_invpol"].get<std::size_t>());

    // world2cam by invpol as the C code does, cam2world's rays, and the exact projection
    // of each ray landing back on its pixel (ocamcalib_reference.hpp).
    const test::OcamcalibVectorsMiss vectors = test::ocamcalib_vectors_miss(camera, inverse, expected);
    CHECK(vectors.pixels == expected["samples"].size() + 1);
    CHECK(vectors.world2cam_px < 1e-9);
    CHECK(vectors.cam2world < 1e-12);
    CHECK(vectors.exact_px < 1e-9);

    // How far invpol lands from each pixel: over every pixel, at least what the computed
    // values' coarser grid found, and of its size.
    const InverseMiss miss = ocamcalib_inverse_miss(camera, inverse);
    const auto& grid = expected["roundtrip_world2cam_cam2world_max_px"];
    const double within = grid["within_radius_min(h,w)/2_of_centre"].get<double>();
    const double whole = grid["whole_image_grid"].get<double>();
    INFO("invpol misses by " << miss.within_half_side << " px within min(w, h) / 2, " << miss.whole_image
                             << " px over the image (at " << miss.worst_pixel.transpose() << "); the grid's: " << within
                             << ", " << whole);
    CHECK(miss.within_half_side >= within * (1 - 1e-6));
    CHECK(miss.within_half_side <= 2 * within);
    CHECK(miss.whole_image >= whole * (1 - 1e-6));
    CHECK(miss.whole_image <= 2.5 * whole);
}

}  // namespace

TEST_CASE("ocamcalib: ches00/360-SL-Metasurface's calib_results.txt", "[ocamcalib]") {
    check_toolbox_file("ches00-360-SL-Metasurface/calib_results.txt");
}
TEST_CASE("ocamcalib: renmengqisheng/calib_fisheye's calib_results.txt", "[ocamcalib]") {
    check_toolbox_file("renmengqisheng-calib_fisheye/calib_results.txt");
}
TEST_CASE("ocamcalib: vivekmudgal/fisheye-localization's calib_results.txt, invpol 0.56 px off at the corners",
          "[ocamcalib]") {
    check_toolbox_file("vivekmudgal-fisheye-localization/calib_results.txt");
}
TEST_CASE("ocamcalib: AnjanaKN/imageconverter's calib_results.txt (CRLF, blank lines)", "[ocamcalib]") {
    check_toolbox_file("AnjanaKN-imageconverter/calib_results.txt");
}
TEST_CASE("ocamcalib: AnjanaKN/imageconverter's Cam0.txt (CRLF)", "[ocamcalib]") {
    check_toolbox_file("AnjanaKN-imageconverter/Cam0.txt");
}
TEST_CASE("ocamcalib: jingdongZhang/Improved_Feature_Descriptor's calib_results.txt", "[ocamcalib]") {
    check_toolbox_file("jingdongZhang-Improved_Feature_Descriptor/calib_results.txt");
}
TEST_CASE("ocamcalib: premnirmal/Homing-in-Scale-Space's omnicam, past 90 degrees, invpol 5.9 px off",
          "[ocamcalib]") {
    check_toolbox_file("premnirmal-Homing-in-Scale-Space/calib_results.txt");
    const std::filesystem::path path = test::real_data_path("ocamcalib/premnirmal-Homing-in-Scale-Space/calib_results.txt");
    if (!test::real_data_present(path)) return;
    const Camera camera = read_camera_file(path).camera;
    const PreparedCamera prepared(camera);
    // 113 degrees off the axis at 384 px from the centre (SOURCES.md); the computed values'
    // worst pixel on their grid, row 0 column 1020, where invpol misses by 5.876 px.
    const Unprojection side = prepared.unproject(Vec2(camera.intrinsics.cx + 384, camera.intrinsics.cy));
    REQUIRE(side.valid);
    CHECK(std::acos(side.direction.normalized().z()) * 180 / std::numbers::pi == Approx(113.4).margin(0.3));
    CHECK(prepared.valid_angle() > std::numbers::pi / 2);
    const Vec2 corner(1020, 0);
    const Unprojection ray = prepared.unproject(corner);
    REQUIRE(ray.valid);
    const double off = (ocamcalib_inverse_pixel(camera, read_ocamcalib_inverse(path).value(), ray.direction) - corner).norm();
    CHECK(off == Approx(5.875711404365189).epsilon(1e-9));
}
TEST_CASE("ocamcalib: urbste/ImprovedOcamCalib's calib_results.txt", "[ocamcalib]") {
    check_toolbox_file("urbste-ImprovedOcamCalib/calib_results.txt");
}

TEST_CASE("ocamcalib: py-OCamCalib's JSON against its cam2world, and its size given", "[ocamcalib]") {
    const std::filesystem::path path =
        test::real_data_path("ocamcalib/jakarto3d-py-OCamCalib/calibration_fisheye_1_18052022_154907.json");
    if (!test::real_data_present(path)) {
        WARN("real data absent: " << path);
        return;
    }
    const std::string error = file_error_of([&] { read_camera_set(path); });
    CHECK(error.find("--image-size") != std::string::npos);
    ReadOptions options;
    options.size = ImageSize{1088, 756};  // any size: the file holds none
    const CameraSet set = read_camera_set(path, std::nullopt, options);
    REQUIRE(set.format == CameraFormat::PyOcamCalib);
    CHECK(set.cameras.at(0).name == "fisheye_1");
    const Camera& camera = set.cameras.at(0).file.camera;
    const PreparedCamera prepared(camera);
    // py-OCamCalib's Camera.cam2world, worked out in ocamcalib_reference.hpp.
    const nlohmann::json file = nlohmann::json::parse(std::ifstream(path));
    for (const Vec2& pixel : test::py_ocamcalib_pixels()) {
        const Vec3 expected = test::py_ocamcalib_ray(file, pixel);
        const Unprojection ray = prepared.unproject(pixel);
        INFO("pixel " << pixel.transpose());
        REQUIRE(ray.valid);
        CHECK((ray.direction.normalized() - expected).norm() < 1e-12);
        CHECK((prepared.project_camera_point(expected).pixel - pixel).norm() < 1e-8);
    }
    // Its inverse_poly (highest degree first, of the angle from the axis) is read too.
    const OcamCalibInverse inverse = read_ocamcalib_inverse(path).value();
    CHECK(inverse.of_angle_from_axis);
    CHECK(inverse.coefficients.front() == Approx(-0.012207504686747209));
    CHECK(inverse.coefficients.size() == 12);
    const InverseMiss miss = ocamcalib_inverse_miss(camera, inverse);
    INFO("py-OCamCalib's inverse_poly misses by " << miss.within_half_side << " px within min(w, h) / 2");
    CHECK(miss.within_half_side < 1.0);
}

namespace {

// A file of our own, as the toolbox writes it: a 400x300 fisheye, f = 150 px.
std::string own_file(const std::string& line_end) {
    const std::string lines[] = {
        "#polynomial coefficients for the DIRECT mapping function (ocam_model.ss in MATLAB). These are used by cam2world",
        "",
        "5 -1.500000e+02 0.000000e+00 2.000000e-03 -1.000000e-06 0.000000e+00 ",
        "",
        "#polynomial coefficients for the inverse mapping function (ocam_model.invpol in MATLAB). These are used by world2cam",
        "",
        "3 200.0 100.0 10.0 ",
        "",
        "#center: \"row\" and \"column\", starting from 0 (C convention)",
        "",
        "149.5 199.25",
        "",
        "#affine parameters \"c\", \"d\", \"e\"",
        "",
        "1.001 0.002 -0.003",
        "",
        "#image size: \"height\" and \"width\"",
        "",
        "300 400",
        "",
    };
    std::string text;
    for (const std::string& line : lines) text += line + line_end;
    return text;
}

}  // namespace

TEST_CASE("ocamcalib: a file of our own, LF and CRLF, and a ray worked by hand", "[ocamcalib]") {
    const test::TempDir dir;
    for (const std::string line_end : {"\n", "\r\n"}) {
        const Camera camera = read_camera_file(write_file(dir, "calib_results.txt", own_file(line_end))).camera;
        CHECK(camera.size.width == 400);
        CHECK(camera.size.height == 300);
        CHECK(camera.intrinsics.fx == 150.0);
        CHECK(camera.intrinsics.cx == 199.25);  // the column
        CHECK(camera.intrinsics.cy == 149.5);   // the row
        // cam2world by hand: row 149.5 + 60, column 199.25 - 40: (x, y) = [c d; e 1]^-1 (60, -40)
        // with c = 1.001, d = 0.002, e = -0.003; z = a0 + a2 rho^2 + a3 rho^3.
        const double det = 1.001 - 0.002 * -0.003;
        const double x = (60 - 0.002 * -40) / det, y = (0.003 * 60 + 1.001 * -40) / det;
        const double rho = std::hypot(x, y);
        const double z = -150 + 2e-3 * rho * rho - 1e-6 * rho * rho * rho;
        const Vec3 toolbox_ray = Vec3(x, y, z).normalized();
        const Unprojection ray = PreparedCamera(camera).unproject(Vec2(199.25 - 40, 149.5 + 60));
        REQUIRE(ray.valid);
        CHECK((toolbox_axes(ray.direction.normalized()) - toolbox_ray).norm() < 1e-13);
    }
}

TEST_CASE("ocamcalib: a malformed file names the file, the line and the value", "[ocamcalib]") {
    const test::TempDir dir;
    std::string text = own_file("\r\n");
    text.replace(text.find("1.001 0.002 -0.003"), 18, "1.001 0.0x2 -0.003");
    const std::filesystem::path path = write_file(dir, "bad.txt", text);
    const std::string error = file_error_of([&] { read_camera_file(path); });
    // A .txt names no format: its contents said OCamCalib.
    CHECK(error == path.string() + ": line 15: the affine parameters (c, d, e): expected a number, got '0.0x2' (read as "
                                   "OCamCalib calib_results.txt, by its contents (OCamCalib's text))");
    // A count that disagrees with the numbers after it.
    std::string counted = own_file("\n");
    counted.replace(counted.find("3 200.0"), 1, "4");
    const std::string count_error = file_error_of([&] { read_camera_file(write_file(dir, "count.txt", counted)); });
    CHECK(count_error.find(": line 7: the inverse mapping polynomial") != std::string::npos);
    CHECK(count_error.find("the count 4 does not match the 3 numbers") != std::string::npos);
    // A file cut short.
    std::string cut = own_file("\n");
    cut.resize(cut.find("#image size"));
    const std::string cut_error = file_error_of([&] { read_camera_file(write_file(dir, "cut.txt", cut)); });
    CHECK(cut_error.find("the image size (height, width): missing") != std::string::npos);
    // A pol whose a0 looks backwards (the toolbox's a0 is negative).
    std::string forward = own_file("\n");
    forward.replace(forward.find("5 -1.5"), 6, "5 1.5");
    const std::string forward_error = file_error_of([&] { read_camera_file(write_file(dir, "a0.txt", forward)); });
    CHECK(forward_error.find("line 3") != std::string::npos);
    CHECK(forward_error.find("a0") != std::string::npos);
}

TEST_CASE("ocamcalib: calib_results.txt written and read back, with an invpol fitted as the toolbox fits it",
          "[ocamcalib]") {
    const test::TempDir dir;
    const Camera camera = read_camera_file(write_file(dir, "calib_results.txt", own_file("\n"))).camera;
    const std::filesystem::path written = dir.path() / "written.txt";
    write_camera_file(written, camera, CameraFormat::OcamCalib);
    const Camera back = read_camera_file(written).camera;
    CHECK(back.size.width == camera.size.width);
    CHECK(back.intrinsics.fx == camera.intrinsics.fx);
    CHECK(back.intrinsics.cx == camera.intrinsics.cx);
    CHECK(back.intrinsics.cy == camera.intrinsics.cy);
    for (std::size_t i = 0; i < camera.lens.coefficients.size(); ++i) {
        CHECK(back.lens.coefficients[i] == Approx(camera.lens.coefficients[i]).epsilon(1e-14).margin(1e-300));
    }
    const InverseMiss miss = ocamcalib_inverse_miss(back, read_ocamcalib_inverse(written).value());
    CHECK(miss.whole_image < 0.01);
}

TEST_CASE("ocamcalib: camodocal's SCARAMUZZA against its spaceToPlane and liftProjective", "[ocamcalib]") {
    // A file as VINS-Fusion's ship them (PAL camera numbers, its own camera's affine), read
    // through the same model; the expected values are camodocal's OCAMCamera formulas worked
    // here: (x, y) = (column, row), z = -poly(rho) of the affine-corrected radius.
    const std::string text =
        "%YAML:1.0\n---\nmodel_type: scaramuzza\ncamera_name: pal\nimage_width: 1280\nimage_height: 720\n"
        "poly_parameters:\n   p0: -2.463825e+02\n   p1: 0.000000e+00\n   p2: 2.001880e-03\n   p3: -3.074460e-06\n"
        "   p4: 6.138370e-09\ninv_poly_parameters:\n   p0: 378.706255\n   p1: 248.013259\n"
        "affine_parameters:\n   ac: 1.000651\n   ad: -0.000625\n   ae: 0.000431\n   cx: 605.933287\n   cy: 357.5\n";
    const CameraSet set = parse_camera_set(text, CameraFormat::Camodocal, "pal.yaml");
    REQUIRE(set.cameras.size() == 1);
    CHECK(set.cameras[0].name == "pal");
    const Camera& camera = set.cameras[0].file.camera;
    CHECK(camera.lens.type == LensType::OcamCalib);
    const PreparedCamera prepared(camera);
    const double C = 1.000651, D = -0.000625, E = 0.000431;
    const double poly[] = {-2.463825e+02, 0.0, 2.001880e-03, -3.074460e-06, 6.138370e-09};
    for (const Vec2& pixel : {Vec2(900, 100), Vec2(10, 700), Vec2(605.933287, 357.5)}) {
        const double xc0 = pixel.x() - 605.933287, xc1 = pixel.y() - 357.5;
        const double inv = 1 / (C - D * E);
        const double xa0 = inv * (xc0 - D * xc1), xa1 = inv * (-E * xc0 + C * xc1);
        const double phi = std::hypot(xa0, xa1);
        double z = 0.0;
        for (int i = 4; i >= 0; --i) z = z * phi + poly[i];
        // spaceToPlane inverts this ray exactly (its liftProjective keeps the uncorrected
        // (xc0, xc1): the same ray only for the identity affine).
        const Vec3 ray(xa0, xa1, -z);
        const Projection projected = prepared.project_camera_point(ray);
        INFO("pixel " << pixel.transpose());
        REQUIRE(projected.valid);
        CHECK((projected.pixel - pixel).norm() < 1e-9);
        const Unprojection back = prepared.unproject(pixel);
        REQUIRE(back.valid);
        CHECK((back.direction.normalized() - ray.normalized()).norm() < 1e-12);
    }
}

TEST_CASE("ocamcalib: real calibrations written and read back, and a pinhole written as one", "[ocamcalib]") {
    const test::TempDir dir;
    for (const std::string name : {"ches00-360-SL-Metasurface/calib_results.txt",
                                   "premnirmal-Homing-in-Scale-Space/calib_results.txt"}) {
        const std::filesystem::path path = test::real_data_path("ocamcalib/" + name);
        if (!test::real_data_present(path)) {
            WARN("real data absent: " << path);
            continue;
        }
        INFO(name);
        const Camera camera = read_camera_file(path).camera;
        const std::filesystem::path written = dir.path() / "written.txt";
        write_camera_file(written, camera, CameraFormat::OcamCalib);
        const Camera back = read_camera_file(written).camera;
        CHECK(back.intrinsics.fx == camera.intrinsics.fx);
        for (std::size_t i = 0; i < camera.lens.coefficients.size(); ++i) {
            CHECK(back.lens.coefficients[i] == Approx(camera.lens.coefficients[i]).epsilon(1e-14).margin(1e-300));
        }
        // The toolbox's aim, 0.01 px; where the file's own invpol misses by far more (the
        // catadioptric camera near its fold), at least much closer than it.
        const InverseMiss miss = ocamcalib_inverse_miss(back, read_ocamcalib_inverse(written).value());
        const InverseMiss own = ocamcalib_inverse_miss(camera, read_ocamcalib_inverse(path).value());
        INFO("the fitted invpol misses by " << miss.whole_image << " px over the image, the file's by " << own.whole_image);
        CHECK(miss.whole_image < std::max(0.01, own.whole_image / 4));
    }
    Camera pinhole;
    pinhole.size = {64, 48};
    pinhole.intrinsics = {50, 50, 31.5, 23.5, 0};
    const std::filesystem::path written = dir.path() / "pinhole.txt";
    write_camera_file(written, pinhole, CameraFormat::OcamCalib);
    const Camera back = read_camera_file(written).camera;
    CHECK(back.lens.type == LensType::OcamCalib);
    const Projection pixel = PreparedCamera(back).project_camera_point(Vec3(0.3, -0.2, 1.0));
    REQUIRE(pixel.valid);
    CHECK((pixel.pixel - Vec2(31.5 + 15, 23.5 - 10)).norm() < 1e-12);
}
