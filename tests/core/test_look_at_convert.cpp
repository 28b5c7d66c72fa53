// The look-at camera <-> calibrated camera: K, R, t by hand, round trips, rays both ways,
// and the way back refusing what is not a look-at camera.

#include <catch2/catch.hpp>

#include "libcam/error.hpp"
#include "support.hpp"

using namespace libcam;
using test::relative_error;

namespace {

constexpr double kPi = std::numbers::pi;

double deg(double radians) { return radians * 180.0 / kPi; }

LookAtCamera camera_1920x1080(double fov, FovAxis axis) {
    return {{1, 2, 3}, {0, 0, -1}, {0, 1, 0}, fov, axis, {1920, 1080}};
}

}  // namespace

TEST_CASE("K for every fov axis, by hand") {
    // fov 60: tan 30 = 1/sqrt3. Horizontal: fx = fy = (W/2)/tan 30 = 960 sqrt3.
    const double root3 = std::sqrt(3.0);
    struct Case {
        FovAxis axis;
        double fx, fy;
    };
    const double diagonal_f = std::hypot(960.0, 540.0) * root3;
    for (const Case& c : {Case{FovAxis::Horizontal, 960 * root3, 960 * root3},
                          Case{FovAxis::Vertical, 540 * root3, 540 * root3},
                          Case{FovAxis::Diagonal, diagonal_f, diagonal_f},
                          Case{FovAxis::Both, 960 * root3, 540 * root3}}) {
        INFO("axis " << to_string(c.axis));
        const Camera camera = to_camera(camera_1920x1080(60.0, c.axis));
        REQUIRE(relative_error(camera.intrinsics.fx, c.fx) < 1e-15);
        REQUIRE(relative_error(camera.intrinsics.fy, c.fy) < 1e-15);
        // Centred principal point, OpenCV convention: (W-1)/2, (H-1)/2.
        REQUIRE(camera.intrinsics.cx == 959.5);
        REQUIRE(camera.intrinsics.cy == 539.5);
        REQUIRE(camera.intrinsics.skew == 0.0);
    }
}

TEST_CASE("R has rows u, -v, gaze and t = -R eye") {
    // Camera at (0, 5, 5) looking at the origin (the second worked example camera):
    // u = (1,0,0), v = (0,1,-1)/sqrt2, w = (0,-1,-1)/sqrt2.
    const Camera camera = to_camera(LookAtCamera::look_at({0, 5, 5}, {0, 0, 0}, {0, 1, 0}, 90, FovAxis::Both, {3, 3}));
    const double s = 1 / std::sqrt(2.0);
    Mat3 expected;
    expected << 1, 0, 0,  //
        0, -s, s,         //
        0, -s, -s;
    REQUIRE((camera.pose.R - expected).cwiseAbs().maxCoeff() < 1e-15);
    // t = -R eye = -(0, -5s + 5s, -5s - 5s) = (0, 0, 10 s) = (0, 0, 5 sqrt2).
    REQUIRE((camera.pose.t - Vec3(0, 0, 5 * std::sqrt(2.0))).norm() < 1e-14);
    REQUIRE((camera.pose.centre() - Vec3(0, 5, 5)).norm() < 1e-14);
    // rvec: a rotation by 135 degrees about -x (R maps world -> camera: the x axis
    // stays, y,z turn). |rvec| = 3 pi / 4.
    REQUIRE(std::abs(camera.pose.rvec().norm() - 3 * kPi / 4) < 1e-15);
    REQUIRE((camera.pose.rvec().normalized() - Vec3(-1, 0, 0)).norm() < 1e-15);
    // P = K [R | t] with K = [1.5 0 1; 0 1.5 1; 0 0 1]: its first row is
    // 1.5 R0 + 1 R2 = (1.5, -s, -s | 5 sqrt2 * 1).
    const Mat34 P = camera.P();
    REQUIRE((P.row(0) - Eigen::RowVector4d(1.5, -s, -s, 5 * std::sqrt(2.0))).norm() < 1e-14);
}

