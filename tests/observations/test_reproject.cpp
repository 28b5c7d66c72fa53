// reproject/reproject.hpp on observation sets made by hand: a pinhole camera whose pixels are
// worked out from x = fx X / Z + cx, so every expected residual is known without libcam.

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"

namespace {

using namespace libcam;

// A 640x480 pinhole (fx 500, fy 400, centre (320, 240)) at the world origin, looking down +Z.
Camera pinhole_camera() {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {500.0, 400.0, 320.0, 240.0, 0.0};
    camera.lens = {LensType::Pinhole, {}};
    return camera;
}

Vec2 pinhole_pixel(const Vec3& p) { return {500.0 * p.x() / p.z() + 320.0, 400.0 * p.y() / p.z() + 240.0}; }

// One view, four points, each observed at its true pixel plus a known offset.
ObservationSet four_points(const std::vector<Vec2>& offsets) {
    ObservationSet set;
    set.source = "hand-made";
    set.cameras.push_back({"cam", pinhole_camera()});
    set.views.push_back({"view 0", 0, Pose{}});
    set.points = {{0.0, 0.0, 2.0}, {0.4, 0.2, 2.0}, {-0.5, 0.3, 4.0}, {0.1, -0.6, 3.0}};
    set.point_ids = {10, 11, 12, 13};
    for (int i = 0; i < 4; ++i) {
        const Vec2 truth = pinhole_pixel(set.points[static_cast<std::size_t>(i)]);
        set.observations.push_back({0, i, truth + offsets[static_cast<std::size_t>(i)]});
    }
    return set;
}

}  // namespace

TEST_CASE("reproject: residuals, RMS, mean, bias and the stored numbers, worked by hand") {
    // Offsets (3, 4), (0, 0), (-1, 0), (0, 2): the residual is minus the offset.
    // |d| = 5, 0, 1, 2; RMS = sqrt((25 + 0 + 1 + 4) / 4) = sqrt(7.5); mean 2;
    // bias = -((3 + 0 - 1 + 0) / 4, (4 + 0 + 0 + 2) / 4) = (-0.5, -1.5).
    ObservationSet set = four_points({{3.0, 4.0}, {0.0, 0.0}, {-1.0, 0.0}, {0.0, 2.0}});
    set.reported.push_back({"avg_reprojection_error", std::sqrt(7.5), ReportedMeasure::RmsOverObservations});
    set.reported.push_back({"mean_point_error_px", 2.0, ReportedMeasure::MeanOfPointMeans});
    set.reported_per_view = {std::sqrt(7.5) + 1e-3};
    set.reported_per_point = {5.0, 0.0, 1.0, 2.5};
    const Reprojection r = reproject(set);
    REQUIRE(r.residuals.size() == 4);
    CHECK(r.residuals[0].residual.x() == Approx(-3.0).margin(1e-12));
    CHECK(r.residuals[0].residual.y() == Approx(-4.0).margin(1e-12));
    CHECK(r.residuals[0].error_px == Approx(5.0).margin(1e-12));
    const ResidualStats& all = r.summary.all;
    CHECK(all.stats.count == 4);
    CHECK(all.stats.rms_px == Approx(std::sqrt(7.5)).epsilon(1e-12));
    CHECK(all.mean_px == Approx(2.0).epsilon(1e-12));
    CHECK(all.stats.max_px == Approx(5.0).epsilon(1e-12));
    CHECK(all.stats.median_px == Approx(1.0).epsilon(1e-12));  // nearest rank: 2nd of 0, 1, 2, 5
    CHECK(all.bias.x() == Approx(-0.5).epsilon(1e-12));
    CHECK(all.bias.y() == Approx(-1.5).epsilon(1e-12));
    CHECK_FALSE(all.weighted_rms_px.has_value());
    REQUIRE(r.summary.reported.size() == 2);
    CHECK(r.summary.reported[0].recomputed == Approx(std::sqrt(7.5)).epsilon(1e-12));
    CHECK(r.summary.reported[1].recomputed == Approx(2.0).epsilon(1e-12));
    REQUIRE(r.summary.per_view_reported);
    CHECK(r.summary.per_view_reported->max_abs_difference == Approx(1e-3).epsilon(1e-6));
    REQUIRE(r.summary.per_point_reported);
    CHECK(r.summary.per_point_reported->compared == 4);
    CHECK(r.summary.per_point_reported->max_abs_difference == Approx(0.5).epsilon(1e-9));
    CHECK(r.summary.per_point_reported->worst_item == "13");
    const std::vector<std::size_t> worst = worst_observations(r.residuals, 2);
    REQUIRE(worst.size() == 2);
    CHECK(worst[0] == 0);
    CHECK(worst[1] == 3);
}

