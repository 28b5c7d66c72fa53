// NVIDIA DriveWorks' rig.json: small rigs written by hand in DriveWorks' layout (properties
// as strings, "polynomial" with its "polynomial-type", the older "bw-poly"), whose rays and
// pixels are NVIDIA's published F-theta formula (NCore's FThetaCameraModelParameters,
// gsplat's and 3DGUT's FThetaCameraModel: the sensor offset A^-1 (p - c), A = [c d; e 1],
// the angle b1 r + ... + b5 r^5 at its length r) worked out beforehand in 40-digit
// arithmetic (mpmath), and whose poses are worked by hand (FLU axes, roll-pitch-yaw in
// degrees as Rz(yaw) Ry(pitch) Rx(roll)).

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <string>

#include "error_message.hpp"
#include "libcam/camera/camera.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using libcam::test::file_error_of;

namespace {

// A front camera (string properties, as DriveWorks writes them, with an affine and the
// nominal pose corrected), a lidar, and a rear camera (number properties, "bw-poly")
// looking backwards.
std::string rig(const std::string& front_properties_extra = "",
                const std::string& polynomial = R"("polynomial": "0 0.0017 1.2e-08 -3.5e-11 1.1e-14",
          "polynomial-type": "pixeldistance-to-angle",)") {
    return R"({"rig": {"sensors": [
  {"name": "camera:front:wide:120fov", "protocol": "camera.gmsl",
   "properties": {"Model": "ftheta", "cx": "959.5", "cy": "603.25", "width": "1920", "height": "1208", )" +
           polynomial + front_properties_extra + R"(
          "linear-c": "1.0004", "linear-d": "0.0002", "linear-e": "-0.0001"},
   "nominalSensor2Rig_FLU": {"roll-pitch-yaw": [0.5, 2.0, -1.0], "t": [1.7, 0.0, 1.45]},
   "correction_sensor_R_FLU": {"roll-pitch-yaw": [0.1, -0.2, 0.05]},
   "correction_rig_T": [0.01, 0.0, -0.02]},
  {"name": "lidar:roof", "protocol": "lidar.socket", "properties": {"device": "x"}},
  {"name": "camera:rear", "protocol": "camera.virtual",
   "properties": {"Model": "ftheta", "cx": 639.5, "cy": 359.5, "width": 1280, "height": 720,
                  "bw-poly": "0 0.0025 -1e-07 2e-10 -1e-13 1e-17"},
   "nominalSensor2Rig_FLU": {"roll-pitch-yaw": [0, 0, 180], "t": [-1.0, 0, 1.2]}}
]}}
)";
}

}  // namespace

TEST_CASE("DriveWorks rig: an ftheta camera's rays and pixels are NVIDIA's formula, past 90 degrees too",
          "[io][driveworks]") {
    const test::TempDir dir;
    const CameraSet set = read_camera_set(write_file(dir, "rig.json", rig()));
    CHECK(set.format == CameraFormat::DriveworksRig);  // a .json told by its keys
    REQUIRE(set.cameras.size() == 2);                  // the lidar skipped
    CHECK(set.cameras[0].name == "camera:front:wide:120fov");
    CHECK(set.cameras[1].name == "camera:rear");
    const Camera& front = set.cameras[0].file.camera;
    CHECK(front.lens.type == LensType::FTheta);
    CHECK(front.size.width == 1920);
    CHECK(front.size.height == 1208);
    CHECK(front.intrinsics.cx == 959.5);
    CHECK(front.intrinsics.cy == 603.25);
    CHECK(front.lens.coefficients[8] == std::numbers::pi);  // a rig holds no max_angle
    const PreparedCamera prepared(front);
    // The camera-frame ray through pixel (1500, 300).
    const Unprojection ray = prepared.unproject(Vec2(1500, 300));
    REQUIRE(ray.valid);
    const Vec3 expected_ray(0.756999334637103218, -0.42476446710273101834, 0.49651500968844432171);
    CHECK((ray.direction.normalized() - expected_ray).norm() < 1e-13);
    struct Case {
        Vec3 point;
        Vec2 pixel;
    };
    const Case cases[] = {
        {{1, -0.5, 2}, {1227.6535502265668594, 469.18662854313097434}},  // 29.2 degrees off the axis
        {{3, 1, -0.5}, {1931.2425071672738842, 926.91595069471703274}},  // 99.0 degrees: behind the camera
    };
    for (const Case& c : cases) {
        INFO(c.point.transpose());
        const Projection projection = prepared.project_camera_point(c.point);
        REQUIRE(projection.valid);
        CHECK((projection.pixel - c.pixel).norm() < 1e-9);
        const Unprojection back = prepared.unproject(c.pixel);
        REQUIRE(back.valid);
        CHECK((back.direction.normalized() - c.point.normalized()).norm() < 1e-12);
    }
    // The optical axis is the principal point.
    const Projection centre = prepared.project_camera_point(Vec3(0, 0, 1));
    REQUIRE(centre.valid);
    CHECK(centre.pixel.x() == 959.5);
    CHECK(centre.pixel.y() == 603.25);
}

