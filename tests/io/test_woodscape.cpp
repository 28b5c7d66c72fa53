// Valeo's WoodScape calibration JSON: small documents in the dataset's layout (its
// scripts/calibration/front.json), whose pixels are worked out here from WoodScape's
// published formula (its calibration_readme.txt: rho = k1 theta + ... + k4 theta^4,
// u = rho X / chi + cx + W / 2 - 0.5, v = rho Y / chi a + cy + H / 2 - 0.5) in long double,
// and checked against the same numbers worked out beforehand in 40-digit arithmetic.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "libcam/camera/camera.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "error_message.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using libcam::test::file_error_of;

namespace {

// The lens and image of the fixture below.
constexpr long double kK[] = {330.5L, -25.25L, 40.125L, -6.0625L};
constexpr long double kCxOffset = 2.5L, kCyOffset = -1.75L, kAspect = 1.0625L, kWidth = 1280, kHeight = 966;

// A front camera looking along the vehicle's x (forward), its x to the vehicle's right
// (-y) and its y down (-z), 3.7 m ahead of the rear axle and 0.66 m up: camera to vehicle
// is R = [0 0 1; -1 0 0; 0 -1 0], the quaternion (x, y, z, w) = (-0.5, 0.5, -0.5, 0.5).
std::string front_camera(const std::string& intrinsic_extra = "", const std::string& quaternion = "-0.5, 0.5, -0.5, 0.5") {
    return R"({
  "extrinsic": {"quaternion": [)" + quaternion + R"(], "translation": [3.7, 0.0, 0.66]},
  "intrinsic": {
    "aspect_ratio": 1.0625, "cx_offset": 2.5, "cy_offset": -1.75, "height": 966.0,
    "k1": 330.5, "k2": -25.25, "k3": 40.125, "k4": -6.0625,)" + intrinsic_extra + R"(
    "model": "radial_poly", "poly_order": 4, "width": 1280.0
  },
  "name": "FV"
}
)";
}

// WoodScape's pixel of a camera-frame point, its readme's formula in long double.
Vec2 woodscape_pixel(long double x, long double y, long double z) {
    const long double chi = std::sqrt(x * x + y * y), theta = std::atan2(chi, z);
    long double rho = 0, power = 1;
    for (long double k : kK) rho += k * (power *= theta);
    const long double u = rho * x / chi + kCxOffset + kWidth / 2 - 0.5L;
    const long double v = rho * y / chi * kAspect + kCyOffset + kHeight / 2 - 0.5L;
    return {static_cast<double>(u), static_cast<double>(v)};
}

}  // namespace

TEST_CASE("WoodScape: a calibration's pixels are its readme's formula, in front, aside and behind the camera",
          "[io][woodscape]") {
    const test::TempDir dir;
    const std::filesystem::path path = write_file(dir, "00000_FV.json", front_camera());
    const CameraSet set = read_camera_set(path);
    CHECK(set.format == CameraFormat::Woodscape);  // a .json told by its keys
    REQUIRE(set.cameras.size() == 1);
    CHECK(set.cameras[0].name == "FV");
    const Camera& camera = set.cameras[0].file.camera;
    CHECK(camera.lens.type == LensType::ThetaPolynomial);
    CHECK(camera.lens.coefficients == std::vector<double>{330.5, -25.25, 40.125, -6.0625});
    CHECK(camera.intrinsics.fx == 1.0);
    CHECK(camera.intrinsics.fy == 1.0625);
    CHECK(camera.intrinsics.cx == 642.0);    // 1280 / 2 + 2.5 - 0.5
    CHECK(camera.intrinsics.cy == 480.75);   // 966 / 2 - 1.75 - 0.5
    const PreparedCamera prepared(camera);
    struct Case {
        Vec3 point;
        Vec2 expected;  // worked out beforehand in 40 digits
    };
    const Case cases[] = {
        {{1, 2, 3}, {736.29820437782158106, 681.13368430287085975}},
        {{2, 1, 10}, {706.30666966534431576, 514.91291825971416775}},
        {{3, -1, -1}, {1326.4930573615422352, 238.32537551778712502}},  // 108 degrees off the axis
    };
    for (const Case& c : cases) {
        INFO(c.point.transpose());
        const Vec2 formula = woodscape_pixel(c.point.x(), c.point.y(), c.point.z());
        CHECK(formula.x() == Approx(c.expected.x()).margin(1e-9));
        CHECK(formula.y() == Approx(c.expected.y()).margin(1e-9));
        const Projection projection = prepared.project_camera_point(c.point);
        REQUIRE(projection.valid);
        CHECK(projection.pixel.x() == Approx(c.expected.x()).margin(1e-9));
        CHECK(projection.pixel.y() == Approx(c.expected.y()).margin(1e-9));
        // And back: the pixel's ray is the point's direction.
        const Unprojection ray = prepared.unproject(projection.pixel);
        REQUIRE(ray.valid);
        CHECK((ray.direction.normalized() - c.point.normalized()).norm() < 1e-12);
    }
    // The optical axis is the principal point.
    const Projection centre = prepared.project_camera_point(Vec3(0, 0, 1));
    REQUIRE(centre.valid);
    CHECK(centre.pixel.x() == 642.0);
    CHECK(centre.pixel.y() == 480.75);
}