TEST_CASE("round trip look-at camera -> K, R, t -> look-at camera") {
    int cameras = 0;
    for (int i = 0; i < 400; ++i) {
        // Aspect ratios from 1:8 to 8:1, fov from 1 to 179 degrees, every axis.
        const double aspect = std::pow(8.0, test::uniform(-1.0, 1.0));
        const long width = std::max(1L, std::lround(1000 * std::sqrt(aspect)));
        const long height = std::max(1L, std::lround(1000 / std::sqrt(aspect)));
        const FovAxis axis = test::random_axis(i);
        LookAtCamera original = test::random_look_at_camera({width, height}, axis);
        if (i < 8) original.fov_deg = (i % 2 == 0) ? 1.0 : 179.0;  // the ends of the range, exactly
        // A diagonal fov must leave both axes under 180: always true; any fov < 180 is valid.
        const LookAtCamera back = to_look_at_camera(to_camera(original), axis);
        INFO("axis " << to_string(axis) << " fov " << original.fov_deg << " size " << width << "x" << height);
        REQUIRE(relative_error(back.fov_deg, original.fov_deg) < 1e-12);
        REQUIRE(back.fov_axis == axis);
        REQUIRE(back.size == original.size);
        REQUIRE((back.eye - original.eye).norm() <= 1e-12 * original.eye.norm());
        // The gaze comes back as a unit vector, the up as the camera's own up.
        const Basis a = original.basis();
        const Basis b = back.basis();
        REQUIRE((b.u - a.u).norm() < 1e-12);
        REQUIRE((b.v - a.v).norm() < 1e-12);
        REQUIRE((b.w - a.w).norm() < 1e-12);
        // And the other fov angles follow from the tangents: 2 atan(tan_x) etc.
        const Vec2 tangents = original.half_tangents();
        const FovDescription description = describe_fov(to_camera(original));
        REQUIRE(relative_error(description.fov_deg.horizontal, deg(2 * std::atan(tangents.x()))) < 1e-12);
        REQUIRE(relative_error(description.fov_deg.vertical, deg(2 * std::atan(tangents.y()))) < 1e-12);
        REQUIRE(relative_error(description.fov_deg.diagonal, deg(2 * std::atan(tangents.norm()))) < 1e-12);
        ++cameras;
    }
    REQUIRE(cameras == 400);
}

TEST_CASE("rays both ways agree on every pixel of a 1920x1080 image", "[sweep]") {
    // 20 random cameras, every fov axis, both pixel origins; plus non-square sizes.
    double worst = 0.0;
    long pixels = 0;
    for (int i = 0; i < 20; ++i) {
        const ImageSize size = i < 16 ? ImageSize{1920, 1080} : ImageSize{i % 2 ? 300L : 2400L, i % 2 ? 2400L : 300L};
        const LookAtCamera fov = test::random_look_at_camera(size, test::random_axis(i));
        const PixelOrigin origin = i % 2 == 0 ? PixelOrigin::BottomLeft : PixelOrigin::TopLeft;
        const PreparedCamera camera(to_camera(fov));
        const LookAtRayFormula look_at = fov.look_at_formula();
        for (long y = 0; y < size.height; ++y) {
            for (long x = 0; x < size.width; ++x) {
                const Vec2 pixel(static_cast<double>(x), static_cast<double>(y));
                const Ray ray = camera.ray(opencv_pixel(pixel, origin, size));
                worst = std::max(worst, angle_between(ray.direction, look_at.ray(pixel, origin)));
                ++pixels;
            }
        }
    }
    INFO("worst angle " << worst << " rad over " << pixels << " pixels");
    REQUIRE(pixels == 16L * 1920 * 1080 + 4L * 300 * 2400);
    REQUIRE(worst <= 1e-12);
}

