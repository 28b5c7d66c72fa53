// The projection uncertainty (libcam/uncertainty/) against its two independent sources:
// mrcal's own projection_uncertainty (python3-mrcal, run by mrcal_uncertainty.py beside
// this file) on a real mrcal solve and on a small solve mrcal makes itself; and the truth,
// the spread of many re-calibrations of a synthetic set with fresh noise.

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/fit/least_squares.hpp"
#include "libcam/geometry/pixel_grid.hpp"
#include "libcam/io/observations.hpp"
#include "libcam/uncertainty/uncertainty_map.hpp"
#include "real_cameras.hpp"
#include "temp_dir.hpp"
#include "shell_output.hpp"

namespace {

using libcam::test::shell_output;

using namespace libcam;
namespace fs = std::filesystem;

const fs::path kScript = fs::path(LIBCAM_DOCS_DIR).parent_path() / "tests/uncertainty/mrcal_uncertainty.py";

// mrcal's sigma (and its noise) at each pixel, the point at `distance` ("inf": at infinity).
nlohmann::json mrcal_sigma(const fs::path& model, const std::string& distance, const std::vector<Vec2>& pixels) {
    std::string command = "/usr/bin/python3 '" + kScript.string() + "' sigma '" + model.string() + "' " + distance;
    for (const Vec2& p : pixels) command += " " + std::to_string(p.x()) + "," + std::to_string(p.y());
    return nlohmann::json::parse(shell_output(command));
}

// The image's centre, its four corners and the middles of its four edges.
std::vector<Vec2> centre_corners_edges(const ImageSize& size) {
    const double w = static_cast<double>(size.width - 1), h = static_cast<double>(size.height - 1);
    return {{w / 2, h / 2}, {0, 0}, {w, 0}, {0, h}, {w, h}, {w / 2, 0}, {w / 2, h}, {0, h / 2}, {w, h / 2}};
}

// libcam's sigma against mrcal's at the centre, corners and edges: returns the largest
// ratio's distance from 1.
double compare_with_mrcal(const fs::path& model, const std::string& distance_text, double distance) {
    const ObservationSet set = read_observations(model);
    const SolvedCalibration solved = solved_calibration(set, std::max(set.own_camera, 0));
    const ProjectionUncertainty uncertainty(solved);
    const std::vector<Vec2> pixels = centre_corners_edges(solved.camera.size);
    const nlohmann::json mrcal = mrcal_sigma(model, distance_text, pixels);
    // The same residuals, the same spread.
    CHECK(uncertainty.observed_pixel_uncertainty_px() == Approx(mrcal["noise_px"].get<double>()).epsilon(1e-6));
    const std::vector<double> sigma = uncertainty.sigma_px(pixels, distance);
    double worst = 0.0;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        const double expected = mrcal["sigma_px"][i].get<double>();
        INFO("pixel (" << pixels[i].x() << ", " << pixels[i].y() << "): libcam " << sigma[i] << " px, mrcal "
                       << expected << " px");
        CHECK(std::abs(sigma[i] / expected - 1.0) < 0.10);
        worst = std::max(worst, std::abs(sigma[i] / expected - 1.0));
    }
    return worst;
}

}  // namespace

TEST_CASE("uncertainty against mrcal: the real OPENCV8 solve in opencv8-0.cameramodel", "[uncertainty][mrcal]") {
    const fs::path folder = test::real_cameras_folder("mrcal");
    if (!test::real_cameras_present(folder)) return;
    const fs::path model = folder / "opencv8-0.cameramodel";
    if (!fs::exists(model)) {
        WARN("skipped: " << model.string() << " is absent");
        return;
    }
    // mrcal freed the board's bow (calobject_warp) in this solve, and libcam frees it too;
    // mrcal also adds its regularization, which libcam has none of: 1.6e-4 at most here, at
    // the centre, the corners and the edges (with the bow held, libcam's sigma was 1 to 3.5%
    // under mrcal's). 10% is allowed.
    REQUIRE(read_observations(model).board->warp_solved);
    const double at_infinity = compare_with_mrcal(model, "inf", kAtInfinity);
    const double at_ten = compare_with_mrcal(model, "10", 10.0);
    CHECK(at_infinity < 1e-3);
    CHECK(at_ten < 1e-3);
    WARN("opencv8-0: libcam's sigma within " << 100.0 * at_infinity << "% of mrcal's at infinity, "
                                             << 100.0 * at_ten << "% at 10 m");
}

