// Unprojection: every valid pixel reprojects, through OpenCV or mrcal, to within 1e-9 px;
// every pixel that an independent solver (mrcal_unproject, cv::undistortPoints) shows
// to have a ray inside the valid domain is valid; where the lens folds over inside the
// image, exactly the pixels past the fold (worked by hand) are flagged.

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/calib3d.hpp>

#include "lens_cases.hpp"
#include "libcam/camera/projector.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/interop/mrcal.hpp"
#include "libcam/interop/opencv.hpp"
#include "libcam/lens/lens_models.hpp"
#include "support.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

constexpr double kPixelTolerance = 1e-9;

struct GridResult {
    std::vector<Vec2> pixels;
    std::vector<Unprojection> rays;
    std::vector<double> residuals;  // reprojection error of each valid pixel, px; NaN if invalid
    double worst = 0;
    std::size_t valid = 0;
};

GridResult unproject_grid(const Camera& camera, int nx, int ny) {
    GridResult result;
    result.pixels = pixel_grid(camera.size, nx, ny);
    result.rays = PreparedCamera(camera).unproject(result.pixels);
    std::vector<Vec3> directions;
    for (const Unprojection& u : result.rays) directions.push_back(u.valid ? u.direction : Vec3(0, 0, 1));
    const std::vector<Vec2> reprojected = reference_project(camera, directions);
    result.residuals.assign(result.pixels.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < result.pixels.size(); ++i) {
        if (!result.rays[i].valid) continue;
        ++result.valid;
        result.residuals[i] = (reprojected[i] - result.pixels[i]).norm();
        result.worst = std::max(result.worst, result.residuals[i]);
    }
    return result;
}

// The radius of the undistorted point of a ray, in the units of the model's
// valid_radius: |(x/z, y/z)| for OpenCV's models, the angle for a model that sees behind the camera.
double undistorted_radius(LensType type, const Vec3& ray) {
    if (lens_info(type).sees_behind_camera) return std::atan2(std::hypot(ray.x(), ray.y()), ray.z());  // an angle
    return std::hypot(ray.x(), ray.y()) / ray.z();
}

// Rays by a solver independent of libcam: mrcal_unproject, or for what mrcal lacks
// cv::undistortPoints (cv::fisheye::undistortPoints) at many iterations.
std::vector<Vec3> independent_unproject(const Camera& camera, const std::vector<Vec2>& pixels) {
    if (has_paper_formulas(camera.lens.type)) {  // the papers' inverses, in long double
        std::vector<Vec3> rays;
        for (const Vec2& pixel : pixels) rays.push_back(paper_ray(camera, pixel).value_or(Vec3::Constant(NAN)));
        return rays;
    }
    if (in_mrcal(camera.lens.type)) return mrcal_unproject_pixels(camera, pixels);
    std::vector<cv::Point2d> in, out;
    for (const Vec2& p : pixels) in.emplace_back(p.x(), p.y());
    // Many iterations, or for cv::omnidir its fixed 20 (it has no rule to set).
    const OpenCvCamera opencv(camera);
    const cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-15);
    opencv_undistort(opencv, in, out,
                     opencv.function == OpenCvFunction::Omnidir ? std::nullopt : std::optional(criteria));
    std::vector<Vec3> rays;
    for (const cv::Point2d& q : out) rays.emplace_back(q.x, q.y, 1.0);
    return rays;
}

}  // namespace

TEST_CASE("The real wide lens (6016x4016, OPENCV8): every pixel of a 601x401 grid unprojects to within 1e-9 px") {
    const Camera camera = wide_reference_camera();
    const GridResult grid = unproject_grid(camera, 601, 401);
    CHECK(grid.valid == grid.pixels.size());
    CHECK(grid.worst <= kPixelTolerance);
    WARN("wide lens, 601x401 pixels: " << grid.valid << " valid, worst reprojection residual through cv::projectPoints "
                                       << grid.worst << " px");
}