TEST_CASE("fov angles and frustum of an off-centre camera, by hand") {
    Camera camera;
    camera.size = {100, 50};
    camera.intrinsics = {100.0, 100.0, 30.0, 20.0, 0.0};
    const FovDescription d = describe_fov(camera);
    // The image spans x in [-0.5, 99.5], y in [-0.5, 49.5]; at z = 1, y up:
    REQUIRE(std::abs(d.frustum.left - (-30.5 / 100)) < 1e-16);
    REQUIRE(std::abs(d.frustum.right - 69.5 / 100) < 1e-16);
    REQUIRE(std::abs(d.frustum.bottom - (-29.5 / 100)) < 1e-16);
    REQUIRE(std::abs(d.frustum.top - 20.5 / 100) < 1e-16);
    REQUIRE(relative_error(d.fov_deg.horizontal, deg(std::atan(0.695) + std::atan(0.305))) < 1e-14);
    REQUIRE(relative_error(d.fov_deg.vertical, deg(std::atan(0.295) + std::atan(0.205))) < 1e-14);
    REQUIRE_FALSE(d.is_look_at_camera());
    REQUIRE_THROWS_AS(to_look_at_camera(camera, FovAxis::Horizontal), NotRepresentable);
    REQUIRE_THROWS_WITH(to_look_at_camera(camera, FovAxis::Both), Catch::Matchers::Contains("principal point cx 30"));
}

TEST_CASE("fov angles of a centred camera, by hand") {
    Camera camera;
    camera.size = {1000, 500};
    camera.intrinsics = {500.0, 500.0, 499.5, 249.5, 0.0};
    const FovDescription d = describe_fov(camera);
    REQUIRE(relative_error(d.fov_deg.horizontal, 90.0) < 1e-15);                            // 2 atan(500/500)
    REQUIRE(relative_error(d.fov_deg.vertical, deg(2 * std::atan(0.5))) < 1e-15);           // 2 atan(250/500)
    REQUIRE(relative_error(d.fov_deg.diagonal, deg(2 * std::atan(std::sqrt(1.25)))) < 1e-15);  // hypot(1, .5)
    // Square pixels: a look-at camera on horizontal, vertical, diagonal; W/fx != H/fy, so not "both".
    REQUIRE(d.fits_axis(FovAxis::Horizontal));
    REQUIRE(d.fits_axis(FovAxis::Vertical));
    REQUIRE(d.fits_axis(FovAxis::Diagonal));
    REQUIRE_FALSE(d.fits_axis(FovAxis::Both));
    REQUIRE_THROWS_WITH(to_look_at_camera(camera, FovAxis::Both), Catch::Matchers::Contains("W/fx"));
    REQUIRE(to_look_at_camera(camera, FovAxis::Horizontal).fov_deg == Approx(90.0).epsilon(1e-15));
}

TEST_CASE("skew and non-square pixels are reported, not dropped") {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {500.0, 500.0, 319.5, 239.5, 2.0};
    FovDescription d = describe_fov(camera);
    REQUIRE_FALSE(d.is_look_at_camera());
    REQUIRE(d.deviations.size() == 2);  // the skew, and W/fx = 1.28 != H/fy = 0.96
    REQUIRE_THAT(d.deviations[0], Catch::Matchers::Contains("skew 2"));

    camera.intrinsics = {500.0, 510.0, 319.5, 239.5, 0.0};
    d = describe_fov(camera);
    REQUIRE_FALSE(d.fits_axis(FovAxis::Horizontal));
    REQUIRE_FALSE(d.fits_axis(FovAxis::Both));
    REQUIRE_THROWS_WITH(to_look_at_camera(camera, FovAxis::Vertical), Catch::Matchers::Contains("not square"));
}