TEST_CASE("uncertainty against mrcal: a small OPENCV4 solve made by mrcal.optimize", "[uncertainty][mrcal]") {
    const test::TempDir folder;
    const fs::path model = folder.path() / "small.cameramodel";
    shell_output("/usr/bin/python3 '" + kScript.string() + "' write '" + model.string() + "'");
    // The same problem in both: the board flat, no regularization, no outlier rejection. Only
    // the solver's last digits differ, so the agreement must be far inside the 10% allowed.
    const double at_infinity = compare_with_mrcal(model, "inf", kAtInfinity);
    const double near = compare_with_mrcal(model, "0.5", 0.5);
    CHECK(at_infinity < 0.01);
    CHECK(near < 0.01);
    WARN("mrcal's small solve: libcam's sigma within " << 100.0 * at_infinity << "% of mrcal's at infinity, "
                                                      << 100.0 * near << "% at 0.5 m");
}

TEST_CASE("uncertainty against mrcal: a solve of a bowed board, its bow solved for beside the rest",
          "[uncertainty][mrcal]") {
    const test::TempDir folder;
    const fs::path model = folder.path() / "bowed.cameramodel";
    shell_output("/usr/bin/python3 '" + kScript.string() + "' write-bowed '" + model.string() + "'");
    const ObservationSet set = read_observations(model);
    REQUIRE(set.board->warp_solved);
    // The bow's freedom counted as mrcal counts it: the same to the solver's last digits.
    const double at_infinity = compare_with_mrcal(model, "inf", kAtInfinity);
    const double near = compare_with_mrcal(model, "0.5", 0.5);
    CHECK(at_infinity < 1e-6);
    CHECK(near < 1e-6);
    // Held, the bow's freedom is missed: sigma comes out under mrcal's where it counts.
    SolvedCalibration held = solved_calibration(set, 0);
    REQUIRE(held.bow);
    const std::vector<Vec2> pixels = centre_corners_edges(held.camera.size);
    const std::vector<double> free_sigma = ProjectionUncertainty(held).sigma_px(pixels);
    held.bow.reset();
    const std::vector<double> held_sigma = ProjectionUncertainty(held).sigma_px(pixels);
    double largest_gap = 0.0;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        CHECK(held_sigma[i] <= free_sigma[i] * (1.0 + 1e-9));
        largest_gap = std::max(largest_gap, 1.0 - held_sigma[i] / free_sigma[i]);
    }
    CHECK(largest_gap > 0.01);
    WARN("a bowed board's solve: libcam's sigma within " << 100.0 * at_infinity << "% of mrcal's at infinity, "
                                                        << 100.0 * near << "% at 0.5 m; with the bow held, up to "
                                                        << 100.0 * largest_gap << "% under");
}

TEST_CASE("uncertainty against mrcal: a solve of two cameras sharing the boards' poses, each camera's model",
          "[uncertainty][mrcal]") {
    const test::TempDir folder;
    const fs::path models[2] = {folder.path() / "rig-0.cameramodel", folder.path() / "rig-1.cameramodel"};
    shell_output("/usr/bin/python3 '" + kScript.string() + "' write-rig '" + models[0].string() + "' '" +
                 models[1].string() + "'");
    for (int camera = 0; camera < 2; ++camera) {
        const fs::path& model = models[camera];
        const ObservationSet set = read_observations(model);
        REQUIRE(set.cameras.size() == 2);
        CHECK(set.own_camera == camera);
        // The whole solve: both cameras' intrinsics, camera 1's pose and the shared boards.
        const double at_infinity = compare_with_mrcal(model, "inf", kAtInfinity);
        const double near = compare_with_mrcal(model, "0.5", 0.5);
        CHECK(at_infinity < 1e-6);
        CHECK(near < 1e-6);
        // The camera taken alone (each of its boards posed on its own, the other camera's
        // corners left out) is not mrcal's number: far over it here.
        SolvedCalibration alone = solved_calibration(set, camera);
        const std::vector<Vec2> pixels = centre_corners_edges(alone.camera.size);
        const std::vector<double> whole = ProjectionUncertainty(alone).sigma_px(pixels);
        alone.others.clear();
        alone.frames.clear();
        alone.frame_of_view.clear();
        alone.camera.pose = Pose{};
        const std::vector<double> by_itself = ProjectionUncertainty(alone).sigma_px(pixels);
        CHECK(by_itself[0] > 1.2 * whole[0]);
        WARN("a two-camera solve, camera " << camera << ": libcam's sigma within " << 100.0 * at_infinity
                                           << "% of mrcal's at infinity, " << 100.0 * near << "% at 0.5 m; alone, "
                                           << by_itself[0] / whole[0] << " times it at the centre");
    }
}

