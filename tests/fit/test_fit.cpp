// libcam::fit: scenes and their samples, the candidates, and the choice.
//
// Expected answers come from how each source camera is built (a camera made as a FOV
// camera is one; a lens whose distortion displaces no pixel of a region by more than a
// bound worked out by hand needs no distortion there) and from evaluations written
// here, through libcam's Camera, independent of the fit's own measurements.

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "lens_cases.hpp"
#include "blender_reference.hpp"
#include "libcam/convert/blender_camera.hpp"
#include "libcam/convert/look_at_convert.hpp"
#include "libcam/error.hpp"
#include "libcam/fit/fit.hpp"
#include "libcam/interop/mrcal.hpp"
#include "support.hpp"
#include "real_cameras.hpp"

using namespace libcam;
using libcam::test::real_cameras_folder;
using libcam::test::real_cameras_present;
using Catch::Matchers::Contains;

namespace {

Vec2 centre_of(const ImageSize& size) { return {size.centre_x(), size.centre_y()}; }

// 1600x1200, f = 1200, centred, mild barrel with a little decentring:
// k1 = -0.02, k2 = 0.004, p1 = 1e-4, p2 = -5e-5. Its corners are 39.8 deg off the axis.
Camera mildly_distorted() {
    Camera camera;
    camera.size = {1600, 1200};
    camera.intrinsics = {1200.0, 1200.0, camera.size.centre_x(), camera.size.centre_y(), 0.0};
    camera.lens = {LensType::OpenCv4, {-0.02, 0.004, 1e-4, -5e-5}};
    return camera;
}

const CandidateReport& chosen(const FitReport& report) {
    REQUIRE(report.chosen.has_value());
    return report.candidates[*report.chosen];
}

const CandidateReport& candidate(const FitReport& report, std::string_view name) {
    for (const CandidateReport& entry : report.candidates) {
        if (entry.fit.candidate.name == name) return entry;
    }
    FAIL("no candidate " << name);
    throw std::logic_error("unreachable");
}

// Which pixels the test regards as in the scene, written here from the scene's definition.
struct SceneTruth {
    enum { Whole, Circle, Rectangle, Angle } kind = Whole;
    Vec2 centre = Vec2::Zero();
    double radius = 0.0;
    Vec2 low = Vec2::Zero(), high = Vec2::Zero();
    double max_angle_rad = 0.0;

    bool contains(const Vec2& pixel, const Vec3& ray) const {
        switch (kind) {
            case Whole: return true;
            case Circle: return (pixel - centre).norm() <= radius;
            case Rectangle: return (pixel.array() >= low.array()).all() && (pixel.array() <= high.array()).all();
            case Angle: return std::atan2(ray.head<2>().norm(), ray.z()) <= max_angle_rad;
        }
        return false;
    }

    // A box around the scene, to spare the dense check the rest of the image.
    std::pair<Vec2, Vec2> box(const ImageSize& size) const {
        switch (kind) {
            case Circle: return {centre.array() - radius, centre.array() + radius};
            case Rectangle: return {low, high};
            default: return {Vec2::Zero(), Vec2(size.width - 1, size.height - 1)};
        }
    }
};

// The pixels of a lattice over the image `density` times denser than `lattice`, inside `box`.
std::vector<Vec2> dense_pixels(const ImageSize& size, const Lattice& lattice, int density, const std::pair<Vec2, Vec2>& box) {
    const double step_x = static_cast<double>(size.width - 1) / static_cast<double>((lattice.columns - 1) * density);
    const double step_y = static_cast<double>(size.height - 1) / static_cast<double>((lattice.rows - 1) * density);
    std::vector<Vec2> pixels;
    for (double y = std::ceil(box.first.y() / step_y) * step_y; y <= box.second.y(); y += step_y) {
        for (double x = std::ceil(box.first.x() / step_x) * step_x; x <= box.second.x(); x += step_x) pixels.emplace_back(x, y);
    }
    return pixels;
}

// The largest error of `fitted` (a world camera) against `source` over the scene's pixels
// on a lattice `density` times denser than the fit's, at each depth along the source's
// rays (far away when none). Every scene pixel with a ray must project through `fitted`.
double independent_max_error(const Camera& source, const Camera& fitted, const SceneTruth& truth,
                             const Lattice& fit_lattice, int density, const std::vector<double>& depths) {
    const std::vector<Vec2> pixels = dense_pixels(source.size, fit_lattice, density, truth.box(source.size));
    const std::vector<Unprojection> rays = PreparedCamera(source).unproject(pixels);
    std::vector<Vec3> points;  // in the fitted camera's frame
    std::vector<Vec2> expected;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        if (!rays[i].valid || !truth.contains(pixels[i], rays[i].direction)) continue;
        const Vec3 world_direction = source.pose.world_direction_from_camera(rays[i].direction.normalized());
        for (const double depth : depths.empty() ? std::vector<double>{1e9} : depths) {
            points.push_back(fitted.pose.camera_from_world(source.pose.centre() + depth * world_direction));
            expected.push_back(pixels[i]);
        }
    }
    REQUIRE(points.size() > 1000);
    const std::vector<Projection> projections = PreparedCamera(fitted).project_camera_points(points);
    double worst = 0.0;
    std::size_t invalid = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!projections[i].valid) ++invalid;
        else worst = std::max(worst, (projections[i].pixel - expected[i]).norm());
    }
    CHECK(invalid == 0);
    return worst;
}

}  // namespace

