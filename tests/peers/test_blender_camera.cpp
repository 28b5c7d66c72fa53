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
#include <utility>

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
    // Pixel aspect on the panoramic cameras: the equisolid and polynomial fisheyes' sensor is
    // S along the fitted side and in proportion to the pixels times their aspect along the
    // other (sensor_height then unused); the equidistant fisheye and the equirectangular
    // camera divide by W and H alone.
    BlenderCamera wide_solid = with(BlenderCameraType::FisheyeEquisolid, {640, 480});
    wide_solid.sensor_fit = SensorFit::Horizontal;
    wide_solid.sensor_height_mm = 5;  // not Cycles' sensor height for a horizontal fit
    wide_solid.pixel_aspect_x = 1.5;
    wide_solid.fisheye_lens_mm = 7;
    wide_solid.fisheye_fov = 1.7 * pi;
    wide_solid.shift_x = 0.06;
    wide_solid.shift_y = -0.04;
    cases.push_back({"FISHEYE_EQUISOLID, pixel aspect 1.5 : 1, shifted", wide_solid});
    BlenderCamera tall_solid = with(BlenderCameraType::FisheyeEquisolid, {1000, 800});
    tall_solid.pixel_aspect_y = 1.6;  // AUTO: 1000 x 1 < 800 x 1.6, the height fitted
    tall_solid.sensor_width_mm = 30;  // AUTO measures with the width's setting
    tall_solid.shift_y = 0.1;
    cases.push_back({"FISHEYE_EQUISOLID, pixel aspect 1 : 1.6, AUTO fits the height", tall_solid});
    BlenderCamera vertical_solid = with(BlenderCameraType::FisheyeEquisolid, {900, 700});
    vertical_solid.sensor_fit = SensorFit::Vertical;
    vertical_solid.sensor_height_mm = 20;
    vertical_solid.pixel_aspect_x = 1.25;
    vertical_solid.shift_x = -0.08;
    cases.push_back({"FISHEYE_EQUISOLID, pixel aspect 1.25 : 1, vertical fit", vertical_solid});
    BlenderCamera wide_polynomial = polynomial;
    wide_polynomial.pixel_aspect_y = 1.3;
    wide_polynomial.shift_y = -0.05;
    cases.push_back({"FISHEYE_LENS_POLYNOMIAL, pixel aspect 1 : 1.3, vertical fit, shifted", wide_polynomial});
    BlenderCamera aspect_equidistant = equidistant;
    aspect_equidistant.size = {1200, 900};
    aspect_equidistant.pixel_aspect_x = 2;
    aspect_equidistant.shift_y = 0.07;
    cases.push_back({"FISHEYE_EQUIDISTANT, pixel aspect 2 : 1 (no part), shifted", aspect_equidistant});
    cases.push_back({"EQUIRECTANGULAR, the whole sphere", with(BlenderCameraType::Equirectangular, {2048, 1024})});
    BlenderCamera band = with(BlenderCameraType::Equirectangular, {1920, 1080});
    band.longitude_min = -pi / 2;
    band.longitude_max = pi / 3;
    band.latitude_min = -pi / 4;
    band.latitude_max = pi / 6;
    band.shift_x = 0.02;
    cases.push_back({"EQUIRECTANGULAR, a band, shifted", band});
    band.pixel_aspect_y = 3;
    cases.push_back({"EQUIRECTANGULAR, a band, pixel aspect 1 : 3 (no part)", band});
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
               Catch::Contains("fisheye_fov: must be in [0.1745, 2 pi] radians (Blender takes 10 degrees or more), got 7"));
    bad.fisheye_fov = 0.17;  // Blender would draw its 10 degrees
    CHECK_THAT(test::error_of([&] { camera_from_blender(bad); }), Catch::Contains("got 0.17"));
    bad = BlenderCamera{};
    bad.type = BlenderCameraType::FisheyeEquisolid;
    bad.pixel_aspect_x = 250;
    CHECK_THAT(test::error_of([&] { camera_from_blender(bad); }),
               Catch::Contains("pixel_aspect_x: Blender takes 1 to 200, got 250"));
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

