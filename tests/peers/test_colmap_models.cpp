// COLMAP's camera models as libcam cameras: every model of the conversion table against
// COLMAP's own formulas (colmap_reference.hpp, evaluated in long double), on the
// parameter sets of COLMAP's model tests (models_test.cc), both ways, with COLMAP's
// pixel centres at +0.5.

#include <catch2/catch.hpp>
#include <algorithm>
#include <optional>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "colmap_reference.hpp"
#include "libcam/camera/camera.hpp"
#include "libcam/convert/colmap_models.hpp"
#include "support.hpp"

using namespace libcam;
using libcam::test::colmap_img_from_cam;

namespace {

struct ColmapCase {
    std::string model;
    std::vector<double> params;
};

// COLMAP's models_test.cc parameter sets (its fx fy cx cy are 651.123 655.123 386.123
// 511.123, f 651.123), one or more per model.
std::vector<ColmapCase> colmap_cases() {
    return {
        {"SIMPLE_PINHOLE", {655.123, 386.123, 511.123}},
        {"PINHOLE", {651.123, 655.123, 386.123, 511.123}},
        {"SIMPLE_RADIAL", {651.123, 386.123, 511.123, 0.1}},
        {"RADIAL", {651.123, 386.123, 511.123, 0.05, 0.03}},
        {"OPENCV", {651.123, 655.123, 386.123, 511.123, -0.471, 0.223, -0.001, 0.001}},
        {"OPENCV_FISHEYE", {651.123, 655.123, 386.123, 511.123, -0.471, 0.223, -0.001, 0.001}},
        {"FULL_OPENCV",
         {651.123, 655.123, 386.123, 511.123, -0.471, 0.223, -0.001, 0.001, 0.001, 0.02, -0.02, 0.001}},
        {"FOV", {651.123, 655.123, 386.123, 511.123, 0.9}},
        {"FOV", {651.123, 655.123, 386.123, 511.123, 1e-2}},
        {"FOV", {651.123, 655.123, 386.123, 511.123, 1e-6}},
        {"SIMPLE_RADIAL_FISHEYE", {651.123, 386.123, 511.123, 0.1}},
        {"RADIAL_FISHEYE", {651.123, 386.123, 511.123, 0, 0.1}},
        {"THIN_PRISM_FISHEYE",
         {651.123, 655.123, 386.123, 511.123, -0.471, 0.223, -0.001, 0.001, 0.001, 0.02, -0.02, 0.001}},
        {"RAD_TAN_THIN_PRISM_FISHEYE",
         {651.123, 655.123, 386.123, 511.123, -0.0232, 0.0924, -0.0591, 0.003, 0.0048, -0.0009, 0.0002, 0.0005,
          -0.0009, -0.0001, 0.00007, -0.00017}},
        {"SIMPLE_FISHEYE", {651.123, 386.123, 511.123}},
        {"FISHEYE", {651.123, 655.123, 386.123, 511.123}},
        {"EUCM", {651.123, 655.123, 386.123, 511.123, 0.56, 0.87}},
        {"EUCM", {400, 400, 400, 400, 0.88, 0.64}},
    };
}

const ImageSize kSize{800, 800};  // the pixel grid COLMAP's model tests sweep

// COLMAP's FOV evaluates its factor atan(2 r tan(omega / 2)) / (r omega) by a
// second-order series for r^2 < 1e-4 (and for omega^2 < 1e-4): there its own result
// is off by up to ~1e-7 px. libcam evaluates the formula itself.
double tolerance_px(const ColmapCase& c, const Vec3& point) {
    const double r2 = (point.x() * point.x() + point.y() * point.y()) / (point.z() * point.z());
    const bool fov_series = c.model == "FOV" && r2 < 1e-4;
    return fov_series ? 1e-6 : 1e-9;
}

}  // namespace