TEST_CASE("Unprojection agrees with mrcal_unproject and cv::undistortPoints wherever they converge inside the domain", "[sweep]") {
    std::vector<LensCase> cases = lens_cases();
    for (const LensCase& c : cases) {
        // COLMAP's models have no independent inverse here; test_unprojector reprojects
        // their rays through COLMAP's formula instead.
        if (colmap_only(c.camera.lens.type)) continue;
        // mrcal 2.2 cannot unproject CAHVORE; test_lens_models reprojects libcam's rays of
        // it through mrcal_project instead.
        if (c.camera.lens.type == LensType::Cahvore) continue;
        // Nor has PanoTools' polynomial (PTLENS, the fisheye *_RADIAL models) an independent
        // inverse: test_unprojector reprojects their rays through PanoTools' formula
        // (lens_cases.hpp, reference_project).
        if (panotools_polynomial(c.camera.lens.type)) continue;
        // Nor has BROWN_K4 (Metashape's and RealityCapture's formulas go one way): its rays
        // are reprojected through Metashape's formula in the same way.
        if (c.camera.lens.type == LensType::BrownK4) continue;
        // OCAMCALIB's unprojection is its own formula (checked against Scaramuzza's cam2world
        // on every OCamCalib file in test_io); test_unprojector reprojects its rays through
        // the root of its polynomial, as his MATLAB world2cam finds it.
        if (c.camera.lens.type == LensType::OcamCalib) continue;
        INFO(c.name);
        const GridResult grid = unproject_grid(c.camera, 121, 91);
        CHECK(grid.worst <= kPixelTolerance);
        const std::vector<Vec3> theirs = independent_unproject(c.camera, grid.pixels);
        std::vector<Vec3> their_rays;
        for (const Vec3& ray : theirs) their_rays.push_back(ray.allFinite() ? ray : Vec3(0, 0, 1));
        const std::vector<Vec2> their_reprojected = reference_project(c.camera, their_rays);
        const double limit = domain_edge_of(c.camera.lens);
        const bool radial_domain = c.camera.lens.type != LensType::Pinhole && c.camera.lens.type != LensType::Stereographic &&
                                   c.camera.lens.type != LensType::Lonlat && c.camera.lens.type != LensType::Latlon;
        std::size_t compared = 0;
        double worst_angle = 0;
        for (std::size_t i = 0; i < grid.pixels.size(); ++i) {
            const bool they_converged = theirs[i].allFinite() && (their_reprojected[i] - grid.pixels[i]).norm() < 1e-6;
            if (!they_converged) continue;
            const double radius = radial_domain ? undistorted_radius(c.camera.lens.type, theirs[i]) / limit : 0.0;
            if (!(radius < 0.999)) continue;
            INFO("pixel " << grid.pixels[i].transpose());
            REQUIRE(grid.rays[i].valid);
            ++compared;
            // Right at the fold a ray is ill-conditioned in its pixel (their 1e-6 px moves it
            // far); compare directions where that does not swamp the comparison.
            if (radius < 0.9) worst_angle = std::max(worst_angle, angle_between(grid.rays[i].direction, theirs[i]));
        }
        // Not vacuous: they converge on at least a quarter of the pixels whose ray they
        // can express at all (OpenCV's (x, y, 1) only rays in front of the camera).
        const auto in_front = static_cast<std::size_t>(std::count_if(grid.rays.begin(), grid.rays.end(), [](const Unprojection& r) {
            return r.valid && r.direction.z() > 0;
        }));
        INFO(compared << " pixels compared of " << in_front << " whose ray is in front of the camera");
        CHECK(compared > in_front / 4);
        CHECK(worst_angle < 1e-8);
    }
}

TEST_CASE("A lens that folds over inside the image: pixels past the fold are flagged, the others exact") {
    for (const FoldCase& fold : fold_cases()) {
        INFO(fold.name);
        const GridResult grid = unproject_grid(fold.camera, 161, 121);
        CHECK(grid.worst <= kPixelTolerance);
        std::size_t flagged = 0;
        for (std::size_t i = 0; i < grid.pixels.size(); ++i) {
            const double radius = fold.camera.intrinsics.normalized_from_pixel(grid.pixels[i]).norm();
            INFO("pixel " << grid.pixels[i].transpose() << " |m| " << radius);
            if (radius < fold.d_max * (1 - 1e-9)) CHECK(grid.rays[i].valid);
            if (radius > fold.d_max * (1 + 1e-9)) CHECK_FALSE(grid.rays[i].valid);
            flagged += grid.rays[i].valid ? 0 : 1;
        }
        CHECK(flagged > grid.pixels.size() / 10);  // the fold is inside the image
    }
}