TEST_CASE("WoodScape: the extrinsic is camera to vehicle (ISO 8855), with scipy's scalar-last quaternion",
          "[io][woodscape]") {
    const CameraFile file = parse_camera(front_camera(), CameraFormat::Woodscape, "FV.json");
    const Pose& pose = file.camera.pose;  // vehicle to camera
    // The camera's centre is the file's translation, in the vehicle frame.
    CHECK((-(pose.R.transpose() * pose.t) - Vec3(3.7, 0.0, 0.66)).norm() < 1e-15);
    // 10 m ahead of the camera, 2 m to its right (vehicle -y) and 1 m below (vehicle -z) is
    // the camera-frame point (2, 1, 10).
    const Vec3 vehicle_point(3.7 + 10, -2, 0.66 - 1);
    CHECK((pose.R * vehicle_point + pose.t - Vec3(2, 1, 10)).norm() < 1e-13);
    const Projection projection = PreparedCamera(file.camera).project(vehicle_point);
    REQUIRE(projection.valid);
    CHECK(projection.pixel.x() == Approx(706.30666966534431576).margin(1e-9));
    CHECK(projection.pixel.y() == Approx(514.91291825971416775).margin(1e-9));
}

TEST_CASE("WoodScape: written back in its own layout, the same numbers, and what it cannot hold refused",
          "[io][woodscape]") {
    const CameraFile file = parse_camera(front_camera(), CameraFormat::Woodscape, "FV.json");
    const std::string text = format_camera(file.camera, CameraFormat::Woodscape);
    CHECK_THAT(text, Catch::Contains("\"model\": \"radial_poly\"") && Catch::Contains("\"k3\": 40.125") &&
                         Catch::Contains("\"cx_offset\": 2.5") && Catch::Contains("\"cy_offset\": -1.75") &&
                         Catch::Contains("\"aspect_ratio\": 1.0625"));
    const Camera back = parse_camera(text, CameraFormat::Woodscape, "back.json").camera;
    CHECK(back.lens == file.camera.lens);
    CHECK(back.intrinsics.fx == file.camera.intrinsics.fx);
    CHECK(back.intrinsics.fy == file.camera.intrinsics.fy);
    CHECK(back.intrinsics.cx == file.camera.intrinsics.cx);
    CHECK(back.intrinsics.cy == file.camera.intrinsics.cy);
    CHECK((back.pose.R - file.camera.pose.R).norm() < 1e-15);
    CHECK((back.pose.t - file.camera.pose.t).norm() < 1e-14);
    // A camera with fx = 2 is the same lens with the coefficients in pixels doubled.
    Camera doubled = file.camera;
    doubled.intrinsics.fx = 2;
    doubled.intrinsics.fy = 2.125;
    for (double& k : doubled.lens.coefficients) k /= 2;
    CHECK_THAT(format_camera(doubled, CameraFormat::Woodscape), Catch::Contains("\"k1\": 330.5"));
    Camera fisheye = file.camera;
    fisheye.lens = {LensType::Fisheye, {0, 0, 0, 0}};
    CHECK_THROWS_WITH(format_camera(fisheye, CameraFormat::Woodscape),
                      Catch::Contains("holds a THETA_POLYNOMIAL lens (radial_poly) only; this camera's is FISHEYE"));
    Camera skewed = file.camera;
    skewed.intrinsics.skew = 0.25;
    CHECK_THROWS_WITH(format_camera(skewed, CameraFormat::Woodscape), Catch::Contains("no skew"));
}

TEST_CASE("WoodScape: a malformed calibration names the file, the field and the value", "[io][woodscape]") {
    const auto error = [](const std::string& text) {
        return file_error_of([&] { parse_camera(text, CameraFormat::Woodscape, "FV.json"); });
    };
    CHECK_THAT(error(front_camera("", "0.5, 0.5, 0.5, 0.6")),
               Catch::Contains("FV.json") && Catch::Contains("extrinsic.quaternion") && Catch::Contains("not 1"));
    CHECK_THAT(error(front_camera("", "0.5, 0.5, 0.5")),
               Catch::Contains("extrinsic.quaternion") && Catch::Contains("expected 4 numbers, got 3"));
    std::string no_k2 = front_camera();
    no_k2.replace(no_k2.find("\"k2\": -25.25,"), 13, "");
    CHECK_THAT(error(no_k2), Catch::Contains("intrinsic.k2") && Catch::Contains("missing"));
    std::string other_model = front_camera();
    other_model.replace(other_model.find("radial_poly"), 11, "cylindrical");
    CHECK_THAT(error(other_model), Catch::Contains("intrinsic.model") && Catch::Contains("'cylindrical'"));
    std::string order = front_camera();
    order.replace(order.find("\"poly_order\": 4"), 15, "\"poly_order\": 5");
    CHECK_THAT(error(order), Catch::Contains("intrinsic.poly_order") && Catch::Contains("must be 4"));
    std::string flat = front_camera();
    flat.replace(flat.find("\"k1\": 330.5"), 11, "\"k1\": -330.5");
    CHECK_THAT(error(flat), Catch::Contains("FV.json") && Catch::Contains("k1") && Catch::Contains("-330.5"));
    std::string aspect = front_camera();
    aspect.replace(aspect.find("\"aspect_ratio\": 1.0625"), 22, "\"aspect_ratio\": 0");
    CHECK_THAT(error(aspect), Catch::Contains("intrinsic.aspect_ratio") && Catch::Contains("must be positive, got 0"));
    std::string width = front_camera();
    width.replace(width.find("\"width\": 1280.0"), 15, "\"width\": 1280.5");
    CHECK_THAT(error(width), Catch::Contains("intrinsic.width"));
}