TEST_CASE("a camera made as a look-at camera is found to be one, with no error") {
    const LookAtCamera made = LookAtCamera::look_at({1, 2, 3}, {4, -1, 9}, {0, 1, 0}, 70.0, FovAxis::Horizontal, {1280, 720});
    const Camera source = to_camera(made);
    FitOptions options;
    options.tolerance_px = 0.01;
    const FitReport report = fit_scene(source, Scene::whole_image(), options);

    const CandidateReport& best = chosen(report);
    CHECK(best.fit.candidate.name == "LOOK_AT");
    CHECK(best.fit.candidate.num_params() == 1);
    CHECK(best.max_px < 1e-9);
    REQUIRE(best.fit.params.size() == 1);
    // f = (W/2) / tan(fov/2) for a horizontal fov.
    CHECK(best.fit.params[0] == Approx(640.0 / std::tan(35.0 * std::numbers::pi / 180.0)).epsilon(1e-12));
    const Camera world = camera_in_world(best.fit, source);
    CHECK(describe_fov(world).fov_deg.horizontal == Approx(70.0).epsilon(1e-12));
    CHECK((world.pose.R - source.pose.R).norm() < 1e-15);
    CHECK(world.pose.centre().isApprox(made.eye, 1e-12));
}

TEST_CASE("a mildly distorted lens needs OPENCV4 over the whole image but is a look-at camera in a small central region") {
    const Camera source = mildly_distorted();
    FitOptions options;
    options.tolerance_px = 0.05;

    // Whole image: the barrel moves the corners by ~12 px (1200 (k1 r^3 + k2 r^5) at
    // r = 0.83), which no focal length or principal point takes back; OPENCV4 is the lens.
    const FitReport whole = fit_scene(source, Scene::whole_image(), options);
    CHECK(chosen(whole).fit.candidate.name == "OPENCV4");
    CHECK_FALSE(candidate(whole, "LOOK_AT").pass);
    CHECK_FALSE(candidate(whole, "PINHOLE").pass);
    CHECK(candidate(whole, "PINHOLE").max_px > 1.0);

    // Within 40 px of the centre (r = 1/30) the distortion moves no pixel by more than
    // 1200 (0.02 r^3 + 3.5e-4 r^2) = 1.4e-3 px, far inside 0.05 px: the look-at camera serves.
    // (A least-squares fit may trade some of its largest error for a smaller RMS: 2x.)
    const FitReport centre = fit_scene(source, Scene::circle(40.0, centre_of(source.size)), options);
    CHECK(chosen(centre).fit.candidate.name == "LOOK_AT");
    CHECK(chosen(centre).max_px < 2 * 1.4e-3);
}