TEST_CASE("Closed forms: STEREOGRAPHIC, LONLAT and LATLON against their formulas") {
    // STEREOGRAPHIC: the ray through m makes the angle 2 atan(|m| / 2) with the axis.
    const Camera stereo = lens_camera(LensType::Stereographic, {}, {1600, 1200}, 200, 200);
    const PreparedCamera stereo_prepared(stereo);
    for (const Vec2& pixel : pixel_grid(stereo.size, 41, 31)) {
        const Unprojection unprojection = stereo_prepared.unproject(pixel);
        REQUIRE(unprojection.valid);
        const Vec3& ray = unprojection.direction;
        const double m = stereo.intrinsics.normalized_from_pixel(pixel).norm();
        CHECK(std::abs(angle_between(ray, Vec3::UnitZ()) - 2 * std::atan(m / 2)) < 1e-14);
    }
    // LONLAT with a field wider than the sphere: a pixel has a ray exactly when
    // |lon| <= pi and |lat| <= pi/2, lon = (x - cx) / fx, lat = (y - cy) / fy.
    const Camera lonlat = lens_camera(LensType::Lonlat, {}, {2000, 1000}, 240, 240);
    const Camera latlon = lens_camera(LensType::Latlon, {}, {1000, 2000}, 240, 240);
    for (const Camera* camera : {&lonlat, &latlon}) {
        const bool swapped = camera == &latlon;
        INFO(lens_info(camera->lens.type).name);
        const GridResult grid = unproject_grid(*camera, 161, 121);
        CHECK(grid.worst <= kPixelTolerance);
        for (std::size_t i = 0; i < grid.pixels.size(); ++i) {
            const Vec2 m = camera->intrinsics.normalized_from_pixel(grid.pixels[i]);
            const double lon = swapped ? m.y() : m.x(), lat = swapped ? m.x() : m.y();
            CHECK(grid.rays[i].valid == (std::abs(lon) <= std::numbers::pi && std::abs(lat) <= std::numbers::pi / 2));
        }
    }
}

TEST_CASE("Closed forms: CYLINDRICAL against its formula, worked by hand") {
    // A full turn across 2000 px and then some (f = 300 px per radian: 382 degrees): a
    // pixel has a ray exactly when |lon| <= pi, lon = (x - cx) / fx; its ray has
    // longitude lon and rises tan(latitude) = (y - cy) / fy.
    const Camera cylinder = lens_camera(LensType::Cylindrical, {}, {2000, 1000}, 300, 300);
    const GridResult grid = unproject_grid(cylinder, 161, 121);
    CHECK(grid.worst <= kPixelTolerance);
    for (std::size_t i = 0; i < grid.pixels.size(); ++i) {
        const Vec2 m = cylinder.intrinsics.normalized_from_pixel(grid.pixels[i]);
        REQUIRE(grid.rays[i].valid == (std::abs(m.x()) <= std::numbers::pi));
        if (!grid.rays[i].valid) continue;
        const Vec3& ray = grid.rays[i].direction;
        const double across = std::hypot(ray.x(), ray.z());
        CHECK(std::abs(std::atan2(ray.x(), ray.z()) - m.x()) < 1e-14);
        CHECK(std::abs(ray.y() / across - m.y()) < 1e-14 * std::max(1.0, std::abs(m.y())));
    }
    // The point (1, 1, 1): 45 degrees across, 1 / sqrt(2) up the unit cylinder; (-1, 0, -1)
    // behind the camera: 135 degrees the other way.
    const PreparedCamera prepared(cylinder);
    const Projection corner = prepared.project_camera_point(Vec3(1, 1, 1));
    REQUIRE(corner.valid);
    CHECK(std::abs(corner.pixel.x() - (cylinder.intrinsics.cx + 300 * std::numbers::pi / 4)) < 1e-12);
    CHECK(std::abs(corner.pixel.y() - (cylinder.intrinsics.cy + 300 / std::sqrt(2.0))) < 1e-12);
    const Projection behind = prepared.project_camera_point(Vec3(-1, 0, -1));
    REQUIRE(behind.valid);
    CHECK(std::abs(behind.pixel.x() - (cylinder.intrinsics.cx - 300 * 3 * std::numbers::pi / 4)) < 1e-12);
}