TEST_CASE("reproject: weights, outliers, points behind the camera and pixels off the image are counted apart") {
    ObservationSet set = four_points({{3.0, 4.0}, {0.0, 0.0}, {-1.0, 0.0}, {0.0, 2.0}});
    set.observations[1].inlier = false;            // an outlier: not counted
    set.observations[2].weight = 0.5;              // |w d| = 0.5
    set.observations[3].weight = 2.0;              // |w d| = 4
    set.points.push_back({0.0, 0.0, -1.0});        // behind the camera
    set.point_ids.push_back(14);
    set.observations.push_back({0, 4, {320.0, 240.0}});
    set.points.push_back({0.0, 0.0, 1.0});         // projects, but its observed pixel is off the image
    set.point_ids.push_back(15);
    set.observations.push_back({0, 5, {700.0, 240.0}});
    const Reprojection r = reproject(set);
    CHECK(r.summary.outliers == 1);
    CHECK(r.summary.behind_camera == 1);
    CHECK(r.summary.outside_image == 1);
    CHECK(r.summary.outside_domain == 0);
    CHECK(r.residuals[4].status == ResidualStatus::BehindCamera);
    CHECK(std::isinf(r.residuals[4].error_px));
    // Counted: |d| = 5, 1, 2 with weights 1, 0.5, 2.
    CHECK(r.summary.all.stats.count == 3);
    CHECK(r.summary.all.stats.rms_px == Approx(std::sqrt(30.0 / 3.0)).epsilon(1e-12));
    REQUIRE(r.summary.all.weighted_rms_px.has_value());
    CHECK(*r.summary.all.weighted_rms_px == Approx(std::sqrt((25.0 + 0.25 + 16.0) / 3.0)).epsilon(1e-12));
}

TEST_CASE("reproject: the half-pixel check finds a model written in the other convention, and stays quiet on a right one") {
    // 400 points seen by two views with noise of 0.3 px per axis; then the same with every
    // observation half a pixel further on both axes, as a file that says its pixels'
    // centres are at (0.5, 0.5) but holds OpenCV's pixels shifted the wrong way would.
    std::mt19937 random(7);
    std::normal_distribution<double> noise(0.0, 0.3);
    std::uniform_real_distribution<double> spread(-1.0, 1.0);
    ObservationSet right;
    right.source = "hand-made";
    right.cameras.push_back({"cam", pinhole_camera()});
    right.views.push_back({"a", 0, Pose{}});
    right.views.push_back({"b", 0, Pose::from_rvec(Vec3(0.0, 0.1, 0.0), Vec3(-0.2, 0.0, 0.1))});
    for (int i = 0; i < 400; ++i) {
        right.points.push_back({spread(random), 0.7 * spread(random), 4.0 + spread(random)});
        right.point_ids.push_back(i);
        for (int v = 0; v < 2; ++v) {
            const Vec3 in_camera = right.views[static_cast<std::size_t>(v)].pose.camera_from_world(right.points.back());
            right.observations.push_back({v, i, pinhole_pixel(in_camera) + Vec2(noise(random), noise(random))});
        }
    }
    const Reprojection quiet = reproject(right);
    CHECK_FALSE(quiet.summary.convention.suspect);
    CHECK(quiet.summary.convention.best_shift_px.norm() < 0.05);

    ObservationSet shifted = right;
    for (Observation& o : shifted.observations) o.pixel += Vec2(0.5, 0.5);
    const Reprojection found = reproject(shifted);
    CHECK(found.summary.convention.suspect);
    CHECK(found.summary.convention.best_shift_px.x() == Approx(0.5).margin(0.05));
    CHECK(found.summary.convention.best_shift_px.y() == Approx(0.5).margin(0.05));
    CHECK(found.summary.convention.rms_half_shift_px == Approx(quiet.summary.all.stats.rms_px).epsilon(1e-9));

    // The other way (a file that should have added half a pixel and did not): (-0.5, -0.5).
    for (Observation& o : shifted.observations) o.pixel -= Vec2(1.0, 1.0);
    const Reprojection other = reproject(shifted);
    CHECK(other.summary.convention.suspect);
    CHECK(other.summary.convention.best_shift_px.x() == Approx(-0.5).margin(0.05));
}

TEST_CASE("reproject: the same residuals with any number of threads") {
    ObservationSet set = four_points({{3.0, 4.0}, {0.0, 0.0}, {-1.0, 0.0}, {0.0, 2.0}});
    for (int copy = 0; copy < 5000; ++copy) set.observations.push_back(set.observations[static_cast<std::size_t>(copy % 4)]);
    const Reprojection one = reproject(set, 1);
    const Reprojection two = reproject(set, 2);
    REQUIRE(one.residuals.size() == two.residuals.size());
    for (std::size_t i = 0; i < one.residuals.size(); ++i) REQUIRE(one.residuals[i].error_px == two.residuals[i].error_px);
    CHECK(one.summary.all.stats.rms_px == two.summary.all.stats.rms_px);
}

TEST_CASE("check_observations refuses an index out of range, naming the observation") {
    ObservationSet set = four_points({{0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}});
    set.observations[2].point = 9;
    try {
        check_observations(set);
        FAIL("no error");
    } catch (const FileError& error) {
        CHECK(std::string(error.what()) == "hand-made: observation 2: point index 9 out of range");
    }
}