TEST_CASE("the chosen model is within the tolerance everywhere in the scene, by an independent denser check", "[sweep]") {
    struct Case {
        std::string name;
        Camera source;
        Scene scene;
        SceneTruth truth;
        double tolerance_px;
        CameraMotion motion;
        std::vector<double> depths;
    };
    const Camera wide = libcam::test::wide_reference_camera();
    const Camera mild = mildly_distorted();
    const double fifty_deg = 50.0 * std::numbers::pi / 180.0;
    const std::vector<Case> cases = {
        {"wide lens, r 1500", wide, Scene::circle(1500, centre_of(wide.size)),
         {SceneTruth::Circle, centre_of(wide.size), 1500}, 0.5, CameraMotion::None, {}},
        {"wide lens, off-centre circle, rotation and shift", wide, Scene::circle(900, {1500, 1200}),
         {SceneTruth::Circle, {1500, 1200}, 900}, 0.2, CameraMotion::RotationAndShift, {10.0, 1000.0}},
        {"wide lens, rectangle", wide, Scene::rectangle({3500, 500}, {5800, 3900}),
         {SceneTruth::Rectangle, {}, 0, {3500, 500}, {5800, 3900}}, 1.0, CameraMotion::None, {}},
        {"wide lens, 50 degrees, rotation", wide, Scene::field_angle(50.0),
         {SceneTruth::Angle, {}, 0, {}, {}, fifty_deg}, 0.5, CameraMotion::Rotation, {}},
        {"mild lens, whole image", mild, Scene::whole_image(), {}, 0.01, CameraMotion::None, {}},
    };
    for (const Case& c : cases) {
        INFO(c.name);
        FitOptions options;
        options.tolerance_px = c.tolerance_px;
        options.motion = c.motion;
        options.depths = c.depths;
        const FitReport report = fit_scene(c.source, c.scene, options);
        const CandidateReport& best = chosen(report);
        INFO("chosen " << best.fit.candidate.name << ", its own max " << best.max_px);
        const double worst = independent_max_error(c.source, camera_in_world(best.fit, c.source), c.truth,
                                                   report.sampling.fit_lattice, 6, c.depths);
        CHECK(worst <= c.tolerance_px);
    }
}

TEST_CASE("the fitted camera may rotate: an off-centre principal point is a rotated look-at camera") {
    // f = 2500 on a 1000x800 image (tan of the half width 0.2), principal point 2 px right
    // and 1.5 px up of the centre. Without motion a centred camera is off by ~2.5 px
    // everywhere; turned by ~(2, 1.5)/2500 rad, it is off by at most about
    // 2.5 tan^2 = 0.1 px at the edge.
    Camera source;
    source.size = {1000, 800};
    source.intrinsics = {2500.0, 2500.0, source.size.centre_x() + 2.0, source.size.centre_y() - 1.5, 0.0};
    FitOptions options;
    options.tolerance_px = 0.2;

    const FitReport still = fit_scene(source, Scene::whole_image(), options);
    CHECK(candidate(still, "LOOK_AT").max_px > 2.0);
    CHECK(chosen(still).fit.candidate.name == "PINHOLE");

    options.motion = CameraMotion::Rotation;
    const FitReport turned = fit_scene(source, Scene::whole_image(), options);
    CHECK(chosen(turned).fit.candidate.name == "LOOK_AT");
    const double angle = camera_in_world(chosen(turned).fit, source).pose.rvec().norm();
    CHECK(angle == Approx(std::hypot(2.0, 1.5) / 2500.0).epsilon(0.05));
}

TEST_CASE("a fisheye view past 90 degrees: perspective models cannot cover it, FISHEYE can") {
    // f = 420 on 1600x1200: the corners are ~2.4 rad (137 deg) off the axis.
    const Camera source = libcam::test::lens_camera(LensType::Fisheye, {-0.013, -0.0057, 0.0023, -0.0009}, {1600, 1200}, 420, 421);
    FitOptions options;
    options.tolerance_px = 0.01;
    const FitReport report = fit_scene(source, Scene::whole_image(), options);
    CHECK(report.largest_angle_deg > 90.0);
    for (const std::string_view name : {"LOOK_AT", "PINHOLE", "OPENCV4", "OPENCV5", "OPENCV8", "OPENCV12"}) {
        INFO(name);
        CHECK_FALSE(candidate(report, name).covers_scene);
        CHECK(std::isinf(candidate(report, name).max_px));
    }
    CHECK(candidate(report, "STEREOGRAPHIC").covers_scene);
    CHECK(chosen(report).fit.candidate.name == "FISHEYE");
}