TEST_CASE("OCAMCALIB: its fold radius, its widest angle and a point behind the camera, worked by hand") {
    // g(r) = 1 + k2 r^2 with k2 = 0.25: theta stops growing where h = 1 - k2 r^2 = 0, at
    // r = 2, the ray (2, 0, 2) there: 45 degrees. With k2 = -0.25 it never stops, and theta
    // tends to 180 degrees. The affine identity, f = 100 px.
    const Camera folding = lens_camera(LensType::OcamCalib, {1, 0, 0, 0, 0.25, 0, 0, 0}, {800, 600}, 100, 100);
    const PreparedCamera fold(folding);
    CHECK(fold.valid_radius() == Approx(2.0).epsilon(1e-14));
    CHECK(fold.valid_angle() == Approx(std::numbers::pi / 4).epsilon(1e-14));
    const Camera wide = lens_camera(LensType::OcamCalib, {1, 0, 0, 0, -0.25, 0, 0, 0}, {800, 600}, 100, 100);
    const PreparedCamera open(wide);
    CHECK(std::isinf(open.valid_radius()));
    CHECK(open.valid_angle() == std::numbers::pi);
    // The point (1, 0, -1), 135 degrees from the axis: g(r) = -r, 0.25 r^2 - r - 1 = 0,
    // r = 2 + 2 sqrt(2).
    const Projection behind = open.project_camera_point(Vec3(1, 0, -1));
    REQUIRE(behind.valid);
    CHECK(behind.pixel.x() == Approx(wide.intrinsics.cx + 100 * (2 + 2 * std::sqrt(2.0))).epsilon(1e-14));
    CHECK(behind.pixel.y() == Approx(wide.intrinsics.cy).margin(1e-12));
    // An affine [1 e; d c]: the pixel of the sensor point n is K (n_x + e n_y, d n_x + c n_y).
    const Camera affine = lens_camera(LensType::OcamCalib, {1.01, 0.02, -0.03, 0, -0.25, 0, 0, 0}, {800, 600}, 100, 100);
    const Projection skewed = PreparedCamera(affine).project_camera_point(Vec3(1, 0, -1));
    REQUIRE(skewed.valid);
    const double r = 2 + 2 * std::sqrt(2.0);
    CHECK(skewed.pixel.x() == Approx(affine.intrinsics.cx + 100 * r).epsilon(1e-14));
    CHECK(skewed.pixel.y() == Approx(affine.intrinsics.cy + 100 * 0.02 * r).epsilon(1e-14));
}

