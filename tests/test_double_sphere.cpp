// DOUBLE_SPHERE against the sources that define it: the paper's equations (transcribed
// apart from libcam's header, in long double), OpenCV's cv::omnidir (the unified model,
// which is the Double Sphere with alpha = 0), mrcal's STEREOGRAPHIC (the Double Sphere
// with xi = 0 and alpha = 1/2), and the domain's edge worked by hand.

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/ccalib/omnidir.hpp>
#include <vector>

#include "double_sphere_reference.hpp"
#include "lens_cases.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/mrcal.hpp"
#include "support.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

// Directions over the whole sphere (cos theta evenly spaced, azimuth by the golden
// angle), each at a distance in [0.1, 100].
std::vector<Vec3> sphere_points(int count) {
    std::vector<Vec3> points;
    const double golden_angle = std::numbers::pi * (3 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        const double cos_theta = 1 - 2 * (i + 0.5) / count, sin_theta = std::sqrt(1 - cos_theta * cos_theta);
        const double distance = 0.1 * std::pow(1000.0, (i * 0.618034) - std::floor(i * 0.618034));
        points.push_back(distance * Vec3(sin_theta * std::cos(golden_angle * i), sin_theta * std::sin(golden_angle * i), cos_theta));
    }
    return points;
}

Camera double_sphere(double xi, double alpha) {
    return real_camera(LensType::DoubleSphere, {xi, alpha}, {1024, 768}, {300.0, 305.0, 515.0, 380.0});
}

// The pixels cv::omnidir::projectPoints gives for camera-frame points (no distortion).
std::vector<Vec2> omnidir_pixels(const Camera& camera, const std::vector<Vec3>& points) {
    std::vector<cv::Vec3d> object;
    for (const Vec3& p : points) object.emplace_back(p.x(), p.y(), p.z());
    std::vector<cv::Vec2d> image;
    const cv::Matx33d K(camera.intrinsics.fx, 0, camera.intrinsics.cx, 0, camera.intrinsics.fy, camera.intrinsics.cy, 0, 0, 1);
    cv::omnidir::projectPoints(object, image, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, camera.lens.coefficients[0],
                               cv::Vec4d(0, 0, 0, 0));
    std::vector<Vec2> pixels;
    for (const cv::Vec2d& q : image) pixels.emplace_back(q[0], q[1]);
    return pixels;
}

}  // namespace

// How many times the paper's denominator alpha d2 + (1 - alpha) zeta cancels at a point:
// the sum of the two terms' sizes over the size of the sum. Behind the first sphere's
// equator with alpha < 1/2 it grows without bound towards the cone, where m goes to
// infinity: no evaluation in double gives m there to better than eps times it.
double denominator_cancellation(const Camera& camera, const Vec3& point) {
    const long double xi = camera.lens.coefficients[0], alpha = camera.lens.coefficients[1];
    const long double x = point.x(), y = point.y(), z = point.z();
    const long double zeta = xi * std::sqrt(x * x + y * y + z * z) + z;
    const long double d2 = std::sqrt(x * x + y * y + zeta * zeta);
    return static_cast<double>((alpha * d2 + (1 - alpha) * std::abs(zeta)) / std::abs(alpha * d2 + (1 - alpha) * zeta));
}

TEST_CASE("DOUBLE_SPHERE projects as the paper's equations, and flags what they exclude") {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    for (const LensCase& c : lens_cases()) {
        if (c.camera.lens.type != LensType::DoubleSphere) continue;
        INFO(c.name);
        const PreparedCamera camera(c.camera);
        const Vec2 principal(c.camera.intrinsics.cx, c.camera.intrinsics.cy);
        // The error over what is allowed: 1e-9 px, and 16 eps of the pixel's distance from
        // the principal point times the denominator's cancellation.
        double worst = 0, worst_px = 0, largest_px = 0;
        int compared = 0;
        for (const Vec3& point : sphere_points(4000)) {
            const std::optional<Vec2> paper = double_sphere_paper_pixel(c.camera, point);
            const Projection ours = camera.project_camera_point(point);
            // Within 1e-9 rad of the domain's edge either answer is right.
            const double angle = std::atan2(point.head<2>().norm(), point.z());
            if (std::abs(angle - camera.valid_radius()) < 1e-9) continue;
            INFO("point " << point.transpose());
            REQUIRE(ours.valid == paper.has_value());
            if (!paper) continue;
            const double error = (ours.pixel - *paper).norm();
            const double allowed =
                1e-9 + 16 * eps * (*paper - principal).norm() * denominator_cancellation(c.camera, point);
            worst = std::max(worst, error / allowed);
            worst_px = std::max(worst_px, error);
            largest_px = std::max(largest_px, (*paper - principal).norm());
            ++compared;
        }
        INFO("worst " << worst_px << " px over " << compared << " points, " << worst
                      << " of what is allowed; pixels up to " << largest_px << " px from the principal point");
        CHECK(compared > 1000);
        CHECK(worst <= 1);
    }
}