TEST_CASE("candidates: simplest first, FISHEYE and STEREOGRAPHIC only for wide scenes") {
    const auto names = [](double angle) {
        std::vector<std::string> out;
        for (const Candidate& c : candidates_for(angle)) out.emplace_back(c.name);
        return out;
    };
    const std::vector<std::string> narrow = {"LOOK_AT", "PINHOLE", "OPENCV4", "OPENCV5", "OPENCV8", "OPENCV12"};
    CHECK(names(44.9) == narrow);
    std::vector<std::string> wide = narrow;
    wide.insert(wide.end(), {"FISHEYE", "STEREOGRAPHIC"});
    CHECK(names(45.0) == wide);
    const std::vector<int> counts = {1, 4, 8, 9, 12, 16, 8, 4};
    for (std::size_t i = 0; i < counts.size(); ++i) CHECK(candidates_for(60.0)[i].num_params() == counts[i]);
}

TEST_CASE("models on request: named ones only, the others refused with the list") {
    CHECK(candidate_named("LOOK_AT").look_at);
    // Its old name, taken for one more release.
    CHECK(candidate_named("FOV").look_at);
    const Candidate polynomial = candidate_named("FISHEYE_LENS_POLYNOMIAL");
    // cx cy and k1..k4: K's scale and k0 are held.
    CHECK(polynomial.num_params() == 6);
    CHECK(polynomial.sensor_width_mm == 36.0);
    CHECK(candidate_named("DOUBLE_SPHERE").num_params() == 6);
    for (const Candidate& c : candidates_for(180.0)) CHECK(c.name != "DOUBLE_SPHERE");
    CHECK_THROWS_WITH(candidate_named("LONLAT"), Contains("libcam fit cannot fit 'LONLAT'") && Contains("EUCM"));
    CHECK_THROWS_WITH(candidate_named("OPENCV"), Contains("unknown model 'OPENCV'"));
}

TEST_CASE("an equidistant fisheye is Blender's polynomial fisheye: theta = r / f, worked by hand") {
    // FISHEYE with zero coefficients images angle theta at theta f pixels from its axis.
    // Blender's polynomial at 1200 / 36 px per mm has r mm = r px / (1200 / 36), so
    // theta = -k1 r with k1 = -(1200 / 36) / f, and k2 = k3 = k4 = 0. (The fit starts from
    // the equidistant lens of the source's focal length, which is the answer here: this
    // checks the scale and k0 held and the solver staying put; the next test fits.)
    Camera source;
    source.size = {1200, 900};
    source.intrinsics = {380.0, 380.0, 601.3, 447.2, 0.0};
    source.lens = {LensType::Fisheye, {0.0, 0.0, 0.0, 0.0}};
    FitOptions options;
    options.tolerance_px = 1e-6;
    options.candidates = {candidate_named("FISHEYE_LENS_POLYNOMIAL")};
    const FitReport report = fit_scene(source, Scene::whole_image(), options);
    const CandidateReport& result = chosen(report);
    const Camera& fitted = result.fit.camera;
    CHECK(fitted.lens.type == LensType::LensPolynomial);
    CHECK(fitted.intrinsics.fx == Approx(1200.0 / 36).epsilon(1e-15));
    CHECK(fitted.intrinsics.fy == fitted.intrinsics.fx);
    CHECK(fitted.intrinsics.cx == Approx(601.3).epsilon(1e-10));
    CHECK(fitted.intrinsics.cy == Approx(447.2).epsilon(1e-10));
    const std::vector<double> expected = {0.0, -(1200.0 / 36) / 380.0, 0.0, 0.0, 0.0};
    for (std::size_t i = 0; i < 5; ++i) CHECK(fitted.lens.coefficients[i] == Approx(expected[i]).margin(1e-10));
    CHECK(result.max_px < 1e-6);
}

