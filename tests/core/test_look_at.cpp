// The look-at formula on two worked example cameras and on random ones, reproduced
// through the library. Expected values are derived from the formula by hand, in the
// comments; where the worked example this comes from printed a wrong value, the
// comment says so and the test uses the correct one.
//
// The look-at formula: alpha = tan(theta/2) (2x - W + 1)/W, beta = tan(theta/2) (2y - H + 1)/H,
// d = alpha u + beta v + w (w along the gaze, left-handed), rows counted upward from the
// bottom-left pixel. All the cameras here are 3x3 with theta = 90 degrees, so
// tan(theta/2) = 1 and alpha, beta are -2/3, 0, 2/3 for x, y = 0, 1, 2.
//
// Example camera 1: eye at the origin looking down -z, up +y.
// Example camera 2: eye (0, 5, 5) looking at the origin, up +y.

#include <catch2/catch.hpp>
#include <type_traits>

#include "libcam/convert/look_at_convert.hpp"
#include "support.hpp"

using namespace libcam;

namespace {

const double kRoot2 = std::sqrt(2.0);

void require_near(const Vec3& actual, const Vec3& expected, double tolerance = 1e-15) {
    INFO("actual " << actual.transpose() << ", expected " << expected.transpose());
    REQUIRE((actual - expected).norm() <= tolerance * std::max(1.0, expected.norm()));
}

LookAtCamera example_camera_1() { return {{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90.0, FovAxis::Both, {3, 3}}; }
LookAtCamera example_camera_2() { return LookAtCamera::look_at({0, 5, 5}, {0, 0, 0}, {0, 1, 0}, 90.0, FovAxis::Both, {3, 3}); }

// The world ray through a pixel (counted from the bottom-left) by the calibrated path,
// scaled so it can be compared with the look-at formula's unnormalised d.
Vec3 calibrated_ray_like(const Camera& camera, const Vec2& pixel, const Vec3& look_at_d) {
    const Ray ray = PreparedCamera(camera).ray(opencv_pixel(pixel, PixelOrigin::BottomLeft, camera.size));
    REQUIRE(ray.valid);
    return ray.direction * look_at_d.norm();
}

}  // namespace

TEST_CASE("look-at example 1: basis of the camera at the origin looking down -z") {
    // The left-handed basis has w along the gaze: w = (0, 0, -1) for a gaze along -z.
    // (The worked example describes it as "w facing away from the gaze" by mistake; its
    // own answer, w = (0, 0, -1), points along the gaze.)
    const Basis left = example_camera_1().basis(Handedness::Left);
    require_near(left.u, {1, 0, 0});
    require_near(left.v, {0, 1, 0});
    require_near(left.w, {0, 0, -1});
    const Basis right = example_camera_1().basis(Handedness::Right);
    require_near(right.u, {1, 0, 0});
    require_near(right.v, {0, 1, 0});
    require_near(right.w, {0, 0, 1});
    // Left-handed: u x v = -w; right-handed: u x v = w.
    require_near(left.u.cross(left.v), -left.w);
    require_near(right.u.cross(right.v), right.w);
}

TEST_CASE("look-at example 1: rays of pixels (1, 1) and (0, 0)") {
    const LookAtCamera camera = example_camera_1();
    // (1,1): alpha = beta = (2 - 3 + 1)/3 = 0, so d = w = (0, 0, -1).
    require_near(camera.look_at_ray({1, 1}), {0, 0, -1});
    // (0,0): alpha = beta = (0 - 3 + 1)/3 = -2/3, d = (-2/3, -2/3, -1).
    // (The worked example labels this second f(t) "at (1, 1)" by mistake; it is the ray
    // at (0, 0).)
    require_near(camera.look_at_ray({0, 0}), {-2.0 / 3, -2.0 / 3, -1});
    // f(t) = o + t d, at t = 3: (-2, -2, -3).
    require_near(camera.eye + 3.0 * camera.look_at_ray({0, 0}), {-2, -2, -3});
}

TEST_CASE("look-at example 1: the lower-left corner of the field of view") {
    const LookAtCamera camera = example_camera_1();
    // alpha = beta = -1: d = -u - v + w = (-1, -1, -1).
    require_near(camera.field_ray(-1, -1), {-1, -1, -1});
    // The corner is the outer edge of pixel (0, 0): x = y = -0.5 gives (2(-0.5) - 3 + 1)/3 = -1.
    require_near(camera.look_at_ray({-0.5, -0.5}), {-1, -1, -1});
}

TEST_CASE("look-at example 2: basis of the camera at (0, 5, 5) looking at the origin") {
    const Basis basis = example_camera_2().basis();
    // w = (target - eye)/|...| = (0, -5, -5)/(5 sqrt2) = (0, -1, -1)/sqrt2.
    require_near(basis.w, Vec3(0, -1, -1) / kRoot2);
    // u = w x up = (0,-1,-1)/sqrt2 x (0,1,0) = ((-1)(0) - (-1)(1), (-1)(0) - (0)(0), (0)(1) - (-1)(0))/sqrt2
    //   = (1, 0, 0)/sqrt2, normalised (1, 0, 0).
    require_near(basis.u, {1, 0, 0});
    // v = u x w = (1,0,0) x (0,-1,-1)/sqrt2 = (0*(-1) - 0*(-1), 0*0 - 1*(-1), 1*(-1) - 0*0)/sqrt2 = (0, 1, -1)/sqrt2.
    require_near(basis.v, Vec3(0, 1, -1) / kRoot2);
}

TEST_CASE("look-at example 2: rays of pixels (1, 1) and (0, 0) for the camera at (0, 5, 5)") {
    const LookAtCamera camera = example_camera_2();
    // (1,1): d = w = (0, -1, -1)/sqrt2; f(t) = (0, 5 - t/sqrt2, 5 - t/sqrt2).
    require_near(camera.look_at_ray({1, 1}), Vec3(0, -1, -1) / kRoot2);
    // (0,0): d = -2/3 u - 2/3 v + w
    //   x: -2/3
    //   y: -2/3 (1/sqrt2) + (-1/sqrt2) = -sqrt2/3 - 1/sqrt2
    //   z: -2/3 (-1/sqrt2) + (-1/sqrt2) = sqrt2/3 - 1/sqrt2
    const Vec3 d00(-2.0 / 3, -kRoot2 / 3 - 1 / kRoot2, kRoot2 / 3 - 1 / kRoot2);
    require_near(camera.look_at_ray({0, 0}), d00);
    // f(t) at (0,0) = eye + t d = (-2t/3, 5 - sqrt2 t/3 - t/sqrt2, 5 + sqrt2 t/3 - t/sqrt2).
    // (The worked example prints x = 0 by mistake: it is -2t/3; and y = 5 - 2t/3 - t/sqrt2,
    // also by mistake: the middle term is sqrt2 t/3, as its own d shows; z matches.)
    const double t = 2.0;
    require_near(camera.eye + t * camera.look_at_ray({0, 0}),
                 {-2 * t / 3, 5 - kRoot2 * t / 3 - t / kRoot2, 5 + kRoot2 * t / 3 - t / kRoot2});
}

TEST_CASE("look-at example 2: the top centre of the field of view") {
    const LookAtCamera camera = example_camera_2();
    // alpha = 0, beta = 1: d = v + w = (0, 1, -1)/sqrt2 + (0, -1, -1)/sqrt2 = (0, 0, -sqrt2).
    require_near(camera.field_ray(0, 1), {0, 0, -kRoot2});
    // On pixels: x = 1 (centre column), y = 2.5 (top edge of the top row): (2(2.5) - 3 + 1)/3 = 1.
    require_near(camera.look_at_ray({1, 2.5}), {0, 0, -kRoot2});
    // f(t) = (0, 5, 5 - t sqrt2) at t = 1.
    require_near(camera.eye + camera.field_ray(0, 1), {0, 5, 5 - kRoot2});
}

TEST_CASE("look-at formula: any eye and orthonormal basis") {
    for (int i = 0; i < 50; ++i) {
        const LookAtCamera camera = test::random_look_at_camera({3, 3}, FovAxis::Both, 90.0, 90.0);
        const Basis b = camera.basis();
        // An orthonormal, left-handed basis with w along the gaze.
        REQUIRE(std::abs(b.u.dot(b.v)) < 1e-15);
        REQUIRE(std::abs(b.u.dot(b.w)) < 1e-15);
        REQUIRE(std::abs(b.v.dot(b.w)) < 1e-15);
        require_near(b.w, camera.gaze.normalized());
        require_near(b.u.cross(b.v), -b.w, 1e-14);
        // (1,1): d = w. (0,0): d = -2/3 u - 2/3 v + w.
        require_near(camera.look_at_ray({1, 1}), b.w);
        require_near(camera.look_at_ray({0, 0}), -2.0 / 3 * b.u - 2.0 / 3 * b.v + b.w);
    }
}

TEST_CASE("the right-handed basis describes the same rays") {
    // With the right-handed basis, the look-at formula holds with w replaced by -w.
    for (int i = 0; i < 20; ++i) {
        const LookAtCamera camera = test::random_look_at_camera({3, 3}, FovAxis::Both, 90.0, 90.0);
        const Basis left = camera.basis(Handedness::Left);
        const Basis right = camera.basis(Handedness::Right);
        require_near(right.u, left.u);
        require_near(right.v, left.v);
        require_near(right.w, -left.w);
        // u = up x w (right-handed) equals w x up (left-handed), normalised.
        require_near(camera.up.cross(right.w).normalized(), left.u, 1e-14);
        require_near(camera.look_at_ray({0, 2}), -2.0 / 3 * right.u + 2.0 / 3 * right.v - right.w);
    }
}

TEST_CASE("the calibrated path reproduces every look-at ray") {
    for (const LookAtCamera& fov : {example_camera_1(), example_camera_2()}) {
        const Camera camera = to_camera(fov);
        for (const Vec2& pixel : {Vec2(0, 0), Vec2(1, 1), Vec2(2, 0), Vec2(0, 2), Vec2(-0.5, -0.5), Vec2(1, 2.5)}) {
            const Vec3 d = fov.look_at_ray(pixel);
            require_near(calibrated_ray_like(camera, pixel, d), d, 1e-15);
        }
    }
}

TEST_CASE("row origin: bottom-left pixel (0, 0) is the lower-left pixel, OpenCV pixel (0, H-1)") {
    const Camera camera = to_camera(example_camera_1());
    // Its ray is (-2/3, -2/3, -1) (docs/conventions.md, "Row origin: top-left or bottom-left").
    const Vec3 expected = Vec3(-2.0 / 3, -2.0 / 3, -1).normalized();
    require_near(PreparedCamera(camera).ray({0, 2}).direction, expected);
    require_near(example_camera_1().look_at_ray({0, 2}, PixelOrigin::TopLeft).normalized(), expected);
}

TEST_CASE("The look-at formula refuses a look-at camera built by hand that validate() refuses, naming the field") {
    using Catch::Matchers::Contains;
    LookAtCamera zero_gaze;
    zero_gaze.gaze = Vec3::Zero();
    LookAtCamera nan_fov;
    nan_fov.fov_deg = std::nan("");
    LookAtCamera up_along_gaze;
    up_along_gaze.up = up_along_gaze.gaze;
    for (const auto& entry : {std::pair{zero_gaze, "gaze"}, std::pair{nan_fov, "fov"}, std::pair{up_along_gaze, "up"}}) {
        // Not a structured binding: clang 14 (the sanitizer build) cannot capture one in a lambda.
        const LookAtCamera& camera = entry.first;
        const char* field = entry.second;
        CAPTURE(field);
        CHECK_THAT(libcam::test::error_of([&] { (void)camera.look_at_ray({1, 1}); }), Contains(field));
        CHECK_THAT(libcam::test::error_of([&] { (void)camera.basis(); }), Contains(field));
        CHECK_THAT(libcam::test::error_of([&] { (void)camera.half_tangents(); }), Contains(field));
        CHECK_THAT(libcam::test::error_of([&] { (void)camera.field_ray(0.5, 0.5); }), Contains(field));
    }
}

// The graphics camera's old names, kept for one release in the one old header left.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
#include "libcam/convert/fov_convert.hpp"
TEST_CASE("FovCamera and to_fov_camera, the old names, are LookAtCamera and to_look_at_camera") {
    static_assert(std::is_same_v<libcam::FovCamera, libcam::LookAtCamera>);
    const libcam::LookAtCamera camera = libcam::LookAtCamera::look_at({0, 5, 5}, {0, 0, 0}, {0, 1, 0}, 90.0,
                                                                      libcam::FovAxis::Both, {3, 3});
    const libcam::LookAtCamera back = libcam::to_fov_camera(libcam::to_camera(camera), libcam::FovAxis::Both);
    // 90 degrees on both axes of a square image: the same angle back, to the last bits.
    CHECK(back.fov_deg == Approx(90.0).epsilon(1e-12));
}
#pragma GCC diagnostic pop