TEST_CASE("Blender cameras: the panoramic fisheyes' fx != fy worked by hand from Cycles' sensor") {
    // 640x480, sensor fitted across at 36 mm, pixels 1.5 times wider than tall: Cycles'
    // sensor is 36 x 36 (480 x 1) / (640 x 1.5) = 18 mm high, whatever sensor_height says.
    // A 7 mm equisolid lens: fx = 7 x 640 / 36, fy = 7 x 480 / 18 = 1.5 fx. The shift moves
    // the axis by 0.06 x 640 px left and 0.04 x 480 px down: (319.5 - 38.4, 239.5 - 19.2).
    BlenderCamera wide;
    wide.type = BlenderCameraType::FisheyeEquisolid;
    wide.size = {640, 480};
    wide.sensor_fit = SensorFit::Horizontal;
    wide.sensor_height_mm = 5;
    wide.pixel_aspect_x = 1.5;
    wide.fisheye_lens_mm = 7;
    wide.shift_x = 0.06;
    wide.shift_y = -0.04;
    const Camera solid = camera_from_blender(wide);
    CHECK(solid.intrinsics.fx == Approx(7.0 * 640 / 36).epsilon(1e-15));
    CHECK(solid.intrinsics.fy == Approx(7.0 * 480 / 18).epsilon(1e-15));
    CHECK(solid.intrinsics.cx == Approx(281.1).epsilon(1e-15));
    CHECK(solid.intrinsics.cy == Approx(220.3).epsilon(1e-15));
    // 1000x800 with pixels 1.6 times taller than wide: AUTO fits the height (1000 < 1280)
    // and measures it with sensor_width, 30 mm; the sensor is 30 x 1000 / 1280 = 23.4375 mm
    // wide. A 10.5 mm lens: fy = 10.5 x 800 / 30 = 280, fx = 10.5 x 1000 / 23.4375 = 448.
    BlenderCamera tall;
    tall.type = BlenderCameraType::FisheyeEquisolid;
    tall.size = {1000, 800};
    tall.pixel_aspect_y = 1.6;
    tall.sensor_width_mm = 30;
    const Camera tall_solid = camera_from_blender(tall);
    CHECK(tall_solid.intrinsics.fx == Approx(448).epsilon(1e-15));
    CHECK(tall_solid.intrinsics.fy == Approx(280).epsilon(1e-15));
    // The polynomial fisheye on that sensor: pixels per mm, 1000 / 23.4375 and 800 / 30.
    tall.type = BlenderCameraType::FisheyeLensPolynomial;
    const Camera tall_polynomial = camera_from_blender(tall);
    CHECK(tall_polynomial.intrinsics.fx == Approx(1000 / 23.4375).epsilon(1e-15));
    CHECK(tall_polynomial.intrinsics.fy == Approx(800 / 30.0).epsilon(1e-15));
    // The equidistant fisheye takes no notice of the pixel aspect: fx = W / fov, fy = H / fov.
    tall.type = BlenderCameraType::FisheyeEquidistant;
    const Camera tall_equidistant = camera_from_blender(tall);
    CHECK(tall_equidistant.intrinsics.fx == Approx(1000 / std::numbers::pi).epsilon(1e-15));
    CHECK(tall_equidistant.intrinsics.fy == Approx(800 / std::numbers::pi).epsilon(1e-15));
}

namespace {

Camera libcam_camera(ImageSize size, Intrinsics k, Lens lens) {
    Camera camera;
    camera.size = size;
    camera.intrinsics = k;
    camera.lens = std::move(lens);
    return camera;
}

}  // namespace

