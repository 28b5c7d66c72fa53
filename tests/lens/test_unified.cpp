// The unified family (DOUBLE_SPHERE, UCM, EUCM) against the sources that define it:
// their papers' equations (transcribed apart from libcam's headers, in long double),
// OpenCV's cv::omnidir (the unified model; the Double Sphere with alpha = 0), mrcal's
// STEREOGRAPHIC (the Double Sphere with xi = 0 and alpha = 1/2), the relations between
// the models, and the domains' edges worked by hand.

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/ccalib/omnidir.hpp>
#include <vector>

#include "unified_reference.hpp"
#include "lens_cases.hpp"
#include "libcam/error.hpp"
#include "libcam/fit/fit.hpp"
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

// How many times the model's denominator cancels at a point: the sum of its two terms'
// sizes over the size of their sum. Near the edge of an unbounded image (alpha < 1/2,
// xi < 1) it grows without bound, as m goes to infinity: no evaluation in double gives
// m there to better than eps times it.
double denominator_cancellation(const Camera& camera, const Vec3& point) {
    // FOV: an angle; EQUISOLID: |p| + z in a form that does not cancel; CYLINDRICAL: a sum
    // of squares. No denominator cancels.
    const LensType type = camera.lens.type;
    if (type == LensType::Fov || type == LensType::Equisolid || type == LensType::Cylindrical) return 1.0;
    const std::vector<double>& c = camera.lens.coefficients;
    const long double x = point.x(), y = point.y(), z = point.z();
    const long double d1 = std::sqrt(x * x + y * y + z * z);
    long double first = 0, second = 0;  // the denominator is first + second
    if (camera.lens.type == LensType::DoubleSphere) {
        const long double zeta = c[0] * d1 + z;
        first = c[1] * std::sqrt(x * x + y * y + zeta * zeta);
        second = (1 - c[1]) * zeta;
    } else if (camera.lens.type == LensType::Ucm) {
        first = z;
        second = c[0] * d1;
    } else {
        first = c[0] * std::sqrt(c[1] * (x * x + y * y) + z * z);
        second = (1 - c[0]) * z;
    }
    return static_cast<double>((std::abs(first) + std::abs(second)) / std::abs(first + second));
}

bool in_unified_family(const LensCase& c) { return has_paper_formulas(c.camera.lens.type); }

// How far two evaluations of the same m may differ, as pixels: 1e-9 px, and 32 eps of
// the pixel's distance from the principal point times the denominator's cancellation.
double agreement_px(const Camera& camera, const Vec3& point, const Vec2& pixel) {
    const Vec2 principal(camera.intrinsics.cx, camera.intrinsics.cy);
    return 1e-9 + 32 * std::numeric_limits<double>::epsilon() * (pixel - principal).norm() *
                      denominator_cancellation(camera, point);
}