TEST_CASE("DriveWorks rig: a forward polynomial (angle-to-pixeldistance) is FTHETA_FORWARD, its pixels NVIDIA's formula",
          "[io][driveworks]") {
    // A 3840x2160 camera whose calibrated polynomial is the forward one: 1200 t - 15 t^2 -
    // 40 t^3 + 6 t^4 pixels at the angle t; pixels and the ray worked out beforehand in 40
    // digits (the ray's angle solved from the polynomial).
    const std::string text = R"({"rig": {"sensors": [{"name": "camera:front:tele", "protocol": "camera.gmsl",
  "properties": {"Model": "ftheta", "cx": "1919.5", "cy": "1079.5", "width": "3840", "height": "2160",
                 "polynomial": "0 1200 -15 -40 6", "polynomial-type": "angle-to-pixeldistance",
                 "linear-c": "1.0002", "linear-d": "0.0001", "linear-e": "-0.0003"},
  "nominalSensor2Rig_FLU": {"roll-pitch-yaw": [0, 0, 0], "t": [2, 0, 1.5]}}]}})";
    const Camera camera = parse_camera(text, CameraFormat::DriveworksRig, "rig.json").camera;
    CHECK(camera.lens.type == LensType::FThetaForward);
    CHECK(camera.intrinsics.fx == 1200.0);
    const PreparedCamera prepared(camera);
    const std::pair<Vec3, Vec2> cases[] = {
        {{1, -0.5, 2}, {2458.8285911512300023, 809.71437369098598195}},
        {{3, 1, -0.5}, {3699.228678250189517, 1672.0707076481368835}},  // 99 degrees off the axis
    };
    for (const auto& [point, pixel] : cases) {
        INFO(point.transpose());
        const Projection projection = prepared.project_camera_point(point);
        REQUIRE(projection.valid);
        CHECK((projection.pixel - pixel).norm() < 1e-9);
    }
    const Unprojection ray = prepared.unproject(Vec2(3000, 400));  // 64 degrees off the axis
    REQUIRE(ray.valid);
    CHECK((ray.direction.normalized() - Vec3(0.76120832996296991774, -0.47854256897192122903, 0.43767440875237419749))
              .norm() < 1e-13);
    // Written back as the forward polynomial, the same numbers.
    const std::string written = format_camera(camera, CameraFormat::DriveworksRig);
    CHECK_THAT(written, Catch::Contains("\"angle-to-pixeldistance\"") && Catch::Contains("\"0 1200 -15 -40 6 0\""));
}