TEST_CASE("Blender cameras: libcam's camera to Blender's and back is the same camera, fx != fy and the principal "
          "point off centre") {
    constexpr double pi = std::numbers::pi;
    const std::vector<std::pair<std::string, Camera>> cameras = {
        {"EQUISOLID, fy > fx", libcam_camera({320, 240}, {150, 210, 171.3, 108.8, 0}, {LensType::Equisolid, {}})},
        {"EQUISOLID, fy < fx", libcam_camera({320, 240}, {210, 150, 140.2, 131.9, 0}, {LensType::Equisolid, {}})},
        // fx / W = 4: a 144 mm lens on the 36 mm sensor, past Blender's 100 mm; a 25 mm sensor.
        {"EQUISOLID, narrow", libcam_camera({300, 200}, {1200, 1300, 160.5, 90.25, 0}, {LensType::Equisolid, {}})},
        {"FISHEYE_LENS_POLYNOMIAL, fy > fx",
         libcam_camera({640, 480}, {640 / 36.0, 1.2 * 640 / 36.0, 301.7, 250.1, 0},
                       {LensType::LensPolynomial, {0.0, -0.06, 1e-4, -3e-5, 2e-7}})},
        {"FISHEYE, W / fx = H / fy = 0.9 x 2 pi, off centre",
         libcam_camera({800, 600}, {800 / (1.8 * pi), 600 / (1.8 * pi), 390.2, 310.7, 0}, {LensType::Fisheye, {0, 0, 0, 0}})},
        {"LONLAT, a band", libcam_camera({640, 360}, {130, 150, 320.7, 170.2, 0}, {LensType::Lonlat, {}})},
        {"PINHOLE, fx != fy", libcam_camera({640, 480}, {500, 560, 330.1, 228.4, 0}, {LensType::Pinhole, {}})},
        // fx < W / 36: a 1 mm lens (Blender's least) on a 64 mm sensor.
        {"PINHOLE, 176 degrees across", libcam_camera({640, 480}, {10, 10, 319.5, 239.5, 0}, {LensType::Pinhole, {}})},
    };
    for (const auto& [name, camera] : cameras) {
        INFO(name);
        const BlenderCamera blender = blender_from_camera(camera);
        const Camera back = camera_from_blender(blender);
        CHECK(back.size == camera.size);
        CHECK(back.lens.type == camera.lens.type);
        CHECK(back.intrinsics.fx == Approx(camera.intrinsics.fx).epsilon(1e-13));
        CHECK(back.intrinsics.fy == Approx(camera.intrinsics.fy).epsilon(1e-13));
        CHECK(back.intrinsics.cx == Approx(camera.intrinsics.cx).margin(1e-10));
        CHECK(back.intrinsics.cy == Approx(camera.intrinsics.cy).margin(1e-10));
        CHECK(back.intrinsics.skew == 0.0);
        CHECK(back.lens.coefficients == camera.lens.coefficients);
        // Within Blender's ranges, so that bpy keeps what it is given.
        CHECK(blender.pixel_aspect_x >= 1);
        CHECK(blender.pixel_aspect_y >= 1);
        CHECK(blender.sensor_width_mm >= 1);
        if (blender.type == BlenderCameraType::FisheyeEquisolid) CHECK(blender.fisheye_lens_mm <= 100);
        if (blender.type == BlenderCameraType::Perspective) CHECK(blender.lens_mm >= 1);
    }
}

namespace {

// The farthest libcam's camera puts the ray Cycles traces through a pixel (Cycles' formula,
// blender_reference.hpp) from that pixel, over a 41x31 grid of the image.
double worst_cycles_ray_error(const Camera& camera, const BlenderCamera& blender) {
    const PreparedCamera ours(camera);
    double worst = 0;
    for (const Vec2& pixel : PixelGrid{41, 31}.pixels(camera.size)) {
        const std::optional<Eigen::Vector3d> theirs = test::blender_ray(blender, pixel.x(), pixel.y());
        REQUIRE(theirs);
        const Projection back = ours.project_camera_point(*theirs);
        REQUIRE(back.valid);
        worst = std::max(worst, (back.pixel - pixel).norm());
    }
    return worst;
}

}  // namespace