namespace {

// A synthetic calibration: an OPENCV4 camera seeing a 9x6 board in eight poses.
struct SyntheticSet {
    Camera truth;
    Candidate candidate = candidate_named("OPENCV4");
    std::vector<Pose> poses;
    std::vector<Vec3> board;
};

SyntheticSet synthetic_set() {
    SyntheticSet set;
    set.truth.size = {640, 480};
    set.truth.intrinsics = {520.0, 522.0, 322.0, 238.0, 0.0};
    set.truth.lens = {LensType::OpenCv4, {-0.28, 0.09, 0.001, -0.0008}};
    for (int j = 0; j < 6; ++j) {
        for (int i = 0; i < 9; ++i) set.board.emplace_back(0.04 * i, 0.04 * j, 0.0);
    }
    // The board's middle at `centre` (camera frame), turned by `tilt` (Rodrigues).
    const auto pose = [&](const Vec3& centre, const Vec3& tilt) {
        const Pose turned = Pose::from_rvec(tilt, Vec3::Zero());
        return Pose{turned.R, centre - turned.R * Vec3(0.16, 0.10, 0.0)};
    };
    set.poses = {pose({0.0, 0.0, 0.55}, {0.0, 0.0, 0.0}),     pose({-0.17, -0.12, 0.6}, {0.3, -0.35, 0.05}),
                 pose({0.17, -0.12, 0.6}, {0.3, 0.35, -0.05}), pose({-0.17, 0.12, 0.6}, {-0.3, -0.35, 0.1}),
                 pose({0.17, 0.12, 0.6}, {-0.3, 0.35, 0.0}),   pose({0.0, 0.0, 0.75}, {0.5, 0.0, 0.2}),
                 pose({0.05, 0.0, 0.5}, {0.0, 0.55, -0.1}),    pose({-0.05, 0.03, 0.65}, {-0.45, 0.1, 0.3})};
    return set;
}

// The camera and the solved calibration of one calibration from corners with fresh noise.
SolvedCalibration recalibrate(const SyntheticSet& set, double noise_px, std::mt19937& random) {
    std::normal_distribution<double> noise(0.0, noise_px);
    std::vector<std::vector<FitSample>> samples;
    detail::ViewsState start;
    start.params = detail::start_from(set.candidate, set.truth).params;
    for (const Pose& pose : set.poses) {
        Camera camera = set.truth;
        camera.pose = pose;
        const PreparedCamera prepared(camera);
        std::vector<FitSample> view;
        for (const Vec3& p : set.board) {
            const Projection q = prepared.project(p);
            REQUIRE(q.valid);
            REQUIRE(on_image(q.pixel.x(), q.pixel.y(), set.truth.size));
            view.push_back({p, q.pixel + Vec2(noise(random), noise(random))});
        }
        samples.push_back(std::move(view));
        start.rotations.push_back(pose.rvec());
        start.shifts.push_back(pose.t);
    }
    const detail::ViewsState solved = detail::solve_views(set.candidate, set.truth.size, samples, start, false);
    SolvedCalibration out;
    out.camera = detail::camera_from_params(set.candidate, set.truth.size, solved.params, Pose{});
    for (std::size_t v = 0; v < samples.size(); ++v) {
        out.views.push_back({"view " + std::to_string(v), Pose::from_rvec(solved.rotations[v], solved.shifts[v]),
                             samples[v]});
    }
    return out;
}

// The true camera's ray through each pixel.
std::vector<Vec3> true_rays(const SyntheticSet& set, const std::vector<Vec2>& pixels) {
    std::vector<Vec3> rays;
    for (const Unprojection& u : PreparedCamera(set.truth).unproject(pixels)) {
        REQUIRE(u.valid);
        rays.push_back(u.direction.normalized());
    }
    return rays;
}

// Where the solved calibration puts the point at infinity that the true camera sees at
// each pixel, measured as mrcal measures a solve against the truth: the point fixed to the
// boards (carried into each board's frame by its true pose), brought back by the solved
// poses (their mean) and projected by the solved camera; minus the pixel.
std::vector<Vec2> displacements(const SyntheticSet& set, const SolvedCalibration& solved,
                                const std::vector<Vec2>& pixels, const std::vector<Vec3>& rays) {
    const PreparedCamera camera(solved.camera);
    std::vector<Vec2> out;
    for (std::size_t k = 0; k < pixels.size(); ++k) {
        Vec3 mean = Vec3::Zero();
        for (std::size_t v = 0; v < set.poses.size(); ++v) {
            mean += solved.views[v].pose.R * (set.poses[v].R.transpose() * rays[k]);
        }
        const Projection q = camera.project_camera_point(mean / static_cast<double>(set.poses.size()));
        REQUIRE(q.valid);
        out.push_back(q.pixel - pixels[k]);
    }
    return out;
}

}  // namespace