TEST_CASE("COLMAP models project as COLMAP's own formulas, with its pixel centres at +0.5") {
    for (const ColmapCase& c : colmap_cases()) {
        INFO(c.model << " " << c.params.back());
        const PreparedCamera camera(camera_from_colmap(c.model, c.params, kSize));
        double worst = 0;
        int compared = 0;
        // COLMAP's sweep (x / z, y / z in [-0.5, 0.5], z 0.5, 1, 2), made denser.
        for (int i = -20; i <= 20; ++i) {
            for (int j = -20; j <= 20; ++j) {
                for (const double z : {0.5, 1.0, 2.0}) {
                    const Vec3 point(0.025 * i * z, 0.025 * j * z, z);
                    const std::optional<Eigen::Vector2d> theirs = colmap_img_from_cam(c.model, c.params, point);
                    const Projection ours = camera.project_camera_point(point);
                    REQUIRE(theirs);
                    REQUIRE(ours.valid);
                    const Vec2 ours_in_colmap = ours.pixel + Vec2::Constant(kColmapPixelShift);
                    const double error = (ours_in_colmap - *theirs).norm();
                    CHECK(error <= tolerance_px(c, point));
                    worst = std::max(worst, error);
                    ++compared;
                }
            }
        }
        INFO("worst " << worst << " px over " << compared << " points");
        CHECK(worst <= 1e-6);
    }
}

TEST_CASE("COLMAP models unproject every pixel back onto itself through COLMAP's formulas") {
    for (const ColmapCase& c : colmap_cases()) {
        INFO(c.model << " " << c.params.back());
        const PreparedCamera camera(camera_from_colmap(c.model, c.params, kSize));
        double worst = 0;
        int compared = 0, pixels = 0;
        for (int x = 0; x <= 800; x += 10) {
            for (int y = 0; y <= 800; y += 10) {
                ++pixels;
                const Vec2 colmap_pixel(x, y);
                const Unprojection ray = camera.unproject(colmap_pixel - Vec2::Constant(kColmapPixelShift));
                // COLMAP's perspective models take points in front of the camera only.
                if (!ray.valid || !(ray.direction.z() > 1e-3 * ray.direction.norm())) continue;
                const std::optional<Eigen::Vector2d> theirs = colmap_img_from_cam(c.model, c.params, ray.direction);
                REQUIRE(theirs);
                const double error = (*theirs - colmap_pixel).norm();
                CHECK(error <= tolerance_px(c, ray.direction));
                worst = std::max(worst, error);
                ++compared;
            }
        }
        INFO("worst " << worst << " px over " << compared << " of " << pixels << " pixels");
        // The strong OPENCV lens (k1 = -0.471) folds over inside the 800 x 800 grid; the
        // others image it all.
        CHECK(compared >= (c.model == "OPENCV" || c.model == "FULL_OPENCV" ? pixels / 4 : pixels * 9 / 10));
    }
}

TEST_CASE("COLMAP models convert back to the same model and parameters, bit for bit") {
    for (const ColmapCase& c : colmap_cases()) {
        INFO(c.model);
        const Camera camera = camera_from_colmap(c.model, c.params, kSize);
        const ColmapCamera back = colmap_from_camera(camera, c.model);
        CHECK(back.model == c.model);
        CHECK(back.params == c.params);
    }
}

TEST_CASE("COLMAP: the principal point moves by half a pixel, the rest maps as the model's table says") {
    const Camera radial = camera_from_colmap("RADIAL", std::vector<double>{500, 320, 240, 0.1, -0.02}, {640, 480});
    CHECK(radial.intrinsics.fx == 500);
    CHECK(radial.intrinsics.fy == 500);
    CHECK(radial.intrinsics.cx == 319.5);
    CHECK(radial.intrinsics.cy == 239.5);
    CHECK(radial.lens.type == LensType::OpenCv4);
    CHECK(radial.lens.coefficients == std::vector<double>{0.1, -0.02, 0, 0});

    const Camera fisheye = camera_from_colmap("RADIAL_FISHEYE", std::vector<double>{500, 320, 240, 0.1, -0.02}, {640, 480});
    CHECK(fisheye.lens.type == LensType::Fisheye);
    CHECK(fisheye.lens.coefficients == std::vector<double>{0.1, -0.02, 0, 0});

    // By default, the model COLMAP users know for the lens; OPENCV5 goes to FULL_OPENCV.
    Camera opencv5 = radial;
    opencv5.lens = {LensType::OpenCv5, {0.1, -0.02, 0.001, 0.002, 0.03}};
    const ColmapCamera full = colmap_from_camera(opencv5);
    CHECK(full.model == "FULL_OPENCV");
    CHECK(full.params == std::vector<double>{500, 500, 320, 240, 0.1, -0.02, 0.001, 0.002, 0.03, 0, 0, 0});
    CHECK(colmap_from_camera(radial).model == "OPENCV");
    CHECK(colmap_from_camera(radial, "RADIAL").params == std::vector<double>{500, 320, 240, 0.1, -0.02});
    CHECK(colmap_from_camera(fisheye, "RAD_TAN_THIN_PRISM_FISHEYE").params.size() == 16);
}