TEST_CASE("FTHETA and FTHETA_FORWARD: their fold, max_angle and points behind the camera, worked by hand") {
    // FTHETA theta(r) = r - r^3 / 12 stops growing at r = 2 (theta' = 1 - r^2 / 4), where
    // theta = 4/3 rad; bounded at max_angle = pi that fold is the edge.
    const Camera folding = lens_camera(LensType::FTheta, {1, 0, 0, 1, 0, -1.0 / 12, 0, 0, std::numbers::pi}, {800, 600}, 100, 100);
    const PreparedCamera fold(folding);
    CHECK(fold.valid_radius() == Approx(2.0).epsilon(1e-14));
    CHECK(fold.valid_angle() == Approx(4.0 / 3).epsilon(1e-14));
    // The equidistant theta = r bounded at max_angle = 2 rad (115 degrees): the point
    // (0, 1, -0.2), 100.3 degrees off the axis, lands at r = pi - atan(5) along +y; the
    // affine [c d; e 1] puts n = (0, r) at m = (d r, r). (1, 0, -1), 135 degrees off, is past it.
    const Camera bounded = lens_camera(LensType::FTheta, {1.01, 0.02, -0.03, 1, 0, 0, 0, 0, 2.0}, {800, 600}, 100, 100);
    const PreparedCamera equidistant(bounded);
    CHECK(equidistant.valid_angle() == Approx(2.0).epsilon(1e-14));
    const double r = std::numbers::pi - std::atan(5.0);
    const Projection behind = equidistant.project_camera_point(Vec3(0, 1, -0.2));
    REQUIRE(behind.valid);
    CHECK(behind.pixel.x() == Approx(bounded.intrinsics.cx + 100 * 0.02 * r).epsilon(1e-14));
    CHECK(behind.pixel.y() == Approx(bounded.intrinsics.cy + 100 * r).epsilon(1e-14));
    CHECK_FALSE(equidistant.project_camera_point(Vec3(1, 0, -1)).valid);
    const Unprojection back = equidistant.unproject(behind.pixel);
    REQUIRE(back.valid);
    CHECK((back.direction.normalized() - Vec3(0, 1, -0.2).normalized()).norm() < 1e-14);
    // FTHETA_FORWARD rho(theta) = theta - theta^3 / 12, the same fold at theta = 2 (rho =
    // 4/3): (0, 1, -0.2) lands at rho(pi - atan(5)) along +y, and its pixel's ray is the point's.
    const Camera forward = lens_camera(LensType::FThetaForward, {1.01, 0.02, -0.03, 1, 0, -1.0 / 12, 0, 0, std::numbers::pi},
                                       {800, 600}, 100, 100);
    const PreparedCamera forward_lens(forward);
    CHECK(forward_lens.valid_radius() == Approx(2.0).epsilon(1e-14));
    const double rho = r - r * r * r / 12;
    const Projection forward_behind = forward_lens.project_camera_point(Vec3(0, 1, -0.2));
    REQUIRE(forward_behind.valid);
    CHECK(forward_behind.pixel.x() == Approx(forward.intrinsics.cx + 100 * 0.02 * rho).epsilon(1e-14));
    CHECK(forward_behind.pixel.y() == Approx(forward.intrinsics.cy + 100 * rho).epsilon(1e-14));
    const Unprojection forward_back = forward_lens.unproject(forward_behind.pixel);
    REQUIRE(forward_back.valid);
    CHECK((forward_back.direction.normalized() - Vec3(0, 1, -0.2).normalized()).norm() < 1e-13);
    CHECK_FALSE(forward_lens.project_camera_point(Vec3(1, 0, -1)).valid);  // 135 degrees: past the fold
}

TEST_CASE("Closed forms: DIVISION against COLMAP's formula, worked by hand") {
    // u = m / (1 + k |m|^2), the ray (m, 1 + k |m|^2). k = -0.2, m = (0.3, 0.4): |m|^2 =
    // 0.25, the ray (0.3, 0.4, 0.95).
    const auto camera_with = [](double k) { return lens_camera(LensType::Division, {k}, {1000, 1000}, 100, 100); };
    const PreparedCamera barrel(camera_with(-0.2));
    const Vec2 centre(barrel.camera().intrinsics.cx, barrel.camera().intrinsics.cy);
    const Unprojection ray = barrel.unproject(centre + Vec2(30, 40));
    REQUIRE(ray.valid);
    CHECK((ray.direction.normalized() - Vec3(0.3, 0.4, 0.95).normalized()).norm() < 1e-15);
    // COLMAP's ImgFromCam for (1, 0, 2), k = 0.1: D = (2 + sqrt(4 - 0.4)) / 2, m = 1 / D =
    // 0.51316701949486200 (1 / 1.9486832980505138; and 0.51316... / (1 + 0.1 * 0.51316...^2)
    // = 0.5 = X / Z).
    const PreparedCamera pincushion(camera_with(0.1));
    const Projection front = pincushion.project_camera_point(Vec3(1, 0, 2));
    REQUIRE(front.valid);
    CHECK(std::abs(front.pixel.x() - (centre.x() + 100 * 0.51316701949486200)) < 1e-11);
    // Past the fold: 1 / (2 sqrt(0.1)) = 1.5811 is the largest X / Z it images.
    CHECK_FALSE(pincushion.project_camera_point(Vec3(1.6, 0, 1)).valid);
    CHECK(pincushion.project_camera_point(Vec3(1.58, 0, 1)).valid);
    CHECK_FALSE(pincushion.unproject(centre + Vec2(100 / std::sqrt(0.1) + 1e-6, 0)).valid);
    // k = -0.5 sees behind the camera: (1, 0, -1) is m = 1 + sqrt(3) (the ray (m, 1 - m^2 / 2)
    // = (2.732, -2.732)), and the backward axis has no image.
    const PreparedCamera wide(camera_with(-0.5));
    const Projection behind = wide.project_camera_point(Vec3(1, 0, -1));
    REQUIRE(behind.valid);
    CHECK(std::abs(behind.pixel.x() - (centre.x() + 100 * (1 + std::sqrt(3.0)))) < 1e-11);
    CHECK_FALSE(wide.project_camera_point(Vec3(0, 0, -1)).valid);
}