TEST_CASE("DOUBLE_SPHERE unprojects as the paper's closed form, and back to the pixel") {
    for (const LensCase& c : lens_cases()) {
        if (c.camera.lens.type != LensType::DoubleSphere) continue;
        INFO(c.name);
        const PreparedCamera camera(c.camera);
        const std::vector<Vec2> pixels = pixel_grid(c.camera.size, 81, 61);
        const std::vector<Unprojection> ours = camera.unproject(pixels);
        double worst_angle = 0, worst_pixel = 0;
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            const std::optional<Vec3> paper = double_sphere_paper_ray(c.camera, pixels[i]);
            INFO("pixel " << pixels[i].transpose());
            REQUIRE(ours[i].valid == paper.has_value());
            if (!paper) continue;
            const Vec3 ray = ours[i].direction.normalized();
            worst_angle = std::max(worst_angle, std::atan2(ray.cross(*paper).norm(), ray.dot(*paper)));
            const std::optional<Vec2> back = double_sphere_paper_pixel(c.camera, ray);
            REQUIRE(back);
            worst_pixel = std::max(worst_pixel, (*back - pixels[i]).norm());
        }
        INFO("worst angle " << worst_angle << " rad, worst reprojection " << worst_pixel << " px");
        CHECK(worst_angle <= 1e-12);
        CHECK(worst_pixel <= 1e-9);
    }
}

TEST_CASE("DOUBLE_SPHERE with alpha = 0 is cv::omnidir's unified camera model") {
    for (const double xi : {0.3, 0.9, 1.0}) {
        INFO("xi " << xi);
        const Camera ucm = double_sphere(xi, 0.0);
        const PreparedCamera camera(ucm);
        // Projection, where the unified model is one-to-one (z > -xi |p| for xi <= 1).
        double worst = 0;
        std::vector<Vec3> inside;
        for (const Vec3& point : sphere_points(3000)) {
            if (point.z() > (-xi + 1e-6) * point.norm()) inside.push_back(point);
        }
        const std::vector<Vec2> theirs = omnidir_pixels(ucm, inside);
        for (std::size_t i = 0; i < inside.size(); ++i) {
            const Projection ours = camera.project_camera_point(inside[i]);
            REQUIRE(ours.valid);
            worst = std::max(worst, (ours.pixel - theirs[i]).norm() / std::max(1.0, (theirs[i] - Vec2(515, 380)).norm() / 1e3));
        }
        INFO("projection: worst " << worst << " px (relative to 1000 px beyond 1000 px from the centre)");
        CHECK(worst <= 1e-9);
        // Unprojection: every pixel's ray goes back to the pixel through cv::omnidir.
        const std::vector<Vec2> pixels = pixel_grid(ucm.size, 41, 31);
        std::vector<Vec3> rays;
        for (const Unprojection& u : camera.unproject(pixels)) {
            REQUIRE(u.valid);
            rays.push_back(u.direction);
        }
        const std::vector<Vec2> back = omnidir_pixels(ucm, rays);
        double worst_back = 0;
        for (std::size_t i = 0; i < pixels.size(); ++i) worst_back = std::max(worst_back, (back[i] - pixels[i]).norm());
        INFO("unprojection reprojected by cv::omnidir: worst " << worst_back << " px");
        CHECK(worst_back <= 1e-9);
    }
}