TEST_CASE("COLMAP: a camera a model cannot express exactly is refused, saying why") {
    const Camera opencv = camera_from_colmap("OPENCV", std::vector<double>{500, 510, 320, 240, 0.1, 0, 0.001, 0}, {640, 480});
    CHECK_THAT(test::error_of([&] { colmap_from_camera(opencv, "SIMPLE_RADIAL"); }),
               Catch::Contains("has one focal length; the camera's fx 500 and fy 510 differ"));
    Camera square = opencv;
    square.intrinsics.fy = 500;
    CHECK_THAT(test::error_of([&] { colmap_from_camera(square, "RADIAL"); }),
               Catch::Contains("COLMAP RADIAL holds p1 at 0; the camera's is 0.001"));
    CHECK_THAT(test::error_of([&] { colmap_from_camera(square, "OPENCV_FISHEYE"); }),
               Catch::Contains("COLMAP OPENCV_FISHEYE cannot express the camera's OPENCV4 lens"));
    Camera skewed = square;
    skewed.intrinsics.skew = 0.5;
    CHECK_THAT(test::error_of([&] { colmap_from_camera(skewed); }), Catch::Contains("COLMAP has no skew"));
    Camera stereographic = square;
    stereographic.lens = {LensType::Stereographic, {}};
    CHECK_THAT(test::error_of([&] { colmap_from_camera(stereographic); }),
               Catch::Contains("COLMAP has no model for a STEREOGRAPHIC lens"));
    CHECK_THAT(test::error_of([&] { camera_from_colmap("SPHERICAL", std::vector<double>{1, 2, 3, 4, 5}, {640, 480}); }),
               Catch::Contains("COLMAP model \"SPHERICAL\": libcam knows SIMPLE_PINHOLE"));
    CHECK_THAT(test::error_of([&] { camera_from_colmap("OPENCV", std::vector<double>{500, 320, 240}, {640, 480}); }),
               Catch::Contains("COLMAP OPENCV takes 8 parameters (fx, fy, cx, cy, k1, k2, p1, p2), got 3"));
    CHECK_THAT(test::error_of([&] {
                   camera_from_colmap("SIMPLE_PINHOLE", std::vector<double>{500, NAN, 240}, {640, 480});
               }),
               Catch::Contains("COLMAP SIMPLE_PINHOLE parameter 2 (of f, cx, cy): must be finite, got nan"));
}

TEST_CASE("COLMAP: every model of the table names a libcam model whose coefficients it fills in order") {
    for (const ColmapModel& model : colmap_models()) {
        INFO(model.name);
        // Its parameter list names as many parameters as it takes.
        const auto commas = std::count(model.parameters.begin(), model.parameters.end(), ',');
        CHECK(commas + 1 == model.num_params());
        CHECK(model.coefficient_count <= lens_info(model.lens).num_coefficients);
    }
}

// ---- COLMAP's EQUIRECTANGULAR (COLMAP 4.1, models.h): w, h; x = (lon / (2 pi) + 0.5) w,
// y = (0.5 - elevation / pi) h with the elevation measured up (-Y), pixel corners at 0.
// The pixels and rays below are worked by hand for a 2000 x 1000 panorama.