TEST_CASE("a fisheye becomes Blender's polynomial fisheye, checked by Cycles' formula and cv::fisheye") {
    // basalt's calibration of a RealSense T265's left fisheye (KB4, 848x800), up to 80
    // degrees off its axis (its image circle). Blender's four-term polynomial follows it
    // within 1.1 px there (a tolerance of 1.2 px). The fitted camera goes to Blender's
    // settings, Cycles' own mapping (blender_reference.hpp) gives each pixel's ray, and
    // cv::fisheye projects it through the source.
    Camera source;
    source.size = {848, 800};
    source.intrinsics = {286.60144163375528, 286.4617087423328, 422.2765876951761, 395.2246466040553, 0.0};
    source.lens = {LensType::Fisheye,
                   {-0.006762412326815424, 0.045170283325720008, -0.043515167278210638, 0.008374959821591333}};
    const double max_angle_deg = 80.0;
    FitOptions options;
    options.tolerance_px = 1.2;
    options.candidates = {candidate_named("FISHEYE_LENS_POLYNOMIAL")};
    const FitReport report = fit_scene(source, Scene::field_angle(max_angle_deg), options);
    const CandidateReport& result = chosen(report);
    const BlenderCamera blender = blender_from_camera(result.fit.camera);
    std::vector<Vec2> pixels;
    std::vector<Vec3> rays;
    for (const Vec2& pixel : test::pixel_grid(source.size, 151, 121)) {
        const std::optional<Eigen::Vector3d> ray = test::blender_ray(blender, pixel.x(), pixel.y());
        // Outside the scene, or past the polynomial's domain (black in Blender's render).
        if (!ray || std::atan2(ray->head<2>().norm(), ray->z()) > radians_from_degrees(max_angle_deg) - 0.01) continue;
        pixels.push_back(pixel);
        rays.push_back(*ray);
    }
    REQUIRE(pixels.size() > 10000);
    const std::vector<Vec2> through_source = test::reference_project(source, rays);
    double worst = 0.0;
    for (std::size_t i = 0; i < pixels.size(); ++i) worst = std::max(worst, (through_source[i] - pixels[i]).norm());
    WARN("FISHEYE_LENS_POLYNOMIAL within " << worst << " px over " << pixels.size() << " pixels (fit's own check: "
                                           << result.max_px << " px)");
    CHECK(worst <= options.tolerance_px);
}

TEST_CASE("the unified models on request: UCM is EUCM with beta = 1, worked by hand, and reaches past 90 degrees") {
    // UCM m = (x, y) / (z + xi |p|) = (x, y) / ((1 + xi) (alpha |p| + (1 - alpha) z)) with
    // alpha = xi / (1 + xi): EUCM with that alpha, beta = 1 and focal length f / (1 + xi).
    Camera source;
    source.size = {1000, 800};
    source.intrinsics = {300.0, 300.0, 505.0, 396.0, 0.0};
    source.lens = {LensType::Ucm, {0.8}};
    FitOptions options;
    options.tolerance_px = 1e-6;
    options.candidates = {candidate_named("EUCM")};
    const FitReport report = fit_scene(source, Scene::whole_image(), options);
    const CandidateReport& eucm = chosen(report);
    CHECK(eucm.fit.camera.intrinsics.fx == Approx(300.0 / 1.8).epsilon(1e-9));
    CHECK(eucm.fit.camera.intrinsics.cx == Approx(505.0).epsilon(1e-9));
    CHECK(eucm.fit.camera.lens.coefficients[0] == Approx(0.8 / 1.8).epsilon(1e-9));
    CHECK(eucm.fit.camera.lens.coefficients[1] == Approx(1.0).epsilon(1e-9));
    // The 137-degree fisheye: a pinhole start reaches none of it past 90 degrees, and the
    // fit widens until UCM and MEI cover it all.
    const Camera fisheye =
        libcam::test::lens_camera(LensType::Fisheye, {-0.013, -0.0057, 0.0023, -0.0009}, {1600, 1200}, 420, 421);
    options.tolerance_px = 5.0;
    options.candidates = {candidate_named("UCM"), candidate_named("MEI"), candidate_named("DOUBLE_SPHERE")};
    // A 20 x 15 fitting lattice (the check lattice 4x denser): coverage is the question
    // here, and the sanitizer build runs this fit too.
    options.lattice = Lattice{20, 15};
    const FitReport wide = fit_scene(fisheye, Scene::whole_image(), options);
    for (const CandidateReport& entry : wide.candidates) {
        INFO(entry.fit.candidate.name << ": max " << entry.max_px << " px");
        CHECK(entry.covers_scene);
    }
}