TEST_CASE("DriveWorks rig: a sensor's place is in the rig's FLU frame, roll-pitch-yaw in degrees, with corrections",
          "[io][driveworks]") {
    const CameraSet set = parse_camera_set(rig(), CameraFormat::DriveworksRig, "rig.json");
    REQUIRE(set.cameras.size() == 2);
    // The rear camera, turned 180 degrees about the rig's up axis, 1 m behind the rear axle
    // and 1.2 m up: it looks along -x, its image's right is the rig's +y (left), its
    // image's down the rig's -z. The rig point (-11, 2, 0.2) is 10 m behind it, 2 m to the
    // rig's left and 1 m below: the camera point (2, 1, 10).
    const Pose& rear = set.cameras[1].file.camera.pose;
    CHECK((rear.R * Vec3(-11, 2, 0.2) + rear.t - Vec3(2, 1, 10)).norm() < 1e-14);
    CHECK((-(rear.R.transpose() * rear.t) - Vec3(-1, 0, 1.2)).norm() < 1e-15);
    // The front camera: nominal roll-pitch-yaw (0.5, 2, -1) degrees turned further by the
    // correction (0.1, -0.2, 0.05), placed at t + correction_rig_T = (1.71, 0, 1.43); the
    // rig point (11.71, -3, 0.43) in its frame, worked out beforehand in 40 digits.
    const Pose& front = set.cameras[0].file.camera.pose;
    CHECK((-(front.R.transpose() * front.t) - Vec3(1.71, 0, 1.43)).norm() < 1e-14);
    const Vec3 in_camera = front.R * Vec3(11.71, -3.0, 0.43) + front.t;
    CHECK((in_camera - Vec3(2.8405127649545417917, 0.65415978677872831451, 10.074897627544009577)).norm() < 1e-13);
    // The rear camera's "bw-poly" has six coefficients (degree 5): k_i = b_i f^i, f = 1 / b1.
    const Camera& rear_camera = set.cameras[1].file.camera;
    CHECK(rear_camera.intrinsics.fx == Approx(400.0).epsilon(1e-15));
    CHECK(rear_camera.lens.coefficients[7] == Approx(1e-17 * std::pow(400.0, 5)).epsilon(1e-14));
}

TEST_CASE("DriveWorks rig: written back, the same camera, and what a rig cannot hold refused", "[io][driveworks]") {
    const Camera front = parse_camera_set(rig(), CameraFormat::DriveworksRig, "rig.json").cameras[0].file.camera;
    const std::string text = format_camera(front, CameraFormat::DriveworksRig);
    CHECK_THAT(text, Catch::Contains("\"Model\": \"ftheta\"") && Catch::Contains("\"pixeldistance-to-angle\"") &&
                         Catch::Contains("\"protocol\": \"camera.virtual\"") &&
                         Catch::Contains("\"cx\": \"959.5\"") && Catch::Contains("\"linear-c\": \"1.0004\""));
    const Camera back = parse_camera(text, CameraFormat::DriveworksRig, "back.json").camera;
    CHECK(back.intrinsics.fx == Approx(front.intrinsics.fx).epsilon(1e-15));
    CHECK(back.intrinsics.cx == front.intrinsics.cx);
    for (std::size_t i = 0; i < front.lens.coefficients.size(); ++i) {
        CHECK(back.lens.coefficients[i] == Approx(front.lens.coefficients[i]).epsilon(1e-14));
    }
    CHECK((back.pose.R - front.pose.R).norm() < 1e-14);
    CHECK((back.pose.t - front.pose.t).norm() < 1e-13);
    // fx != fy goes into the affine: the same pixels.
    Camera stretched = front;
    stretched.intrinsics.fx *= 1.01;
    stretched.lens.coefficients[0] /= 1.01;
    stretched.lens.coefficients[1] /= 1.01;
    const Camera stretched_back = parse_camera(format_camera(stretched, CameraFormat::DriveworksRig), CameraFormat::DriveworksRig,
                                               "back.json")
                                      .camera;
    const Vec3 point(1, -0.5, 2);
    const Projection expected = PreparedCamera(stretched).project_camera_point(point);
    const Projection written = PreparedCamera(stretched_back).project_camera_point(point);
    REQUIRE(written.valid);
    CHECK((written.pixel - expected.pixel).norm() < 1e-9);
    Camera bounded = front;
    bounded.lens.coefficients[8] = 1.5;
    CHECK_THROWS_WITH(format_camera(bounded, CameraFormat::DriveworksRig), Catch::Contains("no max_angle"));
    Camera skewed = front;
    skewed.intrinsics.skew = 0.5;
    CHECK_THROWS_WITH(format_camera(skewed, CameraFormat::DriveworksRig), Catch::Contains("no skew"));
    Camera fisheye = front;
    fisheye.lens = {LensType::Fisheye, {0, 0, 0, 0}};
    CHECK_THROWS_WITH(format_camera(fisheye, CameraFormat::DriveworksRig), Catch::Contains("this camera's is FISHEYE"));
}