TEST_CASE("COLMAP EQUIRECTANGULAR: a panorama's pixels and rays, worked by hand, with COLMAP's half pixel",
          "[colmap][equirectangular]") {
    const double w = 2000, h = 1000;
    const Camera camera = camera_from_colmap("EQUIRECTANGULAR", std::vector<double>{w, h}, {2000, 1000});
    CHECK(camera.lens.type == LensType::Lonlat);
    CHECK(camera.intrinsics.cx == 999.5);
    CHECK(camera.intrinsics.cy == 499.5);
    CHECK(camera.intrinsics.fx == Approx(318.30988618379067).epsilon(1e-15));  // 2000 / (2 pi)
    CHECK(camera.intrinsics.fy == Approx(318.30988618379067).epsilon(1e-15));  // 1000 / pi
    const PreparedCamera prepared(camera);
    struct Case {
        Vec3 point;
        Vec2 colmap_pixel;  // COLMAP's, top-left corner at (0, 0)
    };
    const double s = std::sqrt(0.5);
    const Case cases[] = {
        {{0, 0, 1}, {1000, 500}},     // forward: the centre
        {{1, 0, 0}, {1500, 500}},     // right (+X): longitude pi/2, three quarters across
        {{-1, 0, 0}, {500, 500}},     // left: a quarter across
        {{0, 1, 1}, {1000, 750}},     // 45 degrees below the horizon (+Y is down)
        {{1, -1, 0}, {1500, 250}},    // right and 45 degrees up
        {{0, -1, 0.001}, {1000, 1000 * std::atan(0.001) / std::numbers::pi}},  // nearly straight up: the top row
    };
    for (const Case& c : cases) {
        INFO(c.point.transpose());
        const Projection projection = prepared.project_camera_point(c.point);
        REQUIRE(projection.valid);
        CHECK(projection.pixel.x() + kColmapPixelShift == Approx(c.colmap_pixel.x()).margin(1e-9));
        CHECK(projection.pixel.y() + kColmapPixelShift == Approx(c.colmap_pixel.y()).margin(1e-9));
    }
    // COLMAP's pixel (1500, 250) is the ray (cos 45 sin 90, -sin 45, cos 45 cos 90).
    const Unprojection ray = prepared.unproject(Vec2(1500 - kColmapPixelShift, 250 - kColmapPixelShift));
    REQUIRE(ray.valid);
    const Vec3 unit = ray.direction.normalized();
    CHECK(unit.x() == Approx(s).margin(1e-14));
    CHECK(unit.y() == Approx(-s).margin(1e-14));
    CHECK(unit.z() == Approx(0).margin(1e-14));
    // Straight behind: longitude pi (atan2(0, -1)), COLMAP's right edge x = w.
    const Projection behind = prepared.project_camera_point(Vec3(0, 0, -1));
    REQUIRE(behind.valid);
    CHECK(behind.pixel.x() + kColmapPixelShift == Approx(w).margin(1e-9));
    CHECK(behind.pixel.y() + kColmapPixelShift == Approx(h / 2).margin(1e-9));
}

TEST_CASE("COLMAP EQUIRECTANGULAR: written back as w and h, exactly, and a LONLAT that is not the whole sphere "
          "refused, saying why",
          "[colmap][equirectangular]") {
    const std::vector<double> size{5376, 2688};
    const Camera camera = camera_from_colmap("EQUIRECTANGULAR", size, {5376, 2688});
    const ColmapCamera back = colmap_from_camera(camera);
    CHECK(back.model == "EQUIRECTANGULAR");
    CHECK(back.params == size);
    CHECK(colmap_model_by_id(17)->name == "EQUIRECTANGULAR");
    Camera cropped = camera;
    cropped.intrinsics.fy *= 1.5;  // a panorama covering 120 degrees of latitude
    CHECK_THAT(test::error_of([&] { colmap_from_camera(cropped); }),
               Catch::Contains("COLMAP EQUIRECTANGULAR spans the whole sphere") &&
                   Catch::Contains("fx = w / (2 pi) and fy = h / pi"));
    Camera pinhole = camera;
    pinhole.lens = {LensType::Pinhole, {}};
    CHECK_THAT(test::error_of([&] { colmap_from_camera(pinhole, "EQUIRECTANGULAR"); }),
               Catch::Contains("COLMAP EQUIRECTANGULAR cannot express the camera's PINHOLE lens"));
    CHECK_THAT(test::error_of([&] {
                   camera_from_colmap("EQUIRECTANGULAR", std::vector<double>{0, 1000}, {2000, 1000});
               }),
               Catch::Contains("COLMAP EQUIRECTANGULAR parameter 1 (of w, h): must be a positive size, got 0"));
    CHECK_THAT(test::error_of([&] {
                   camera_from_colmap("EQUIRECTANGULAR", std::vector<double>{2000, 1000, 3}, {2000, 1000});
               }),
               Catch::Contains("COLMAP EQUIRECTANGULAR takes 2 parameters (w, h), got 3"));
}