TEST_CASE("The one solver runs in float and long double too") {
    const Camera camera = wide_reference_camera();
    const auto check = [&]<class Scalar>(Scalar tolerance) {
        using Model = OpenCv8Lens<Scalar>;
        const auto lens = Model::parameters(camera.lens.coefficients);
        double worst = 0;
        for (const Vec2& pixel : pixel_grid(camera.size, 31, 21)) {
            const Eigen::Matrix<Scalar, 2, 1> m = camera.intrinsics.normalized_from_pixel(pixel).template cast<Scalar>();
            Eigen::Matrix<Scalar, 3, 1> ray = Eigen::Matrix<Scalar, 3, 1>::Zero();
            Eigen::Matrix<Scalar, 2, 1> back = Eigen::Matrix<Scalar, 2, 1>::Zero();
            REQUIRE(Model::unproject(lens, m, ray));
            REQUIRE(Model::project(lens, ray, back));
            worst = std::max(worst, double((back - m).norm()));
        }
        CHECK(worst <= double(tolerance));
    };
    check(2e-6f);     // about 64 float roundings of |m| ~ 3
    check(1e-17L);    // long double: a thousand times below double's result
}

TEST_CASE("A camera it cannot use is refused when it is prepared, naming the field: never a silent wrong pixel") {
    using Catch::Matchers::Contains;
    const Camera good = wide_reference_camera();
    struct Misuse {
        const char* what;
        Camera camera;
        const char* field;
    };
    std::vector<Misuse> cases;
    const auto with = [&](const char* what, const char* field, auto&& change) {
        Camera camera = good;
        change(camera);
        cases.push_back({what, camera, field});
    };
    with("fx = 0 (would give every point the pixel cx)", "K.fx", [](Camera& c) { c.intrinsics.fx = 0; });
    with("fy NaN", "K.fy", [](Camera& c) { c.intrinsics.fy = std::nan(""); });
    with("cx infinite", "K.cx", [](Camera& c) { c.intrinsics.cx = INFINITY; });
    with("7 coefficients for OPENCV8", "dist", [](Camera& c) { c.lens.coefficients.pop_back(); });
    with("a NaN coefficient", "dist[2]", [](Camera& c) { c.lens.coefficients[2] = std::nan(""); });
    with("R scaled by 2", "R", [](Camera& c) { c.pose.R *= 2.0; });
    with("t NaN", "t", [](Camera& c) { c.pose.t.x() = std::nan(""); });
    with("a zero-sized image", "image_size", [](Camera& c) { c.size.width = 0; });
    for (const Misuse& m : cases) {
        CAPTURE(m.what);
        CHECK_THAT(error_of([&] { (void)PreparedCamera(m.camera); }), Contains(m.field));
        CHECK_THAT(error_of([&] { (void)Projector<double>(m.camera); }), Contains(m.field));
        CHECK_THAT(error_of([&] { (void)Unprojector<float>(m.camera); }), Contains(m.field));
    }
    CHECK(PreparedCamera(good).project_camera_point(Vec3(0.1, 0.2, 1.0)).valid);
}