TEST_CASE("scene samples: the lattice inside the scene and its boundary, and a denser check set") {
    const Camera source = mildly_distorted();
    const Vec2 centre(700.0, 500.0);
    const double radius = 300.0;
    const Lattice lattice{33, 25};  // steps of 1599/32 and 1199/24 px
    const PreparedCamera prepared(source);
    const SceneSampling sampling = sample_scene(prepared, Scene::circle(radius, centre), lattice);

    const ScenePixels& fit = sampling.fit;
    REQUIRE(fit.boundary_count > 0);
    const double step_x = 1599.0 / 32, step_y = 1199.0 / 24;
    for (std::size_t i = 0; i < fit.pixels.size(); ++i) {
        const Vec2& p = fit.pixels[i];
        CHECK((p - centre).norm() <= radius * (1 + 1e-9));
        if (i < fit.boundary_count) {
            CHECK((p - centre).norm() == Approx(radius).epsilon(1e-12));
        } else {
            CHECK(std::abs(p.x() / step_x - std::round(p.x() / step_x)) < 1e-9);
            CHECK(std::abs(p.y() / step_y - std::round(p.y() / step_y)) < 1e-9);
        }
        const Unprojection expected = prepared.unproject(p);
        REQUIRE(expected.valid);
        CHECK(fit.directions[i].isApprox(expected.direction.normalized(), 1e-15));
    }
    // Lattice points inside the disc: about its area over a cell's.
    const double interior = static_cast<double>(fit.pixels.size() - fit.boundary_count);
    CHECK(interior == Approx(std::numbers::pi * radius * radius / (step_x * step_y)).epsilon(0.1));
    CHECK(sampling.check_lattice.columns == 32 * kCheckDensity + 1);
    CHECK(sampling.check.pixels.size() > 10 * fit.pixels.size());
    CHECK(sampling.check.boundary_count > 3 * fit.boundary_count);
}

TEST_CASE("a field-angle scene holds the pixels whose rays are within the angle, its edge at the angle") {
    const PreparedCamera source(libcam::test::wide_reference_camera());
    const SceneSampling sampling = sample_scene(source, Scene::field_angle(30.0));
    const ScenePixels& fit = sampling.fit;
    REQUIRE(fit.boundary_count > 16);
    for (std::size_t i = 0; i < fit.pixels.size(); ++i) {
        const Unprojection unprojection = source.unproject(fit.pixels[i]);
        REQUIRE(unprojection.valid);
        const Vec3& ray = unprojection.direction;
        const double angle_deg = std::atan2(ray.head<2>().norm(), ray.z()) * 180.0 / std::numbers::pi;
        CHECK(angle_deg <= 30.0 + 1e-7);
        if (i < fit.boundary_count) CHECK(angle_deg == Approx(30.0).epsilon(1e-9));
    }
}

TEST_CASE("bad scenes and options are refused with a clear message") {
    const Camera source = mildly_distorted();
    const auto fails = [&](const Scene& scene, const std::string& words, FitOptions options = {}) {
        INFO(words);
        CHECK_THROWS_WITH(fit_scene(source, scene, options), Contains(words));
    };
    fails(Scene::circle(0.0, centre_of(source.size)), "radius: must be > 0");
    fails(Scene::circle(-5.0, centre_of(source.size)), "radius: must be > 0");
    fails(Scene::circle(10.0, {2000.0, 10.0}), "outside the image's pixel centres [0, 1599] x [0, 1199]");
    fails(Scene::rectangle({100, 100}, {100, 300}), "empty");
    fails(Scene::rectangle({300, 100}, {200, 300}), "empty");
    fails(Scene::rectangle({100, 100}, {1700, 300}), "outside the image");
    fails(Scene::rectangle({-1, 100}, {300, 300}), "outside the image");
    fails(Scene::field_angle(0.0), "max angle: must be in (0, 180)");
    fails(Scene::field_angle(180.0), "max angle: must be in (0, 180)");
    fails(Scene::circle(std::nan(""), centre_of(source.size)), "radius: must be finite");

    FitOptions options;
    options.tolerance_px = 0.0;
    fails(Scene::whole_image(), "tolerance: must be > 0", options);
    options.tolerance_px = -1.0;
    fails(Scene::whole_image(), "tolerance: must be > 0", options);
    options.tolerance_px = 1.0;
    options.depths = {-1.0, 10.0};
    fails(Scene::whole_image(), "depth: must be > 0", options);
    options.depths = {};
    options.motion = CameraMotion::RotationAndShift;
    fails(Scene::whole_image(), "needs points at finite depths", options);
}

