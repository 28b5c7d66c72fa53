// The OpenGL projection: its entries by hand (gluPerspective, glFrustum), the same pixel
// through the GL pipeline and through K [R | t], depth, and K back from the matrix.

#include <catch2/catch.hpp>

#include "libcam/convert/opengl.hpp"
#include "libcam/error.hpp"
#include "support.hpp"

using namespace libcam;
using test::relative_error;

namespace {

// A calibrated camera with random K (optionally off-centre and skewed) and pose.
Camera random_camera(bool centred, bool skewed) {
    const ImageSize size{std::lround(test::uniform(100, 4000)), std::lround(test::uniform(100, 4000))};
    Camera camera = to_camera(test::random_look_at_camera(size, test::random_axis(static_cast<int>(size.width)), 5, 170));
    if (!centred) {
        camera.intrinsics.cx += test::uniform(-0.2, 0.2) * static_cast<double>(size.width);
        camera.intrinsics.cy += test::uniform(-0.2, 0.2) * static_cast<double>(size.height);
    }
    if (skewed) camera.intrinsics.skew = test::uniform(-0.05, 0.05) * camera.intrinsics.fx;
    return camera;
}

}  // namespace

TEST_CASE("a centred camera gives gluPerspective's matrix") {
    // gluPerspective(fovy = 60, aspect = W/H, near, far): f = 1/tan(30 deg) = sqrt3,
    // [f/aspect 0 0 0; 0 f 0 0; 0 0 (far+near)/(near-far) 2 far near/(near-far); 0 0 -1 0].
    const LookAtCamera fov{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60.0, FovAxis::Vertical, {1600, 900}};
    const GlCamera gl = to_opengl(to_camera(fov), 0.5, 200.0);
    const double f = std::sqrt(3.0);
    const double aspect = 1600.0 / 900.0;
    Mat4 expected;
    expected << f / aspect, 0, 0, 0,  //
        0, f, 0, 0,                   //
        0, 0, (200.0 + 0.5) / (0.5 - 200.0), 2 * 200.0 * 0.5 / (0.5 - 200.0), 0, 0, -1, 0;
    INFO("projection\n" << gl.projection << "\nexpected\n" << expected);
    REQUIRE((gl.projection - expected).cwiseAbs().maxCoeff() < 1e-15);
    // Looking down -z with y up from the origin: the view matrix is the identity.
    REQUIRE((gl.view - Mat4::Identity()).cwiseAbs().maxCoeff() < 1e-15);
    REQUIRE(gl.viewport == std::array<long, 4>{0, 0, 1600, 900});
}

TEST_CASE("an off-centre camera gives glFrustum's matrix for its frustum") {
    // glFrustum(l, r, b, t, n, f): [2n/(r-l) 0 (r+l)/(r-l) 0; 0 2n/(t-b) (t+b)/(t-b) 0; ...].
    // The image spans pixels [-0.5, W-0.5] x [-0.5, H-0.5]; at the near plane n, with y up:
    // l = -n (cx + 0.5)/fx, r = n (W - 0.5 - cx)/fx, b = -n (H - 0.5 - cy)/fy, t = n (cy + 0.5)/fy.
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {500.0, 520.0, 300.0, 250.0, 0.0};
    const double n = 2.0, far = 50.0;
    const double l = -n * 300.5 / 500, r = n * (639.5 - 300) / 500, b = -n * (479.5 - 250) / 520, t = n * 250.5 / 520;
    const GlCamera gl = to_opengl(camera, n, far);
    REQUIRE(relative_error(gl.projection(0, 0), 2 * n / (r - l)) < 1e-15);
    REQUIRE(relative_error(gl.projection(0, 2), (r + l) / (r - l)) < 1e-13);
    REQUIRE(relative_error(gl.projection(1, 1), 2 * n / (t - b)) < 1e-15);
    REQUIRE(relative_error(gl.projection(1, 2), (t + b) / (t - b)) < 1e-13);
}

TEST_CASE("the GL pipeline and K [R | t] land on the same pixel") {
    double worst_px = 0.0;
    int points = 0;
    for (int i = 0; i < 60; ++i) {
        const Camera camera = random_camera(i % 3 == 0, i % 5 == 0);
        const DepthRange range = i % 2 ? DepthRange::ZeroToOne : DepthRange::MinusOneToOne;
        const GlCamera gl = to_opengl(camera, 0.01, 1e5, range);
        const PreparedCamera prepared(camera);
        for (int j = 0; j < 200; ++j) {
            // A pixel anywhere on the image (edges included), at a depth in front.
            const Vec2 pixel(test::uniform(-0.5, static_cast<double>(camera.size.width) - 0.5),
                             test::uniform(-0.5, static_cast<double>(camera.size.height) - 0.5));
            const Ray ray = prepared.ray(pixel);
            const Vec3 point = ray.origin + test::uniform(0.1, 1000.0) * ray.direction;
            const Projection cv = prepared.project(point);
            const GlWindowPoint window = gl_project(gl, point);
            REQUIRE(cv.valid);
            REQUIRE(window.valid);
            const Vec2 from_gl = opencv_from_gl_window(window.window, camera.size);
            worst_px = std::max({worst_px, (from_gl - cv.pixel).norm(), (from_gl - pixel).norm()});
            ++points;
        }
    }
    INFO("worst " << worst_px << " px over " << points << " points");
    REQUIRE(worst_px < 1e-9);
}

