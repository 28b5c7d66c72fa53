// Blender's cameras as libcam cameras: every pixel's ray against Cycles' own mapping
// (blender_reference.hpp), both ways, for the perspective camera and the panoramic
// FISHEYE_EQUIDISTANT, FISHEYE_EQUISOLID, FISHEYE_LENS_POLYNOMIAL and EQUIRECTANGULAR, with
// sensor fits and shifts.

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <optional>
#include <numbers>
#include <string>
#include <vector>

#include "blender_reference.hpp"
#include "libcam/camera/camera.hpp"
#include "libcam/convert/blender_camera.hpp"
#include "libcam/geometry/pixel_grid.hpp"
#include "libcam/geometry/vector_math.hpp"
#include "support.hpp"

using namespace libcam;

namespace {

struct BlenderCase {
    std::string name;
    BlenderCamera camera;
};

BlenderCamera with(BlenderCameraType type, ImageSize size) {
    BlenderCamera camera;
    camera.type = type;
    camera.size = size;
    return camera;
}

std::vector<BlenderCase> blender_cases() {
    constexpr double pi = std::numbers::pi;
    std::vector<BlenderCase> cases;
    cases.push_back({"perspective, Blender's defaults", with(BlenderCameraType::Perspective, {1920, 1080})});
    BlenderCamera portrait = with(BlenderCameraType::Perspective, {1080, 1920});  // AUTO fits the height
    portrait.lens_mm = 35;
    portrait.shift_x = 0.1;
    portrait.shift_y = -0.05;
    cases.push_back({"perspective, portrait, shifted", portrait});
    BlenderCamera vertical = with(BlenderCameraType::Perspective, {1600, 1200});
    vertical.sensor_fit = SensorFit::Vertical;
    vertical.sensor_height_mm = 15.6;
    vertical.shift_y = 0.2;
    cases.push_back({"perspective, vertical fit, shifted", vertical});
    // Pixel aspect (fy = fx pixel_aspect_x / pixel_aspect_y), with the shift in each axis's
    // own pixels; and AUTO fitting the height because the pixels are tall.
    BlenderCamera wide_pixels = with(BlenderCameraType::Perspective, {1280, 720});
    wide_pixels.sensor_fit = SensorFit::Horizontal;
    wide_pixels.pixel_aspect_x = 2;
    wide_pixels.shift_x = -0.07;
    wide_pixels.shift_y = 0.11;
    cases.push_back({"perspective, pixel aspect 2 : 1, shifted", wide_pixels});
    BlenderCamera tall_pixels = with(BlenderCameraType::Perspective, {1000, 800});
    tall_pixels.pixel_aspect_y = 1.5;
    tall_pixels.shift_x = 0.05;
    tall_pixels.shift_y = -0.08;
    cases.push_back({"perspective, pixel aspect 1 : 1.5, AUTO fits the height", tall_pixels});
    cases.push_back({"FISHEYE_EQUIDISTANT 180 degrees", with(BlenderCameraType::FisheyeEquidistant, {1920, 1080})});
    BlenderCamera equidistant = with(BlenderCameraType::FisheyeEquidistant, {1200, 1200});
    equidistant.fisheye_fov = 1.5 * pi;
    equidistant.shift_x = -0.05;
    cases.push_back({"FISHEYE_EQUIDISTANT 270 degrees, shifted", equidistant});
    cases.push_back({"FISHEYE_EQUISOLID, Blender's defaults", with(BlenderCameraType::FisheyeEquisolid, {1920, 1080})});
    BlenderCamera equisolid = with(BlenderCameraType::FisheyeEquisolid, {1080, 1920});
    equisolid.fisheye_lens_mm = 8;
    equisolid.fisheye_fov = 1.8 * pi;
    equisolid.sensor_fit = SensorFit::Vertical;
    equisolid.sensor_height_mm = 30;
    equisolid.shift_y = 0.03;
    cases.push_back({"FISHEYE_EQUISOLID 324 degrees, vertical fit, shifted", equisolid});
    cases.push_back({"FISHEYE_LENS_POLYNOMIAL, Blender's defaults (its 50 mm perspective camera)",
                     with(BlenderCameraType::FisheyeLensPolynomial, {1920, 1080})});
    // A fisheye: theta = 0.09 r + 4e-5 r^3 (mm), 106 degrees at the top and bottom edges
    // (18 mm), 142 at the corners, rendered up to 95 degrees off the axis.
    BlenderCamera polynomial = with(BlenderCameraType::FisheyeLensPolynomial, {1200, 1600});
    polynomial.fisheye_polynomial = {0.0, -0.09, 0.0, -4e-5, 0.0};
    polynomial.fisheye_fov = radians_from_degrees(190);
    polynomial.sensor_fit = SensorFit::Vertical;
    polynomial.sensor_height_mm = 36;
    polynomial.shift_x = 0.02;
    cases.push_back({"FISHEYE_LENS_POLYNOMIAL 190 degrees, vertical fit, shifted", polynomial});
    // k1 > 0: angles negative, the image turned half a turn.
    BlenderCamera turned = with(BlenderCameraType::FisheyeLensPolynomial, {800, 800});
    turned.fisheye_polynomial = {0.0, 0.1, 0.0, 1e-5, 0.0};
    turned.fisheye_fov = pi;
    cases.push_back({"FISHEYE_LENS_POLYNOMIAL with negative angles", turned});
    cases.push_back({"EQUIRECTANGULAR, the whole sphere", with(BlenderCameraType::Equirectangular, {2048, 1024})});
    BlenderCamera band = with(BlenderCameraType::Equirectangular, {1920, 1080});
    band.longitude_min = -pi / 2;
    band.longitude_max = pi / 3;
    band.latitude_min = -pi / 4;
    band.latitude_max = pi / 6;
    band.shift_x = 0.02;
    cases.push_back({"EQUIRECTANGULAR, a band, shifted", band});
    return cases;
}

// The angle between two directions, by atan2 (accurate for small angles).
double angle(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

}  // namespace

TEST_CASE("Blender cameras: each pixel's ray is the one Cycles traces, and projects back onto the pixel") {
    for (const BlenderCase& c : blender_cases()) {
        INFO(c.name);
        const Camera libcam_camera = camera_from_blender(c.camera);
        const PreparedCamera camera(libcam_camera);
        double worst_angle = 0, worst_px = 0;
        int compared = 0;
        const std::vector<Vec2> pixels = PixelGrid{97, 55}.pixels(c.camera.size);
        for (const Vec2& pixel : pixels) {
            const std::optional<Eigen::Vector3d> theirs = test::blender_ray(c.camera, pixel.x(), pixel.y());
            if (!theirs) continue;  // black in Blender's render: outside the fisheye's circle
            const Unprojection ours = camera.unproject(pixel);
            // A polynomial with k0 != 0 gives the centre an angle |k0| in a direction Cycles
            // picks arbitrarily (up): libcam gives that one point no ray.
            const bool tilted_centre = c.camera.type == BlenderCameraType::FisheyeLensPolynomial &&
                                       c.camera.fisheye_polynomial[0] != 0 &&
                                       pixel == Vec2(libcam_camera.intrinsics.cx, libcam_camera.intrinsics.cy);
            if (tilted_centre) {
                CHECK_FALSE(ours.valid);
                continue;
            }
            REQUIRE(ours.valid);
            worst_angle = std::max(worst_angle, angle(ours.direction, *theirs));
            const Projection back = camera.project_camera_point(*theirs);
            REQUIRE(back.valid);
            worst_px = std::max(worst_px, (back.pixel - pixel).norm());
            ++compared;
        }
        INFO("worst " << worst_angle << " rad, " << worst_px << " px over " << compared << " of " << pixels.size()
                      << " pixels");
        CHECK(compared > static_cast<int>(pixels.size()) / 2);
        CHECK(worst_angle <= 1e-12);
        CHECK(worst_px <= 1e-9);
    }
}

TEST_CASE("Blender cameras: the intrinsics worked by hand") {
    // Perspective: f = W lens / sensor width = 1920 * 50 / 36; centre (W - 1) / 2.
    const Camera perspective = camera_from_blender(BlenderCamera{});
    CHECK(perspective.intrinsics.fx == Approx(1920.0 * 50 / 36).epsilon(1e-15));
    CHECK(perspective.intrinsics.cx == 959.5);
    CHECK(perspective.intrinsics.cy == 539.5);
    // Equidistant over 180 degrees: theta = pi / 2 at the image's edges, W / 2 px away.
    BlenderCamera equidistant;
    equidistant.type = BlenderCameraType::FisheyeEquidistant;
    const Camera fisheye = camera_from_blender(equidistant);
    CHECK(fisheye.lens.type == LensType::Fisheye);
    CHECK(fisheye.intrinsics.fx == Approx(1920 / std::numbers::pi).epsilon(1e-15));
    CHECK(fisheye.intrinsics.fy == Approx(1080 / std::numbers::pi).epsilon(1e-15));
    // Equisolid, 10.5 mm on a 36 mm sensor across 1920 px: f = 560 px; r = 2 f sin(theta / 2).
    BlenderCamera equisolid;
    equisolid.type = BlenderCameraType::FisheyeEquisolid;
    const PreparedCamera solid(camera_from_blender(equisolid));
    CHECK(solid.camera().intrinsics.fx == Approx(560).epsilon(1e-15));
    const double theta = 1.0;
    const Projection at_one = solid.project_camera_point(Vec3(std::sin(theta), 0, std::cos(theta)));
    REQUIRE(at_one.valid);
    CHECK(at_one.pixel.x() - 959.5 == Approx(2 * 560 * std::sin(theta / 2)).epsilon(1e-14));
    // Equirectangular over the whole sphere: longitude 0 at the centre column, 2 pi across.
    BlenderCamera equirectangular;
    equirectangular.type = BlenderCameraType::Equirectangular;
    equirectangular.size = {2048, 1024};
    const Camera lonlat = camera_from_blender(equirectangular);
    CHECK(lonlat.lens.type == LensType::Lonlat);
    CHECK(lonlat.intrinsics.fx == Approx(2048 / (2 * std::numbers::pi)).epsilon(1e-15));
    CHECK(lonlat.intrinsics.cx == Approx(1023.5).epsilon(1e-15));
    CHECK(lonlat.intrinsics.cy == Approx(511.5).epsilon(1e-15));
}

TEST_CASE("Blender cameras: a setting out of range is refused, naming it") {
    BlenderCamera bad;
    bad.lens_mm = 0;
    CHECK_THAT(test::error_of([&] { camera_from_blender(bad); }), Catch::Contains("lens: must be > 0, got 0"));
    bad = BlenderCamera{};
    bad.type = BlenderCameraType::FisheyeEquidistant;
    bad.fisheye_fov = 7;
    CHECK_THAT(test::error_of([&] { camera_from_blender(bad); }),
               Catch::Contains("fisheye_fov: must be in (0, 2 pi] radians, got 7"));
    bad = BlenderCamera{};
    bad.type = BlenderCameraType::Equirectangular;
    bad.longitude_max = bad.longitude_min;
    CHECK_THAT(test::error_of([&] { camera_from_blender(bad); }),
               Catch::Contains("longitude_max - longitude_min: must be > 0, got 0"));
    bad = BlenderCamera{};
    bad.shift_x = NAN;
    CHECK_THAT(test::error_of([&] { camera_from_blender(bad); }), Catch::Contains("shift_x: must be finite"));
}

TEST_CASE("Blender cameras back from libcam's: the same rays by Cycles' own mapping") {
    // Each Blender case to a libcam camera and back: the settings may differ (the sensor is
    // fitted horizontally, 36 mm wide where its size is free) but Cycles must trace the
    // same ray through every pixel both cameras render.
    for (const BlenderCase& c : blender_cases()) {
        INFO(c.name);
        const BlenderCamera back = blender_from_camera(camera_from_blender(c.camera));
        CHECK(back.type == c.camera.type);
        CHECK(back.size.width == c.camera.size.width);
        CHECK(back.size.height == c.camera.size.height);
        CHECK(back.sensor_fit == SensorFit::Horizontal);
        double worst = 0;
        int compared = 0;
        const std::vector<Vec2> pixels = PixelGrid{97, 55}.pixels(c.camera.size);
        for (const Vec2& pixel : pixels) {
            const std::optional<Eigen::Vector3d> theirs = test::blender_ray(c.camera, pixel.x(), pixel.y());
            const std::optional<Eigen::Vector3d> ours = test::blender_ray(back, pixel.x(), pixel.y());
            if (!theirs || !ours) continue;
            worst = std::max(worst, angle(*ours, *theirs));
            ++compared;
        }
        INFO("worst " << worst << " rad over " << compared << " pixels");
        CHECK(compared > static_cast<int>(pixels.size()) / 2);
        CHECK(worst <= 1e-12);
    }
}

TEST_CASE("Blender cameras back from libcam's: the settings worked by hand, and cameras Blender cannot draw") {
    // A FISHEYE_LENS_POLYNOMIAL camera at 40 px per mm on a 1200x900 image, its axis at
    // (610.5, 440.5): the sensor is 1200 / 40 = 30 mm wide; the axis is 11 px right of the
    // centre (599.5) and 9 px above it (449.5). Cycles' shift moves the axis left and down
    // (its U = u / W + shift_x, V = v / H + shift_y, v up): shift_x = -11 / 1200,
    // shift_y = -9 / 900.
    Camera camera;
    camera.size = {1200, 900};
    camera.intrinsics = {40.0, 40.0, 610.5, 440.5, 0.0};
    camera.lens = {LensType::LensPolynomial, {0.0, -0.05, 0.0, -1e-5, 0.0}};
    const BlenderCamera blender = blender_from_camera(camera);
    CHECK(blender.type == BlenderCameraType::FisheyeLensPolynomial);
    CHECK(blender.sensor_width_mm == Approx(30.0).epsilon(1e-15));
    CHECK(blender.shift_x == Approx(-11.0 / 1200).epsilon(1e-13));
    CHECK(blender.shift_y == Approx(-9.0 / 900).epsilon(1e-13));
    CHECK(blender.fisheye_polynomial[1] == -0.05);
    CHECK(blender.fisheye_polynomial[3] == -1e-5);
    // theta = 0.05 r + 1e-5 r^3 is one-to-one up to pi at r = 44.8 mm (the root of
    // 1e-5 r^3 + 0.05 r - pi): fisheye_fov covers the whole domain, 2 pi.
    CHECK(blender.fisheye_fov == Approx(2 * std::numbers::pi).epsilon(1e-12));

    camera.lens = {LensType::OpenCv4, {0.1, 0.0, 0.0, 0.0}};
    CHECK_THAT(test::error_of([&] { blender_from_camera(camera); }),
               Catch::Contains("Blender has no camera for OPENCV4"));
    // A pinhole with fy = 41 / 40 fx: to Blender, pixels 1.025 times wider than tall (fewer
    // pixels per unit across than down).
    camera.lens = {LensType::Pinhole, {}};
    camera.intrinsics.fy = 41.0;
    const BlenderCamera tall = blender_from_camera(camera);
    CHECK(tall.pixel_aspect_x == Approx(1.025).epsilon(1e-15));
    CHECK(tall.pixel_aspect_y == 1.0);
    camera.intrinsics.fy = 39.0;
    CHECK(blender_from_camera(camera).pixel_aspect_y == Approx(40.0 / 39.0).epsilon(1e-15));
    camera.intrinsics.skew = 0.5;
    CHECK_THAT(test::error_of([&] { blender_from_camera(camera); }),
               Catch::Contains("Blender's perspective camera has no skew, got 0.5"));
    camera.intrinsics.skew = 0.0;
    camera.intrinsics.fy = 40.0;
    camera.lens = {LensType::Fisheye, {0.01, 0.0, 0.0, 0.0}};
    CHECK_THAT(test::error_of([&] { blender_from_camera(camera); }),
               Catch::Contains("FISHEYE_EQUIDISTANT is FISHEYE with zero coefficients"));
}