// Camera::validate's rule for numbers that image nothing (camera.cpp): each case's line
// worked by hand. A 640x480 camera, f = 500, principal point at the centre.
TEST_CASE("A camera whose numbers contradict each other is refused, naming the number, and real lenses are not") {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {500.0, 500.0, 319.5, 239.5, 0.0};
    const auto refusal = [&](const Lens& lens, double fx = 500.0) {
        Camera with = camera;
        with.lens = lens;
        with.intrinsics.fx = fx;
        return error_of([&] { with.validate(); });  // "InvalidArgument: <message>"
    };
    // 5e-324 is subnormal: 1 / 5e-324 overflows.
    CHECK(refusal({}, 5e-324) ==
          "InvalidArgument: K.fx: 5e-324 is subnormal (a focal length must be at least 2.2250738585072014e-308)");
    // k1 = 1e30: r + k1 r^3 = m has r = C t^(1/3) at t pixels off the axis. From t0 = 2^-20,
    // r moves per pixel (2^(-10/3) - 2^(-20/3)) C / (2^-10 - 2^-20) = 91.60 C over the
    // first 1/1024 of a pixel and (1 - 2^(-20/3)) C / (1 - 2^-20) = 0.9902 C over the
    // whole: a factor of 92.5.
    const std::string tail = " within the pixel (1, 0) off the principal point (by at most 2 in a camera: its focal "
                             "length is the lens's scale there)";
    CHECK(refusal({LensType::OpenCv4, {1e30, 0.0, 0.0, 0.0}}) ==
          "InvalidArgument: dist[0] (k1): 1e+30: the lens's scale changes by a factor of 92.5" + tail);
    // k1 = -1e30 folds the lens over at r = 1 / sqrt(3e30): 2.9e-13 pixels from the centre.
    CHECK(refusal({LensType::OpenCv4, {-1e30, 0.0, 0.0, 0.0}}) ==
          "InvalidArgument: dist[0] (k1): -1e+30: the pixel (1, 0) off the principal point has no ray");
    CHECK(refusal({LensType::OpenCv5, {-0.2, 0.05, 0.0, 0.0, -1e20}}) ==
          "InvalidArgument: dist[4] (k3): -1e+20: the pixel (1, 0) off the principal point has no ray");
    // An image whose corner K's inverse cannot reach: (-0.5 - 1e300) / 1e-9 overflows.
    Camera far = camera;
    far.intrinsics = {1e-9, 500.0, 1e300, 239.5, 0.0};
    CHECK(error_of([&] { far.validate(); }) ==
          "InvalidArgument: K: the image's corner (-0.5, -0.5) has no finite direction (fx 1e-09, fy 500, cx 1e+300, cy 239.5, skew 0)");

    // Kept: a field of view of a millionth of a degree (fx = W / (2 tan(fov / 2))), a
    // strong real lens, a wide fisheye, UCM whose centre scales by 1 / (1 + xi).
    Camera narrow = camera;
    narrow.intrinsics.fx = narrow.intrinsics.fy = 640.0 / (2.0 * std::tan(1e-6 * std::numbers::pi / 360.0));
    CHECK_NOTHROW(narrow.validate());
    // And 179 degrees on a 3-pixel image, whose one pixel spans 89 degrees: the pinhole's
    // scale is its plane's, which K keeps linear.
    Camera wide;
    wide.size = {3, 2};
    wide.intrinsics = {3.0 / (2.0 * std::tan(89.5 * std::numbers::pi / 180.0)), 1.0, 1.0, 0.5, 0.0};
    CHECK_NOTHROW(wide.validate());
    for (const Lens& lens : {Lens{LensType::OpenCv8, {-0.4, 0.2, 0.001, -0.002, -0.05, 0.1, 0.05, 0.01}},
                             Lens{LensType::Fisheye, {0.1, -0.05, 0.01, -0.001}}, Lens{LensType::Ucm, {3.0}}}) {
        CAPTURE(lens_info(lens.type).name);
        Camera real = camera;
        real.lens = lens;
        CHECK_NOTHROW(real.validate());
    }
    CHECK_NOTHROW(wide_reference_camera().validate());
}