TEST_CASE("Blender cameras: an equidistant fisheye with W / fx != H / fy, off centre, is the polynomial fisheye "
          "theta = r, and Cycles traces its rays") {
    // W / fx = 4.57 rad across, H / fy = 2.82 rad down: FISHEYE_EQUIDISTANT's one field of view
    // cannot draw it. theta = r with r in libcam's m (k1 = -1): the sensor W / fx mm wide, the
    // pixel aspect fy / fx, the shift the principal point's offset.
    const Camera camera = libcam_camera({320, 240}, {70, 85, 171.3, 108.8, 0}, {LensType::Fisheye, {0, 0, 0, 0}});
    const BlenderCamera blender = blender_from_camera(camera);
    CHECK(blender.type == BlenderCameraType::FisheyeLensPolynomial);
    CHECK(blender.sensor_width_mm == Approx(320.0 / 70).epsilon(1e-15));
    CHECK(blender.fisheye_polynomial[0] == 0.0);
    CHECK(blender.fisheye_polynomial[1] == -1.0);
    CHECK(blender.pixel_aspect_x == Approx(85.0 / 70).epsilon(1e-15));
    CHECK(blender.pixel_aspect_y == 1.0);
    CHECK(blender.shift_x == Approx((160 - 0.5 - 171.3) / 320).epsilon(1e-13));
    CHECK(blender.shift_y == Approx((108.8 - 120 + 0.5) / 240).epsilon(1e-13));
    CHECK(worst_cycles_ray_error(camera, blender) <= 1e-9);
}

TEST_CASE("Blender cameras: a polynomial fisheye narrower than Blender's 1 mm sensor takes rescaled coefficients") {
    // fx = 2 W: the sensor would be 0.5 mm wide. On a 1 mm sensor the radius in Blender's mm
    // is half libcam's m: k_i becomes k_i / 2^i, and Cycles traces the same rays.
    const Camera camera = libcam_camera({400, 300}, {800, 880, 210.3, 140.6, 0},
                                        {LensType::LensPolynomial, {0.0, -1.0, 0.0, -0.05, 0.0}});
    const BlenderCamera blender = blender_from_camera(camera);
    CHECK(blender.sensor_width_mm == 1.0);
    CHECK(blender.fisheye_polynomial[1] == -0.5);
    CHECK(blender.fisheye_polynomial[3] == Approx(-0.05 / 8).epsilon(1e-15));
    CHECK(worst_cycles_ray_error(camera, blender) <= 1e-9);
}

TEST_CASE("Blender cameras: what Cycles' panoramic cameras cannot draw is refused, saying what does not fit") {
    // Past 360 degrees, and under Blender's 10.
    Camera fisheye = libcam_camera({800, 600}, {100, 75, 399.5, 299.5, 0}, {LensType::Fisheye, {0, 0, 0, 0}});
    CHECK_THAT(test::error_of([&] { blender_from_camera(fisheye); }), Catch::Contains("fisheye_fov: must be in"));
    fisheye.intrinsics = {8000, 6000, 399.5, 299.5, 0};
    CHECK_THAT(test::error_of([&] { blender_from_camera(fisheye); }), Catch::Contains("got 0.1"));
    // fy / fx beyond the pixel aspect's 200, and skew.
    Camera solid = libcam_camera({800, 600}, {100, 30000, 399.5, 299.5, 0}, {LensType::Equisolid, {}});
    CHECK_THAT(test::error_of([&] { blender_from_camera(solid); }),
               Catch::Contains("Blender draws FISHEYE_EQUISOLID with fy / fx from 1/200 to 200"));
    solid.intrinsics = {300, 300, 399.5, 299.5, 0.5};
    CHECK_THAT(test::error_of([&] { blender_from_camera(solid); }),
               Catch::Contains("Blender's FISHEYE_EQUISOLID has no skew, got 0.5"));
    // An equisolid lens narrower than a 100 mm lens on a 1 mm sensor.
    solid.intrinsics = {90000, 90000, 399.5, 299.5, 0};
    CHECK_THAT(test::error_of([&] { blender_from_camera(solid); }), Catch::Contains("fx / W up to 100"));
}