TEST_CASE("bad look-at cameras are refused with the field named") {
    using Catch::Matchers::Contains;
    auto fov = [](double deg) { return LookAtCamera{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, deg, FovAxis::Both, {3, 3}}; };
    for (double bad : {0.0, -5.0, 180.0, 200.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
        REQUIRE_THROWS_WITH(to_camera(fov(bad)), Contains("fov"));
    }
    LookAtCamera camera = fov(90);
    camera.size = {0, 3};
    REQUIRE_THROWS_WITH(to_camera(camera), Contains("size") && Contains("width"));
    camera = fov(90);
    camera.up = {0, 0, 5};  // parallel to the gaze
    REQUIRE_THROWS_WITH(to_camera(camera), Contains("up") && Contains("parallel"));
    camera.up = {0, 0, -1};  // antiparallel... also parallel to the line
    REQUIRE_THROWS_WITH(to_camera(camera), Contains("up"));
    camera.up = {0, 1, 0};
    camera.eye = {0, std::nan(""), 0};
    REQUIRE_THROWS_WITH(to_camera(camera), Contains("eye"));
    REQUIRE_THROWS_WITH(LookAtCamera::look_at({1, 2, 3}, {1, 2, 3}, {0, 1, 0}, 90, FovAxis::Both, {3, 3}),
                        Contains("target") && Contains("eye"));
    camera = fov(90);
    camera.gaze = {0, 0, 0};
    REQUIRE_THROWS_WITH(to_camera(camera), Contains("gaze"));
}

TEST_CASE("up close to the gaze: a clear error below the threshold, a correct basis above") {
    // Gaze -z; up tilted from -z by angle a toward +y: up = (0, sin a, -cos a).
    // The basis then is u = gaze x up = (sin a, 0, 0)/sin a = (1, 0, 0) exactly, v = (0, 1, 0).
    for (double angle : {1e-3, 1e-6, 1e-8}) {
        const LookAtCamera camera{{0, 0, 0}, {0, 0, -1}, {0, std::sin(angle), -std::cos(angle)}, 90, FovAxis::Both, {3, 3}};
        const Basis b = camera.basis();
        INFO("angle " << angle);
        REQUIRE((b.u - Vec3(1, 0, 0)).norm() < 1e-15);
        REQUIRE((b.v - Vec3(0, 1, 0)).norm() < 1e-15);
        REQUIRE_NOTHROW(to_camera(camera));
    }
    const LookAtCamera too_close{{0, 0, 0}, {0, 0, -1}, {0, 1e-12, -1}, 90, FovAxis::Both, {3, 3}};
    REQUIRE_THROWS_AS(to_camera(too_close), InvalidArgument);
}

TEST_CASE("tan of half an angle near 180 degrees keeps its digits") {
    for (double angle : {179.0, 179.9, 179.999, 179.99999, 1.0, 1e-3, 90.0}) {
        // The reference takes the tangent of the smaller of the half angle and its complement,
        // where long double's tan is well conditioned.
        constexpr long double kDegree = 3.14159265358979323846264338327950288L / 180.0L;
        const long double a = static_cast<long double>(angle);
        const long double reference = angle > 90.0 ? 1.0L / std::tan((180.0L - a) / 2.0L * kDegree)
                                                   : std::tan(a / 2.0L * kDegree);
        INFO("angle " << angle << " error " << relative_error(tan_half_angle_deg(angle), static_cast<double>(reference)));
        // A few ulps (1 ulp is 1.1e-16 to 2.2e-16 relative): degrees->radians and tan each round once.
        REQUIRE(relative_error(tan_half_angle_deg(angle), static_cast<double>(reference)) < 1e-15);
        REQUIRE(relative_error(angle_deg_from_half_tangent(tan_half_angle_deg(angle)), angle) < 1e-15);
    }
}

TEST_CASE("Rodrigues both ways refuses what is not a rotation, naming the field") {
    const auto message = [](auto&& call) { return libcam::test::error_of(call); };
    using Catch::Matchers::Contains;
    CHECK_THAT(message([] { (void)rotation_from_rvec(Vec3(0, std::nan(""), 1)); }),
               Contains("InvalidArgument") && Contains("rvec"));
    CHECK_THAT(message([] { (void)rotation_from_rvec(Vec3(0, INFINITY, 1)); }), Contains("rvec"));
    CHECK_THAT(message([] { (void)rvec_from_rotation(2.0 * Mat3::Identity()); }),
               Contains("R: not a rotation matrix"));
    Mat3 reflection = Mat3::Identity();
    reflection(2, 2) = -1;  // orthogonal, det -1
    CHECK_THAT(message([&] { (void)rvec_from_rotation(reflection); }), Contains("det = -1"));
    // A rotation by 0.25 rad about z, by hand, still converts.
    Mat3 rz;
    rz << std::cos(0.25), -std::sin(0.25), 0, std::sin(0.25), std::cos(0.25), 0, 0, 0, 1;
    CHECK((rvec_from_rotation(rz) - Vec3(0, 0, 0.25)).norm() < 1e-15);
}