TEST_CASE("DOUBLE_SPHERE, UCM, EUCM, FOV, EQUISOLID and CYLINDRICAL project as their formulas, and flag what they "
          "exclude") {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    for (const LensCase& c : lens_cases()) {
        if (!in_unified_family(c)) continue;
        INFO(c.name);
        const PreparedCamera camera(c.camera);
        const Vec2 principal(c.camera.intrinsics.cx, c.camera.intrinsics.cy);
        // The error over what is allowed: 1e-9 px, and 16 eps of the pixel's distance from
        // the principal point times the denominator's cancellation.
        double worst = 0, worst_px = 0, largest_px = 0;
        int compared = 0;
        for (const Vec3& point : sphere_points(4000)) {
            const std::optional<Vec2> paper = paper_pixel(c.camera, point);
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

TEST_CASE("DOUBLE_SPHERE, UCM, EUCM and FOV unproject as their papers' inverses, and back to the pixel") {
    for (const LensCase& c : lens_cases()) {
        if (!in_unified_family(c)) continue;
        INFO(c.name);
        const PreparedCamera camera(c.camera);
        const std::vector<Vec2> pixels = pixel_grid(c.camera.size, 81, 61);
        const std::vector<Unprojection> ours = camera.unproject(pixels);
        double worst_angle = 0, worst_pixel = 0;
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            const std::optional<Vec3> paper = paper_ray(c.camera, pixels[i]);
            INFO("pixel " << pixels[i].transpose());
            REQUIRE(ours[i].valid == paper.has_value());
            if (!paper) continue;
            const Vec3 ray = ours[i].direction.normalized();
            worst_angle = std::max(worst_angle, std::atan2(ray.cross(*paper).norm(), ray.dot(*paper)));
            const std::optional<Vec2> back = paper_pixel(c.camera, ray);
            REQUIRE(back);
            worst_pixel = std::max(worst_pixel, (*back - pixels[i]).norm());
        }
        INFO("worst angle " << worst_angle << " rad, worst reprojection " << worst_pixel << " px");
        CHECK(worst_angle <= 1e-12);
        CHECK(worst_pixel <= 1e-9);
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

TEST_CASE("UCM, and DOUBLE_SPHERE with alpha = 0, are cv::omnidir's unified camera model, the pinhole inside the sphere or outside it") {
    const Intrinsics k{300.0, 305.0, 515.0, 380.0, 0.0};
    std::vector<Camera> cameras;
    for (const double xi : {0.5, 1.0, 1.4456544769803834, 3.6313355285286337}) {
        cameras.push_back(real_camera(LensType::Ucm, {xi}, {1024, 768}, {k.fx, k.fy, k.cx, k.cy}));
    }
    for (const double xi : {0.3, 0.9, 1.0}) cameras.push_back(double_sphere(xi, 0.0));
    for (const Camera& unified : cameras) {
        const double xi = unified.lens.coefficients[0];
        INFO(lens_info(unified.lens.type).name << " xi " << xi);
        const PreparedCamera camera(unified);
        // Projection where the model is one-to-one: z / |p| > -w, w = xi up to 1, then 1 / xi.
        const double w = xi <= 1 ? xi : 1 / xi;
        std::vector<Vec3> inside;
        for (const Vec3& point : sphere_points(3000)) {
            if (point.z() > (-w + 1e-6) * point.norm()) inside.push_back(point);
        }
        const std::vector<Vec2> theirs = omnidir_pixels(unified, inside);
        double worst = 0;
        for (std::size_t i = 0; i < inside.size(); ++i) {
            const Projection ours = camera.project_camera_point(inside[i]);
            REQUIRE(ours.valid);
            worst = std::max(worst, (ours.pixel - theirs[i]).norm() / std::max(1.0, (theirs[i] - Vec2(k.cx, k.cy)).norm() / 1e3));
        }
        INFO("projection: worst " << worst << " px (relative to 1000 px beyond 1000 px from the centre)");
        CHECK(worst <= 1e-9);
        // Unprojection: every pixel inside the rim r^2 < 1 / (xi^2 - 1) has a ray, which goes
        // back to the pixel through cv::omnidir; no pixel outside it has one. (For xi = 3.63
        // the rim is 86 px from the principal point: the grid is fine enough to put a
        // hundred pixels inside it.)
        const std::vector<Vec2> pixels = pixel_grid(unified.size, 81, 61);
        const std::vector<Unprojection> rays = camera.unproject(pixels);
        std::vector<Vec2> with_ray;
        std::vector<Vec3> directions;
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            const Vec2 m((pixels[i].x() - k.cx) / k.fx, (pixels[i].y() - k.cy) / k.fy);
            const bool inside_rim = xi <= 1 || m.squaredNorm() < 1 / (xi * xi - 1);
            INFO("pixel " << pixels[i].transpose());
            REQUIRE(rays[i].valid == inside_rim);
            if (!rays[i].valid) continue;
            with_ray.push_back(pixels[i]);
            directions.push_back(rays[i].direction);
        }
        const std::vector<Vec2> back = omnidir_pixels(unified, directions);
        double worst_back = 0;
        for (std::size_t i = 0; i < with_ray.size(); ++i) worst_back = std::max(worst_back, (back[i] - with_ray[i]).norm());
        INFO("unprojection reprojected by cv::omnidir: worst " << worst_back << " px over " << with_ray.size() << " pixels");
        CHECK(with_ray.size() > 100);
        CHECK(worst_back <= 1e-9);
    }
}

// Two cameras that are the same map: the same valid angle, the same flags (but within
// 1e-9 rad of the domain's edge) and the same pixels within agreement_px of the second
// (a UCM, whose denominator's two terms measure the cancellation).
void check_same_map(const PreparedCamera& first, const PreparedCamera& second, const std::vector<Vec3>& points) {
    CHECK(first.valid_angle() == Approx(second.valid_angle()).epsilon(1e-15));
    for (const Vec3& point : points) {
        const Projection a = first.project_camera_point(point), b = second.project_camera_point(point);
        const double angle = std::atan2(point.head<2>().norm(), point.z());
        if (std::abs(angle - first.valid_angle()) < 1e-9) continue;
        REQUIRE(a.valid == b.valid);
        if (a.valid) CHECK((a.pixel - b.pixel).norm() <= agreement_px(second.camera(), point, a.pixel));
    }
}

TEST_CASE("UCM with xi <= 1 is DOUBLE_SPHERE with alpha = 0, and EUCM with beta = 1 is UCM with a longer focal length") {
    // EUCM (alpha, 1): m = (x, y) / (alpha |p| + (1 - alpha) z) = (x, y) / ((1 - alpha) (z + xi |p|))
    // with xi = alpha / (1 - alpha): UCM's m over (1 - alpha), so UCM with f / (1 - alpha).
    const std::vector<Vec3> points = sphere_points(2000);
    for (const double xi : {-0.3, 0.4, 1.0}) {
        INFO("xi " << xi);
        const PreparedCamera ucm(real_camera(LensType::Ucm, {xi}, {1024, 768}, {300.0, 305.0, 515.0, 380.0}));
        check_same_map(PreparedCamera(double_sphere(xi, 0.0)), ucm, points);
    }
    for (const double alpha : {0.3, 0.5, 0.62}) {
        INFO("alpha " << alpha);
        const double xi = alpha / (1 - alpha);
        const PreparedCamera eucm(real_camera(LensType::Eucm, {alpha, 1.0}, {1024, 768}, {300.0, 305.0, 515.0, 380.0}));
        const PreparedCamera ucm(
            real_camera(LensType::Ucm, {xi}, {1024, 768}, {300.0 / (1 - alpha), 305.0 / (1 - alpha), 515.0, 380.0}));
        check_same_map(eucm, ucm, points);
    }
}

TEST_CASE("UCM's and EUCM's valid angles and rims are the ones worked by hand, and bad coefficients are refused") {
    // UCM: xi = 2 (w = 1/2) and xi = 1/2 (w = 1/2) both see 120 degrees off the axis.
    for (const double xi : {2.0, 0.5}) {
        const PreparedCamera ucm(real_camera(LensType::Ucm, {xi}, {1024, 768}, {300.0, 305.0, 515.0, 380.0}));
        CHECK(std::abs(ucm.valid_radius() - 2 * std::numbers::pi / 3) <= 1e-15);
    }
    // xi = 2: the rim r^2 = 1 / (xi^2 - 1) = 1/3.
    const PreparedCamera ucm(real_camera(LensType::Ucm, {2.0}, {1024, 768}, {300.0, 300.0, 515.0, 380.0}));
    CHECK(ucm.unproject(Vec2(515.0 + 300.0 * std::sqrt(1.0 / 3) * (1 - 1e-9), 380.0)).valid);
    CHECK_FALSE(ucm.unproject(Vec2(515.0 + 300.0 * std::sqrt(1.0 / 3) * (1 + 1e-9), 380.0)).valid);
    // EUCM alpha = 0.6, beta = 0.5: w = 2/3, c_min = -w sqrt(beta / (1 - w^2 + w^2 beta))
    // = -(2/3) sqrt(0.5 / (7/9)) = -2 / sqrt(14) (122.3 degrees); there z / d = -2/3
    // exactly (d = sqrt(0.5 (10/14) + 4/14) = 3 / sqrt(14)). The rim: r^2 = 1 / (0.2 * 0.5) = 10.
    const PreparedCamera eucm(real_camera(LensType::Eucm, {0.6, 0.5}, {1024, 768}, {300.0, 300.0, 515.0, 380.0}));
    CHECK(std::abs(eucm.valid_radius() - std::acos(-2 / std::sqrt(14.0))) <= 1e-15);
    CHECK(eucm.unproject(Vec2(515.0 + 300.0 * std::sqrt(10.0) * (1 - 1e-9), 380.0)).valid);
    CHECK_FALSE(eucm.unproject(Vec2(515.0 + 300.0 * std::sqrt(10.0) * (1 + 1e-9), 380.0)).valid);
    // On the optical axis both give the principal point.
    CHECK(ucm.project_camera_point({0, 0, 2}).pixel == Vec2(515.0, 380.0));
    CHECK(eucm.project_camera_point({0, 0, 2}).pixel == Vec2(515.0, 380.0));

    const auto refused = [](LensType type, std::vector<double> coefficients) {
        return test::error_of(
            [&] { PreparedCamera(real_camera(type, coefficients, {1024, 768}, {300.0, 305.0, 515.0, 380.0})); });
    };
    CHECK_THAT(refused(LensType::Ucm, {-1.0}), Catch::Contains("(xi): must be above -1, got -1"));
    CHECK_THAT(refused(LensType::Eucm, {1.2, 1.0}), Catch::Contains("(alpha): must be in [0, 1], got 1.2"));
    CHECK_THAT(refused(LensType::Eucm, {0.5, 0.0}), Catch::Contains("(beta): must be positive, got 0"));
}

TEST_CASE("fit: basalt's Double Sphere and EUCM calibrations become an OpenCV model within 0.1 px, as OpenCV projects it", "[sweep]") {
    for (const LensCase& c : lens_cases()) {
        if (c.name != "DOUBLE_SPHERE mild" && c.name != "DOUBLE_SPHERE strong" && c.name != "EUCM mild" &&
            c.name != "EUCM strong") {
            continue;
        }
        FitOptions options;
        options.tolerance_px = 0.1;
        const FitReport report = fit_scene(c.camera, Scene::whole_image(), options);
        REQUIRE(report.chosen);
        const CandidateReport& chosen = report.candidates[*report.chosen];
        const Camera& fitted = chosen.fit.camera;
        INFO(c.name << ": chose " << chosen.fit.candidate.name << ", max " << chosen.max_px << " px by libcam's measure");
        REQUIRE(in_opencv(fitted.lens.type));
        // The fitted camera checked apart from the fit: each pixel's ray by the paper's
        // inverse (long double), projected by OpenCV through the fitted camera. OpenCV
        // takes rays in front of the camera only; the fit's own measure covers the rest.
        std::vector<Vec2> pixels;
        std::vector<Vec3> rays;
        for (const Vec2& pixel : pixel_grid(c.camera.size, 61, 61)) {
            const std::optional<Vec3> ray = paper_ray(c.camera, pixel);
            if (!ray || !(ray->z() > 0.05)) continue;
            pixels.push_back(pixel);
            rays.push_back(*ray);
        }
        const std::vector<Vec2> by_opencv = opencv_project_points(fitted, rays);
        double worst = 0;
        for (std::size_t i = 0; i < pixels.size(); ++i) worst = std::max(worst, (by_opencv[i] - pixels[i]).norm());
        INFO("by OpenCV: worst " << worst << " px over " << pixels.size() << " pixels");
        CHECK(pixels.size() > 1000);
        CHECK(worst <= 0.1);
    }
}

// ---------------------------------------------------------------------------------
// MEI: UCM followed by OPENCV4's radial-tangential distortion, as cv::omnidir defines it.

namespace {

bool is_mei_case(const LensCase& c) { return c.camera.lens.type == LensType::Mei; }

// The angle between a point and the optical axis.
double off_axis(const Vec3& point) { return std::atan2(point.head<2>().norm(), point.z()); }

}  // namespace

TEST_CASE("MEI projects as cv::omnidir::projectPoints over its whole domain, behind the camera too") {
    for (const LensCase& c : lens_cases()) {
        if (!is_mei_case(c)) continue;
        INFO(c.name);
        const PreparedCamera camera(c.camera);
        std::vector<Vec3> inside;
        for (const Vec3& point : sphere_points(3000)) {
            if (off_axis(point) < camera.valid_angle() - 1e-6) inside.push_back(point);
        }
        const std::vector<Vec2> theirs = opencv_project_points(c.camera, inside);
        const Vec2 principal(c.camera.intrinsics.cx, c.camera.intrinsics.cy);
        double worst = 0;
        std::size_t behind = 0;
        for (std::size_t i = 0; i < inside.size(); ++i) {
            const Projection ours = camera.project_camera_point(inside[i]);
            REQUIRE(ours.valid);
            behind += inside[i].z() < 0 ? 1 : 0;
            worst = std::max(worst, (ours.pixel - theirs[i]).norm() / std::max(1.0, (theirs[i] - principal).norm() / 1e3));
        }
        INFO("worst " << worst << " px (relative to 1000 px beyond 1000 px from the centre), " << behind
                      << " of " << inside.size() << " points behind the camera");
        CHECK(behind > 100);
        CHECK(worst <= 1e-9);
    }
}

TEST_CASE("MEI unprojects every pixel of VINS-Fusion's calibrations, back to the pixel through cv::omnidir") {
    for (const LensCase& c : lens_cases()) {
        if (!is_mei_case(c)) continue;
        INFO(c.name);
        const PreparedCamera camera(c.camera);
        const std::vector<double>& k = c.camera.lens.coefficients;
        const double xi = k[0];
        // Where the image of the domain ends, by hand. None of these lenses folds:
        // q (1 + k1 q^2 + k2 q^4) has a positive slope everywhere when 9 k1^2 < 20 k2
        // (the slope's quadratic in q^2 has no real root) or k1, k2 >= 0. For xi > 1 the
        // domain ends at UCM's rim |q| = 1 / sqrt(xi^2 - 1), distorted radially (the
        // tangential terms move it by under 0.5 %); every pixel closer to the principal
        // point than that has a ray. For xi <= 1 the image is unbounded: every pixel.
        REQUIRE((9 * k[1] * k[1] < 20 * k[2] || (k[1] >= 0 && k[2] >= 0)));
        double reach = std::numeric_limits<double>::infinity();
        if (xi > 1) {
            const double rim = 1 / std::sqrt(xi * xi - 1);
            reach = rim * (1 + k[1] * rim * rim + k[2] * std::pow(rim, 4)) * 0.995;
        }
        const std::vector<Vec2> pixels = pixel_grid(c.camera.size, 76, 49);
        const std::vector<Unprojection> rays = camera.unproject(pixels);
        std::vector<Vec2> with_ray;
        std::vector<Vec3> directions;
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            const Vec2 m = c.camera.intrinsics.normalized_from_pixel(pixels[i]);
            INFO("pixel " << pixels[i].transpose());
            if (m.norm() < reach) REQUIRE(rays[i].valid);
            if (!rays[i].valid) continue;
            with_ray.push_back(pixels[i]);
            directions.push_back(rays[i].direction);
        }
        const std::vector<Vec2> back = opencv_project_points(c.camera, directions);
        double worst = 0;
        for (std::size_t i = 0; i < with_ray.size(); ++i) worst = std::max(worst, (back[i] - with_ray[i]).norm());
        INFO("libcam's rays reprojected by cv::omnidir: worst " << worst << " px over " << with_ray.size() << " pixels");
        CHECK(with_ray.size() > 3000);
        CHECK(worst <= 1e-9);
    }
}

TEST_CASE("MEI without distortion is UCM, and its valid radius and angle are UCM's rim and edge or the fold, worked by hand") {
    const std::vector<Vec3> points = sphere_points(2000);
    for (const double xi : {0.5, 1.0, 2.0, 3.6313355285286337}) {
        INFO("xi " << xi);
        const PreparedCamera mei(real_camera(LensType::Mei, {xi, 0, 0, 0, 0}, {1024, 768}, {300.0, 305.0, 515.0, 380.0}));
        const PreparedCamera ucm(real_camera(LensType::Ucm, {xi}, {1024, 768}, {300.0, 305.0, 515.0, 380.0}));
        check_same_map(mei, ucm, points);
        for (const Vec2& pixel : pixel_grid({1024, 768}, 33, 25)) {
            const Unprojection a = mei.unproject(pixel), b = ucm.unproject(pixel);
            REQUIRE(a.valid == b.valid);
            if (a.valid) CHECK(angle_between(a.direction, b.direction) <= 1e-13);
        }
    }
    // xi = 1: q = tan(theta / 2) (x, y) / |(x, y)|, unbounded; k1 = -1/2 folds at
    // |q| = sqrt(2/3), so the lens sees theta < 2 atan(sqrt(2/3)), and a pixel has a ray
    // exactly when |m| < d_max = (2/3) sqrt(2/3).
    const PreparedCamera folding(real_camera(LensType::Mei, {1.0, -0.5, 0, 0, 0}, {1024, 768}, {300.0, 300.0, 515.0, 380.0}));
    const double fold = std::sqrt(2.0 / 3);
    CHECK(std::abs(folding.valid_radius() - fold) <= 1e-15);
    CHECK(std::abs(folding.valid_angle() - 2 * std::atan(fold)) <= 1e-14);
    const double d_max = 2.0 / 3 * fold;
    CHECK(folding.unproject(Vec2(515.0 + 300.0 * d_max * (1 - 1e-6), 380.0)).valid);
    CHECK_FALSE(folding.unproject(Vec2(515.0 + 300.0 * d_max * (1 + 1e-6), 380.0)).valid);
    CHECK_FALSE(folding.project_camera_point(Vec3(std::sin(2 * std::atan(fold) + 1e-6), 0, std::cos(2 * std::atan(fold) + 1e-6))).valid);
    // xi = 2 and no fold: UCM's rim |q| = 1 / sqrt(3), its edge cos(theta) = -1 / xi, 120 degrees.
    const PreparedCamera edge(real_camera(LensType::Mei, {2.0, 0.1, 0.01, 0, 0}, {1024, 768}, {300.0, 300.0, 515.0, 380.0}));
    CHECK(std::abs(edge.valid_radius() - 1 / std::sqrt(3.0)) <= 1e-15);
    CHECK(std::abs(edge.valid_angle() - 2 * std::numbers::pi / 3) <= 1e-15);
    // A perspective lens: the angle of its radius of (x/z, y/z); OPENCV4 k1 = -1/2 folds at
    // r = sqrt(2/3).
    const PreparedCamera perspective(real_camera(LensType::OpenCv4, {-0.5, 0, 0, 0}, {1024, 768}, {300.0, 300.0, 515.0, 380.0}));
    CHECK(std::abs(perspective.valid_angle() - std::atan(fold)) <= 1e-15);
    CHECK_THAT(test::error_of([] {
                   PreparedCamera(real_camera(LensType::Mei, {-1.5, 0, 0, 0, 0}, {1024, 768}, {300.0, 300.0, 515.0, 380.0}));
               }),
               Catch::Contains("(xi): must be above -1, got -1.5"));
}

// ---------------------------------------------------------------------------------
// FOV: r_d = atan(2 tan(omega / 2) r) / omega, on behind the camera as basalt writes it.

TEST_CASE("FOV's radii worked by hand, behind the camera too, and its image's edge") {
    // omega = pi / 2: 2 tan(omega / 2) = 2, so r_d = atan2(2 sin(theta), cos(theta)) / (pi / 2).
    const Camera camera = real_camera(LensType::Fov, {std::numbers::pi / 2}, {1024, 768}, {300.0, 300.0, 515.0, 380.0});
    const PreparedCamera fov(camera);
    const double s = std::sqrt(0.5);
    const struct {
        Vec3 point;
        double distorted_radius;
    } by_hand[] = {
        {{s, 0, s}, 2 * std::atan(2.0) / std::numbers::pi},       // 45 degrees
        {{0, 1, 0}, 1.0},                                         // 90 degrees: atan2(2, 0) = pi / 2
        {{-s, 0, -s}, 2 - 2 * std::atan(2.0) / std::numbers::pi},  // 135 degrees: pi - atan(2)
    };
    for (const auto& [point, distorted_radius] : by_hand) {
        INFO("point " << point.transpose());
        const Projection p = fov.project_camera_point(point);
        REQUIRE(p.valid);
        const Vec2 expected = Vec2(515.0, 380.0) + 300.0 * distorted_radius * point.head<2>().normalized();
        CHECK((p.pixel - expected).norm() <= 1e-12);
        const Unprojection back = fov.unproject(expected);
        REQUIRE(back.valid);
        CHECK(angle_between(back.direction, point) <= 1e-15);
    }
    CHECK(fov.valid_radius() == std::numbers::pi);
    CHECK_FALSE(fov.project_camera_point({0, 0, -1}).valid);  // the backward axis
    // The image is the disc r_d < pi / omega = 2 (600 px).
    CHECK(fov.unproject(Vec2(515.0, 380.0 + 600.0 * (1 - 1e-9))).valid);
    CHECK_FALSE(fov.unproject(Vec2(515.0, 380.0 + 600.0 * (1 + 1e-9))).valid);
    const auto refused = [](double omega) {
        return test::error_of([&] { PreparedCamera(real_camera(LensType::Fov, {omega}, {1024, 768}, {300.0, 300.0, 515.0, 380.0})); });
    };
    CHECK_THAT(refused(-0.1), Catch::Contains("(omega): must be in [0, pi) radians, got -0.1"));
    CHECK_THAT(refused(4.0), Catch::Contains("(omega): must be in [0, pi) radians, got 4"));
}

TEST_CASE("FOV as omega -> 0 becomes the pinhole, and omega = 0 is the pinhole exactly") {
    // r_d = atan(2 tan(omega / 2) r) / omega = r + omega^2 (r / 12 - r^3 / 3) + O(omega^4)
    // for r = |(x, y)| / z (by the series of tan and atan).
    const Intrinsics k{300.0, 305.0, 515.0, 380.0, 0.0};
    const Camera pinhole_camera = real_camera(LensType::Pinhole, {}, {1024, 768}, {k.fx, k.fy, k.cx, k.cy});
    const PreparedCamera pinhole(pinhole_camera);
    for (const double omega : {0.0, 1e-12, 1e-8, 1e-4}) {
        INFO("omega " << omega);
        const PreparedCamera fov(real_camera(LensType::Fov, {omega}, {1024, 768}, {k.fx, k.fy, k.cx, k.cy}));
        CHECK(fov.valid_radius() == (omega > 0 ? std::numbers::pi : std::numbers::pi / 2));
        for (const Vec3& point : sphere_points(500)) {
            const Projection a = fov.project_camera_point(point), b = pinhole.project_camera_point(point);
            if (!(point.z() > 0)) {
                CHECK(a.valid == (omega > 0 && point.head<2>().norm() > 0));
                continue;
            }
            REQUIRE(a.valid);
            const double r = point.head<2>().norm() / point.z();
            const double shift = omega * omega * std::abs(r / 12 - r * r * r / 3) * 305.0;
            CHECK((a.pixel - b.pixel).norm() <= 1e-9 * std::max(1.0, (b.pixel - Vec2(k.cx, k.cy)).norm() / 1e3) + 2 * shift);
        }
        for (const Vec2& pixel : pixel_grid({1024, 768}, 17, 13)) {
            const Unprojection a = fov.unproject(pixel), b = pinhole.unproject(pixel);
            REQUIRE(a.valid);
            CHECK(angle_between(a.direction, b.direction) <= 1e-15 + omega * omega);
        }
    }
}