TEST_CASE("DOUBLE_SPHERE with xi = 0 and alpha = 1/2 is mrcal's STEREOGRAPHIC") {
    // m = (x, y) / (d/2 + z/2) = 2 (x, y) / (|p| + z).
    Camera stereographic = double_sphere(0.0, 0.5);
    const PreparedCamera camera(stereographic);
    stereographic.lens = Lens{LensType::Stereographic, {}};
    std::vector<Vec3> points;
    for (const Vec3& point : sphere_points(3000)) {
        if (point.z() > -0.999 * point.norm()) points.push_back(point);  // mrcal is inaccurate at the backward axis
    }
    const std::vector<Vec2> theirs = mrcal_project_points(stereographic, points);
    double worst = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Projection ours = camera.project_camera_point(points[i]);
        REQUIRE(ours.valid);
        worst = std::max(worst, (ours.pixel - theirs[i]).norm() / std::max(1.0, (theirs[i] - Vec2(515, 380)).norm() / 1e3));
    }
    INFO("worst " << worst << " px (relative to 1000 px beyond 1000 px from the centre)");
    CHECK(worst <= 1e-9);
    CHECK(camera.valid_radius() == std::numbers::pi);  // w1 = 1, w2 = 1: everything but the backward axis
}

TEST_CASE("DOUBLE_SPHERE's valid angle is the one worked by hand, and bad coefficients are refused") {
    // xi = -0.2, alpha = 0.6: w1 = 0.4 / 0.6 = 2/3, 1 - w1^2 = 5/9, and the edge is the root
    // of (c + xi)^2 = w1^2 (1 + 2 xi c + xi^2) with c + xi <= 0:
    // c = -xi (5/9) - w1 sqrt(1 - xi^2 (5/9)) = 1/9 - (2/3) sqrt(1 - 1/45) = -0.5481
    // (123.24 degrees off the axis; the paper's equation 43 would say 122.05).
    const double by_hand = std::acos(1.0 / 9.0 - (2.0 / 3.0) * std::sqrt(1 - 1.0 / 45.0));
    const PreparedCamera camera(double_sphere(-0.2, 0.6));
    CHECK(std::abs(camera.valid_radius() - by_hand) <= 1e-15);
    // On the optical axis every Double Sphere gives the principal point.
    const Projection centre = camera.project_camera_point({0, 0, 3});
    REQUIRE(centre.valid);
    CHECK(centre.pixel == Vec2(515.0, 380.0));

    // alpha < 1/2: the image is unbounded, every pixel has a ray, and the rays of pixels
    // far out approach the cone's edge from inside (m goes to infinity there).
    const PreparedCamera unbounded(double_sphere(0.1, 0.4));
    for (double radius : {1e3, 1e6, 1e9}) {
        const Unprojection far_out = unbounded.unproject(Vec2(515.0 + 300.0 * radius, 380.0));
        INFO("|m| " << radius);
        REQUIRE(far_out.valid);
        const double angle = std::atan2(far_out.direction.head<2>().norm(), far_out.direction.z());
        CHECK(angle <= unbounded.valid_radius());
        CHECK(unbounded.valid_radius() - angle <= 10 / radius);
    }
    // alpha > 1/2: the rim r^2 = 1 / (2 alpha - 1) (here 5, in m) is the domain's edge.
    const double rim = std::sqrt(5.0) * 300.0;
    CHECK(camera.unproject(Vec2(515.0 + rim * (1 - 1e-9), 380.0)).valid);
    CHECK_FALSE(camera.unproject(Vec2(515.0 + rim * (1 + 1e-9), 380.0)).valid);

    const auto refused = [](double xi, double alpha) {
        return test::error_of([&] { PreparedCamera(double_sphere(xi, alpha)); });
    };
    CHECK_THAT(refused(-1.0, 0.5), Catch::Contains("(xi): must be in (-1, 1], got -1"));
    CHECK_THAT(refused(1.5, 0.5), Catch::Contains("(xi): must be in (-1, 1], got 1.5"));
    CHECK_THAT(refused(0.0, -0.1), Catch::Contains("(alpha): must be in [0, 1], got -0.1"));
    CHECK_THAT(refused(0.0, 1.5), Catch::Contains("(alpha): must be in [0, 1], got 1.5"));
}