TEST_CASE("uncertainty against the truth: re-calibrations with fresh noise spread as sigma predicts",
          "[uncertainty][truth]") {
    const SyntheticSet set = synthetic_set();
    constexpr double kNoise = 0.25;
    constexpr int kRepeats = 150;
    // Pixels to follow, and a grid over the region the corners covered.
    const std::vector<Vec2> followed = {{319.5, 239.5}, {150.0, 120.0}, {500.0, 380.0}, {480.0, 100.0}, {100.0, 300.0}};
    std::mt19937 random(7);
    const SolvedCalibration first = recalibrate(set, kNoise, random);
    const std::vector<Vec2> region = observed_region(first);
    std::vector<Vec2> grid;
    for (const Vec2& p : tile_centres(set.truth.size, 16, 12)) {
        if (inside_region(region, p)) grid.push_back(p);
    }
    REQUIRE(grid.size() > 60);
    for (const Vec2& p : followed) REQUIRE(inside_region(region, p));
    const std::vector<Vec3> followed_rays = true_rays(set, followed);
    const std::vector<Vec3> grid_rays = true_rays(set, grid);

    std::vector<std::vector<Vec2>> moved(followed.size());
    std::vector<double> predicted(followed.size(), 0.0);
    std::size_t within = 0, counted = 0;
    double noise_sum = 0.0;
    for (int r = 0; r < kRepeats; ++r) {
        const SolvedCalibration solved = r == 0 ? first : recalibrate(set, kNoise, random);
        const ProjectionUncertainty uncertainty(solved);
        noise_sum += uncertainty.observed_pixel_uncertainty_px();
        const std::vector<double> sigma = uncertainty.sigma_px(followed);
        const std::vector<Vec2> followed_moved = displacements(set, solved, followed, followed_rays);
        for (std::size_t i = 0; i < followed.size(); ++i) {
            moved[i].push_back(followed_moved[i]);
            predicted[i] += sigma[i] / kRepeats;
        }
        const std::vector<double> grid_sigma = uncertainty.sigma_px(grid);
        const std::vector<Vec2> grid_moved = displacements(set, solved, grid, grid_rays);
        for (std::size_t k = 0; k < grid.size(); ++k) {
            within += grid_moved[k].norm() <= 3.0 * grid_sigma[k] ? 1 : 0;
            ++counted;
        }
    }
    // The noise the residuals imply is the noise put in, less the share the fit absorbs.
    CHECK(noise_sum / kRepeats == Approx(kNoise).epsilon(0.05));
    for (std::size_t i = 0; i < followed.size(); ++i) {
        Vec2 mean = Vec2::Zero();
        for (const Vec2& d : moved[i]) mean += d / kRepeats;
        Mat2 spread = Mat2::Zero();
        for (const Vec2& d : moved[i]) spread += (d - mean) * (d - mean).transpose() / (kRepeats - 1);
        const double measured = worst_direction_stdev(spread);
        WARN("pixel (" << followed[i].x() << ", " << followed[i].y() << "): measured spread " << measured
                       << " px, predicted sigma " << predicted[i] << " px");
        CHECK(measured / predicted[i] == Approx(1.0).margin(0.20));
    }
    const double share = static_cast<double>(within) / static_cast<double>(counted);
    WARN("the truth within 3 sigma at " << 100.0 * share << "% of " << counted << " grid points");
    CHECK(share >= 0.90);
}

TEST_CASE("uncertainty refuses what it cannot measure, in one line", "[uncertainty]") {
    const SyntheticSet set = synthetic_set();
    std::mt19937 random(3);
    SolvedCalibration solved = recalibrate(set, 0.2, random);
    const ProjectionUncertainty uncertainty(solved);
    CHECK_THROWS_AS(uncertainty.sigma_px({Vec2(320, 240)}, 0.0), InvalidArgument);
    // One view cannot tell the intrinsics from its pose.
    SolvedCalibration one = solved;
    one.views.resize(1);
    CHECK_THROWS_WITH(ProjectionUncertainty(one), Catch::Contains("the observations do not determine it"));
    // A model the fit cannot differentiate.
    SolvedCalibration splined = solved;
    splined.camera.intrinsics.skew = 1.0;
    CHECK_THROWS_WITH(ProjectionUncertainty(splined), Catch::Contains("skew"));
}