TEST_CASE("DriveWorks rig: a malformed rig names the file, the field and the value", "[io][driveworks]") {
    const auto error = [](const std::string& text) {
        return file_error_of([&] { parse_camera_set(text, CameraFormat::DriveworksRig, "rig.json"); });
    };
    CHECK_THAT(error(rig("", R"("polynomial": "0 0.0017 1.2e-08", "polynomial-type": "pixel-to-angle",)")),
               Catch::Contains("rig.json") && Catch::Contains("polynomial-type") && Catch::Contains("'pixel-to-angle'"));
    CHECK_THAT(error(rig("", R"("polynomial": "0.01 0.0017", "polynomial-type": "pixeldistance-to-angle",)")),
               Catch::Contains("properties.polynomial") && Catch::Contains("b0") && Catch::Contains("0.01"));
    CHECK_THAT(error(rig("", R"("polynomial": "0 0.0017 x", "polynomial-type": "pixeldistance-to-angle",)")),
               Catch::Contains("properties.polynomial\"[2]") && Catch::Contains("expected a number, got x"));
    CHECK_THAT(error(rig("", R"("polynomial": "0 1 2 3 4 5 6", "polynomial-type": "pixeldistance-to-angle",)")),
               Catch::Contains("properties.polynomial") && Catch::Contains("too many"));
    CHECK_THAT(error(rig("", R"("polynomial": "0 -0.0017", "polynomial-type": "pixeldistance-to-angle",)")),
               Catch::Contains("b1 must be positive"));
    CHECK_THAT(error(rig("", R"("polynomial": "0 0.0017",)")),
               Catch::Contains("properties.polynomial-type") && Catch::Contains("missing"));
    std::string folded = rig();
    folded.replace(folded.find("\"linear-c\": \"1.0004\""), 20, "\"linear-c\": \"-1\"");
    CHECK_THAT(error(folded), Catch::Contains("rig.json") && Catch::Contains("c - d e"));
    std::string ocam = rig();
    ocam.replace(ocam.find("\"Model\": \"ftheta\""), 17, "\"Model\": \"ocam\"");
    CHECK_THAT(error(ocam), Catch::Contains("properties.Model") && Catch::Contains("'ocam'"));
    std::string angles = rig();
    angles.replace(angles.find("[0.5, 2.0, -1.0]"), 16, "[0.5, 2.0]");
    CHECK_THAT(error(angles), Catch::Contains("nominalSensor2Rig_FLU.roll-pitch-yaw") && Catch::Contains("got 2"));
    std::string width = rig();
    width.replace(width.find("\"width\": \"1920\""), 15, "\"width\": \"19x0\"");
    CHECK_THAT(error(width), Catch::Contains("properties.width") && Catch::Contains("19x0"));
    CHECK_THAT(error(R"({"rig": {"sensors": [{"name": "imu", "protocol": "imu.xsens"}]}})"),
               Catch::Contains("rig.sensors") && Catch::Contains("no camera sensor"));
}