TEST_CASE("a scene with no pixel that has a ray is refused") {
    // OPENCV4 k1 = -0.5 folds at r = sqrt(2/3) (distorted radius 0.5443, 272 px at f = 500):
    // a rectangle in the corner of the 1000x750 image, 400+ px from the centre, has no rays.
    Camera source;
    source.size = {1000, 750};
    source.intrinsics = {500.0, 500.0, 499.5, 374.5, 0.0};
    source.lens = {LensType::OpenCv4, {-0.5, 0.0, 0.0, 0.0}};
    CHECK_THROWS_WITH(fit_scene(source, Scene::rectangle({900, 650}, {999, 749}), {}), Contains("no pixel of it has a ray"));
    // The whole image: the corners are skipped and counted; the middle is fitted.
    FitOptions options;
    options.tolerance_px = 1e-6;
    const FitReport report = fit_scene(source, Scene::whole_image(), options);
    CHECK(report.sampling.check.skipped > 0);
    CHECK(report.sampling.fit.skipped > 0);
    CHECK(chosen(report).fit.candidate.name == "OPENCV4");
}

namespace {

// The source camera's rays through a dense grid (151 x 121 pixels), those within
// max_angle of its optical axis: what the [real] fits below are checked on.
struct GridRays {
    std::vector<Vec2> pixels;
    std::vector<Vec3> rays;
};

GridRays grid_rays(const Camera& source, double max_angle = std::numbers::pi) {
    const std::vector<Vec2> pixels = test::pixel_grid(source.size, 151, 121);
    const std::vector<Unprojection> rays = PreparedCamera(source).unproject(pixels);
    GridRays out;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        if (!rays[i].valid || std::atan2(rays[i].direction.head<2>().norm(), rays[i].direction.z()) > max_angle) continue;
        out.pixels.push_back(pixels[i]);
        out.rays.push_back(rays[i].direction);
    }
    return out;
}

// The farthest OpenCV (or the table's reference library) puts the rays, seen from the
// fitted camera, from their source pixels.
double worst_through_reference(const Camera& fitted, const GridRays& grid) {
    std::vector<Vec3> directions;
    for (const Vec3& ray : grid.rays) directions.push_back(fitted.pose.camera_from_world(ray));
    const std::vector<Vec2> projected = test::reference_project(fitted, directions);
    double worst = 0.0;
    for (std::size_t i = 0; i < directions.size(); ++i) worst = std::max(worst, (projected[i] - grid.pixels[i]).norm());
    return worst;
}

}  // namespace

// basalt's calibrations of the EuRoC and TUM-VI cameras (Double Sphere and EUCM), read
// here from basalt's JSON by hand (fx fy cx cy and the model's two parameters).
namespace {

Camera basalt_camera(const std::filesystem::path& file) {
    std::ifstream in(file);
    const nlohmann::json calibration = nlohmann::json::parse(in).at("value0");
    const nlohmann::json& first = calibration.at("intrinsics").at(0);
    const nlohmann::json& k = first.at("intrinsics");
    Camera camera;
    camera.size = {calibration.at("resolution").at(0).at(0).get<int>(), calibration.at("resolution").at(0).at(1).get<int>()};
    camera.intrinsics = {k.at("fx").get<double>(), k.at("fy").get<double>(), k.at("cx").get<double>(), k.at("cy").get<double>(), 0.0};
    const std::string type = first.at("camera_type").get<std::string>();
    REQUIRE((type == "ds" || type == "eucm"));
    camera.lens = type == "ds" ? Lens{LensType::DoubleSphere, {k.at("xi").get<double>(), k.at("alpha").get<double>()}}
                               : Lens{LensType::Eucm, {k.at("alpha").get<double>(), k.at("beta").get<double>()}};
    return camera;
}

}  // namespace

