// fit/observation_fit.hpp on board corners made through a known lens with known noise:
// the choice is that lens's model, its held-out RMS near the noise's, its intrinsics
// within the noise's reach. The corners are projected by OpenCV's formula written out
// here, not by libcam.

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "libcam/fit/observation_fit.hpp"

namespace {

using namespace libcam;

// OpenCV's k1 k2 p1 p2 model, by its documented formula.
Vec2 opencv4_pixel(const Vec3& p, double fx, double fy, double cx, double cy, const std::array<double, 4>& d) {
    const double x = p.x() / p.z(), y = p.y() / p.z();
    const double r2 = x * x + y * y;
    const double radial = 1.0 + d[0] * r2 + d[1] * r2 * r2;
    const double xd = x * radial + 2.0 * d[2] * x * y + d[3] * (r2 + 2.0 * x * x);
    const double yd = y * radial + d[2] * (r2 + 2.0 * y * y) + 2.0 * d[3] * x * y;
    return {fx * xd + cx, fy * yd + cy};
}

constexpr double kFx = 610.0, kFy = 605.0, kCx = 322.0, kCy = 236.0;
constexpr std::array<double, 4> kDistortion = {-0.28, 0.09, 0.0012, -0.0008};
constexpr double kNoisePx = 0.2;  // per axis

// 14 views of a 10x7 board (corners 25 mm apart), turned and placed to cover a 640x480
// image, each corner seen with Gaussian noise.
std::vector<FitView> board_views(unsigned seed) {
    std::mt19937 random(seed);
    std::normal_distribution<double> noise(0.0, kNoisePx);
    std::uniform_real_distribution<double> tilt(-0.45, 0.45);
    std::uniform_real_distribution<double> place(-0.12, 0.12);
    std::uniform_real_distribution<double> depth(0.35, 0.6);
    std::vector<FitView> views;
    while (views.size() < 14) {
        const Pose pose = Pose::from_rvec(Vec3(tilt(random), tilt(random), 0.3 * tilt(random)),
                                          Vec3(place(random) - 0.11, place(random) - 0.075, depth(random)));
        FitView view;
        view.name = "view " + std::to_string(views.size());
        view.pose = pose;
        bool inside = true;
        for (int i = 0; i < 7 && inside; ++i) {
            for (int j = 0; j < 10; ++j) {
                const Vec3 corner(0.025 * j, 0.025 * i, 0.0);
                const Vec2 pixel = opencv4_pixel(pose.camera_from_world(corner), kFx, kFy, kCx, kCy, kDistortion);
                if (pixel.x() < 0 || pixel.y() < 0 || pixel.x() > 639 || pixel.y() > 479) {
                    inside = false;
                    break;
                }
                view.observations.push_back({corner, pixel + Vec2(noise(random), noise(random))});
            }
        }
        if (inside) views.push_back(std::move(view));
    }
    return views;
}

}  // namespace

TEST_CASE("fit --observations chooses the lens that made the corners, its held-out RMS near the noise") {
    const std::vector<FitView> views = board_views(11);
    // The fit starts where a tool would leave it: a pinhole near the truth.
    Camera start;
    start.size = {640, 480};
    start.intrinsics = {600.0, 600.0, 319.5, 239.5, 0.0};
    start.lens = {LensType::Pinhole, {}};
    ObservationFitOptions options;
    options.candidates = {candidate_named("PINHOLE"), candidate_named("OPENCV4"), candidate_named("OPENCV5"),
                          candidate_named("OPENCV8")};
    options.folds = 7;
    const ObservationFitReport report = fit_observations(start, views, options);
    REQUIRE(report.candidates.size() == 4);
    for (const ObservationCandidate& c : report.candidates) {
        INFO(c.candidate.name << ": " << c.failure);
        REQUIRE(c.fitted);
    }
    for (const ObservationCandidate& c : report.candidates) {
        UNSCOPED_INFO(c.candidate.name << ": rms " << c.rms_px << ", held out " << c.heldout_rms_px << ", flags "
                                       << c.flags.size());
    }
    REQUIRE(report.chosen);
    const ObservationCandidate& chosen = report.candidates[*report.chosen];
    CHECK(chosen.candidate.name == "OPENCV4");
    // Gaussian noise of 0.2 px per axis: |d| has RMS 0.2 sqrt(2) = 0.283 px. Held out, a
    // little more (the pose and intrinsics carry their own error); the pinhole far more.
    const double noise_rms = kNoisePx * std::sqrt(2.0);
    CHECK(chosen.rms_px == Approx(noise_rms).epsilon(0.1));
    CHECK(chosen.heldout_rms_px > chosen.rms_px);
    CHECK(chosen.heldout_rms_px < 1.15 * noise_rms);
    CHECK(report.candidates[0].heldout_rms_px > 3.0 * noise_rms);
    // The intrinsics within the noise's reach: a fraction of a pixel for K, a few hundredths
    // for the distortion.
    CHECK(chosen.camera.intrinsics.fx == Approx(kFx).margin(1.5));
    CHECK(chosen.camera.intrinsics.fy == Approx(kFy).margin(1.5));
    CHECK(chosen.camera.intrinsics.cx == Approx(kCx).margin(1.0));
    CHECK(chosen.camera.intrinsics.cy == Approx(kCy).margin(1.0));
    REQUIRE(chosen.camera.lens.coefficients.size() == 4);
    CHECK(chosen.camera.lens.coefficients[0] == Approx(kDistortion[0]).margin(0.01));
    CHECK(chosen.camera.lens.coefficients[1] == Approx(kDistortion[1]).margin(0.03));
    CHECK(chosen.camera.lens.coefficients[2] == Approx(kDistortion[2]).margin(5e-4));
    CHECK(chosen.camera.lens.coefficients[3] == Approx(kDistortion[3]).margin(5e-4));
    // A richer model fits the training views at least as well, and is not chosen.
    CHECK(report.candidates[3].rms_px <= chosen.rms_px + 1e-9);
    CHECK(!report.reason.empty());
}

TEST_CASE("fit --observations needs two views") {
    std::vector<FitView> one = board_views(3);
    one.resize(1);
    Camera start;
    start.size = {640, 480};
    start.intrinsics = {600.0, 600.0, 319.5, 239.5, 0.0};
    CHECK_THROWS_WITH(fit_observations(start, one, {}), Catch::Contains("at least two"));
}

TEST_CASE("fit --observations holds out repeated views together, and refuses one pose repeated") {
    std::vector<FitView> views = board_views(5);
    Camera start;
    start.size = {640, 480};
    start.intrinsics = {600.0, 600.0, 319.5, 239.5, 0.0};
    ObservationFitOptions options;
    options.candidates = {candidate_named("OPENCV4")};
    options.folds = 4;
    // Three views taken again with the board left still: the same corners within a pixel.
    for (const std::size_t copy : {2u, 7u, 9u}) {
        FitView again = views[copy];
        for (FitSample& o : again.observations) o.pixel += Vec2(0.4, -0.3);
        views.push_back(again);
    }
    const ObservationFitReport report = fit_observations(start, views, options);
    CHECK(report.repeated_views == 3);
    REQUIRE(report.candidates.front().fitted);
    CHECK(report.candidates.front().heldout_rms_px < 1.2 * kNoisePx * std::sqrt(2.0));

    std::vector<FitView> still(6, views.front());
    CHECK_THROWS_WITH(fit_observations(start, still, options), Catch::Contains("one pose repeated"));
}
