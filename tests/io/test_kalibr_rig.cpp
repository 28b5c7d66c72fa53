// A rig written as one Kalibr camchain (format_kalibr_rig): each camera after the first is
// placed from the one before it, as Kalibr's T_cn_cnm1 says (X_cn = T_cn_cnm1 X_cnm1), and the
// text reads back as the same cameras. Expected transforms are worked by hand from the
// cameras' world-to-camera poses.

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/kalibr_rig.hpp"

using namespace libcam;

namespace {

Camera rig_camera(LensType type, std::vector<double> coefficients, const Pose& pose) {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {410.5, 409.25, 322.75, 238.5, 0.0};
    camera.lens = {type, std::move(coefficients)};
    camera.pose = pose;
    return camera;
}

}  // namespace

TEST_CASE("A rig as one Kalibr camchain: each camera from the one before it, read back the same", "[io][kalibr]") {
    // The first camera's pose is not the identity: the camchain holds the cameras relative to it.
    const Pose first = Pose::from_rvec(Vec3(0.1, -0.2, 0.05), Vec3(0.3, 0.0, -1.0));
    const Pose second = Pose::from_rvec(Vec3(0.12, -0.21, 0.04), Vec3(0.2, 0.01, -1.02));
    const Pose third = Pose::from_rvec(Vec3(0.0, 0.3, 0.0), Vec3(-0.5, 0.0, 0.0));
    const std::vector<Camera> rig = {rig_camera(LensType::OpenCv4, {-0.28, 0.07, 1e-4, -2e-4}, first),
                                     rig_camera(LensType::Fisheye, {0.01, -0.002, 3e-4, -1e-5}, second),
                                     rig_camera(LensType::Pinhole, {}, third)};
    const std::string text = format_kalibr_rig(rig);
    INFO(text);
    CHECK(text.find("cam0:\n  camera_model: pinhole\n") == 0);  // the first: no transform
    CHECK(text.find("distortion_model: radtan") != std::string::npos);
    CHECK(text.find("distortion_model: equidistant") != std::string::npos);

    const CameraSet set = parse_camera_set(text, CameraFormat::Kalibr, "camchain.yaml");
    REQUIRE(set.cameras.size() == 3);
    for (std::size_t i = 0; i < 3; ++i) {
        const Camera& read = set.cameras[i].file.camera;
        CHECK(read.size == rig[i].size);
        CHECK(read.intrinsics.K() == rig[i].intrinsics.K());
        CHECK(read.lens.type == rig[i].lens.type);
        CHECK(read.lens.coefficients == rig[i].lens.coefficients);
        // Read back in the first camera's frame: X_i = R_i R_0^T (X_0 - t_0) + t_i, so
        // R = R_i R_0^T and t = t_i - R_i R_0^T t_0.
        const Mat3 R = rig[i].pose.R * rig[0].pose.R.transpose();
        const Vec3 t = rig[i].pose.t - R * rig[0].pose.t;
        CHECK((read.pose.R - R).cwiseAbs().maxCoeff() < 1e-14);
        CHECK((read.pose.t - t).cwiseAbs().maxCoeff() < 1e-14);
    }
}

TEST_CASE("A rig with a camera Kalibr has no model for is refused, naming the model", "[io][kalibr]") {
    const std::vector<Camera> rig = {rig_camera(LensType::OpenCv4, {-0.28, 0.07, 1e-4, -2e-4}, Pose{}),
                                     rig_camera(LensType::OpenCv5, {-0.28, 0.07, 1e-4, -2e-4, 0.01},
                                                Pose::from_rvec(Vec3(0.0, 0.01, 0.0), Vec3(-0.1, 0.0, 0.0)))};
    try {
        (void)format_kalibr_rig(rig);
        FAIL("an OPENCV5 camera was written to a camchain");
    } catch (const NotRepresentable& error) {
        CHECK_THAT(error.what(), Catch::Contains("Kalibr has no model for a OPENCV5 lens"));
    }
}