TEST_CASE("basalt's Double Sphere and EUCM calibrations become a FISHEYE within 0.1 px, checked by the papers' formulas "
          "and cv::fisheye",
          "[sweep][real]") {
    const std::filesystem::path folder = real_cameras_folder("basalt");
    if (!real_cameras_present(folder)) return;
    for (const char* name : {"euroc_ds_calib.json", "euroc_eucm_calib.json", "tumvi_512_ds_calib.json", "tumvi_512_eucm_calib.json"}) {
        INFO(name);
        const Camera source = basalt_camera(folder / name);
        FitOptions options;
        options.tolerance_px = 0.1;
        const FitReport report = fit_scene(source, Scene::whole_image(), options);
        const CandidateReport& result = chosen(report);
        CHECK(result.fit.candidate.name == "FISHEYE");
        // Independently: rays through a dense grid whose pixel the paper's formula for the
        // source gives back (to 1e-9 px), projected by cv::fisheye through the fitted camera.
        const GridRays grid = grid_rays(source);
        for (std::size_t i = 0; i < grid.rays.size(); ++i) {
            const std::optional<Vec2> paper = test::paper_pixel(source, grid.rays[i]);
            REQUIRE(paper.has_value());
            REQUIRE((*paper - grid.pixels[i]).norm() < 1e-9);
        }
        REQUIRE(grid.rays.size() > 151 * 121 * 9 / 10);
        const double worst = worst_through_reference(result.fit.camera, grid);
        WARN(name << ": " << report.candidates.size() << " candidates, FISHEYE within " << worst << " px over " << grid.rays.size()
                  << " pixels (fit's own check: " << result.max_px << " px)");
        CHECK(worst <= 0.1);
    }
}

// mrcal's splined calibrations: cam0's 4000x2200 camera (a spline mrcal fitted to its
// OPENCV8 calibration) and the 170-degree 6016x4016 lens calibrated as a 30 x 20 spline.
// A spline follows a real lens (and its calibration's noise) more closely than any
// OpenCV or FISHEYE model can: no candidate is within 0.1 px over either image (cam0's
// spline departs from any model by 0.3 px in its knot pattern; the 170-degree lens by
// 0.6 px within 30 degrees of its axis). So the scenes and tolerances here are ones a
// model meets. The spline also turns the image a little about its axis (it projects the
// axis 66 px from its principal point on the 170-degree lens), so the fitted camera may
// rotate, as mrcal-convert-lensmodel's fit does.
TEST_CASE("mrcal's splined calibrations become an OpenCV model, checked by mrcal_project and OpenCV", "[sweep][real]") {
    const std::filesystem::path folder = real_cameras_folder("mrcal");
    if (!real_cameras_present(folder)) return;
    struct SplinedCase {
        const char* file;
        Scene scene;
        double max_angle_deg;  // the scene's (180: the whole image)
        double tolerance_px;
    };
    for (const SplinedCase& c : {SplinedCase{"cam0.splined.cameramodel", Scene::whole_image(), 180, 0.5},
                                 SplinedCase{"splined-0.cameramodel", Scene::field_angle(30), 30, 1.0}}) {
        const char* name = c.file;
        INFO(name);
        std::ifstream in(folder / name);
        std::stringstream text;
        text << in.rdbuf();
        const Camera source = parse_cameramodel(text.str(), name);
        FitOptions options;
        options.tolerance_px = c.tolerance_px;
        options.motion = CameraMotion::Rotation;
        const FitReport report = fit_scene(source, c.scene, options);
        const CandidateReport& result = chosen(report);
        CHECK(lens_info(result.fit.camera.lens.type).opencv == OpenCvFunction::ProjectPoints);
        // Independently: rays through a dense grid that mrcal_project puts back on their
        // pixels (to 1e-9 px), projected by OpenCV through the fitted camera, in the scene.
        const GridRays grid = grid_rays(source, radians_from_degrees(c.max_angle_deg));
        REQUIRE(grid.rays.size() > 1000);
        const std::vector<Vec2> through_mrcal = mrcal_project_points(source, grid.rays);
        for (std::size_t i = 0; i < grid.rays.size(); ++i) REQUIRE((through_mrcal[i] - grid.pixels[i]).norm() < 1e-9);
        const double worst = worst_through_reference(result.fit.camera, grid);
        WARN(name << ": " << result.fit.candidate.name << " within " << worst << " px over " << grid.rays.size()
                  << " grid pixels of the scene (fit's own check: " << result.max_px << " px, tolerance "
                  << c.tolerance_px << " px)");
        CHECK(worst <= c.tolerance_px);
    }
}