TEST_CASE("near and far map to the ends of the depth range") {
    const LookAtCamera fov{{1, 2, 3}, {1, -1, 2}, {0, 1, 0}, 70.0, FovAxis::Horizontal, {800, 600}};
    const Camera camera = to_camera(fov);
    const Vec3 gaze = fov.gaze.normalized();
    for (const auto& [range, low] : {std::pair{DepthRange::MinusOneToOne, -1.0}, {DepthRange::ZeroToOne, 0.0}}) {
        const GlCamera gl = to_opengl(camera, 0.25, 80.0, range);
        REQUIRE(std::abs(gl_project(gl, fov.eye + 0.25 * gaze).ndc_depth - low) < 1e-12);
        REQUIRE(std::abs(gl_project(gl, fov.eye + 80.0 * gaze).ndc_depth - 1.0) < 1e-12);
        REQUIRE_FALSE(gl_project(gl, fov.eye - gaze).valid);  // behind the camera
    }
}

TEST_CASE("K, near and far come back from the projection matrix") {
    for (int i = 0; i < 100; ++i) {
        const Camera camera = random_camera(i % 2 == 0, i % 3 == 0);
        const DepthRange range = i % 2 ? DepthRange::ZeroToOne : DepthRange::MinusOneToOne;
        const double near = test::uniform(0.001, 1.0), far = test::uniform(10.0, 1e4);
        const GlIntrinsics back = intrinsics_from_opengl(to_opengl(camera, near, far, range).projection, camera.size, range);
        const Intrinsics& k = camera.intrinsics;
        REQUIRE(relative_error(back.intrinsics.fx, k.fx) < 1e-14);
        REQUIRE(relative_error(back.intrinsics.fy, k.fy) < 1e-14);
        REQUIRE(std::abs(back.intrinsics.cx - k.cx) < 1e-10 * static_cast<double>(camera.size.width));
        REQUIRE(std::abs(back.intrinsics.cy - k.cy) < 1e-10 * static_cast<double>(camera.size.height));
        REQUIRE(std::abs(back.intrinsics.skew - k.skew) < 1e-12 * k.fx);
        REQUIRE(relative_error(back.near, near) < 1e-9);
        REQUIRE(relative_error(back.far, far) < 1e-9);
    }
}

TEST_CASE("a matrix that is not a perspective projection is refused, naming the entry") {
    const GlCamera gl = to_opengl(to_camera(LookAtCamera{}), 0.1, 10.0);
    Mat4 bad = gl.projection;
    bad(3, 2) = 1.0;
    REQUIRE_THROWS_WITH(intrinsics_from_opengl(bad, {1, 1}), Catch::Matchers::Contains("projection[3][2]"));
    bad = gl.projection;
    bad(1, 0) = 0.5;
    REQUIRE_THROWS_WITH(intrinsics_from_opengl(bad, {1, 1}), Catch::Matchers::Contains("projection[1][0]"));
    REQUIRE_THROWS_WITH(to_opengl(to_camera(LookAtCamera{}), 1.0, 0.5), Catch::Matchers::Contains("far"));
    REQUIRE_THROWS_WITH(to_opengl(to_camera(LookAtCamera{}), 0.0, 0.5), Catch::Matchers::Contains("near"));
}

TEST_CASE("gl_project flags a point it cannot place: behind the eye, or a matrix with NaN") {
    GlCamera gl = to_opengl(to_camera(LookAtCamera{}), 0.1, 10.0);
    const Vec3 in_view = LookAtCamera{}.eye + LookAtCamera{}.gaze;  // one unit along the gaze
    CHECK(gl_project(gl, in_view).valid);
    CHECK_FALSE(gl_project(gl, LookAtCamera{}.eye - LookAtCamera{}.gaze).valid);
    gl.projection(0, 0) = std::nan("");  // clip x NaN while w stays positive: was "valid" with a NaN window
    const GlWindowPoint nan_point = gl_project(gl, in_view);
    CHECK_FALSE(nan_point.valid);
}
