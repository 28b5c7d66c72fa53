// OpenCV's calibration sample's outputs (out_camera_data.yml/.xml): read_observations on
// the nine real files of the shared real-data folder, whose stored avg_reprojection_error
// and per-view errors libcam's reprojection must reproduce (to their float storage), and
// whose every projection must equal cv::projectPoints' on the same numbers, read here
// with cv::FileStorage; and hand-made files that are malformed.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/io/observations.hpp"
#include "real_cameras.hpp"

namespace {

using namespace libcam;

// Each file, with what SOURCES.md says of it: the stored avg_reprojection_error, the
// number of views and the board.
struct SampleOutput {
    const char* path;
    double stored_avg;
    std::size_t views;
    int board_width, board_height;
};

const SampleOutput kSampleOutputs[] = {
    {"opencv-calib-outputs2/opencv-tutorial/out_camera_data.yml", 0.38441346462381665, 8, 9, 6},
    {"opencv-calib-outputs2/spaceview-opencv455-demo/out_camera_data.xml", 8.1388840849437472, 5, 9, 6},
    {"opencv-calib-outputs2/arnoldad-rs435i/out_camera_data.xml", 0.21650052128653835, 5, 8, 6},
    {"opencv-calib-outputs2/scanvan/out_camera_data.xml", 1.6316837814849146, 9, 9, 6},
    {"opencv-calib-outputs2/shamisen00/out_camera_data.yml", 2.9082761973083158, 5, 7, 7},
    {"opencv-calib-outputs2/jrebort-mcc/out_camera_data.xml", 0.075289322143560919, 8, 11, 8},
    {"opencv-calib-outputs2/bryan-bai/out_camera_data.yml", 0.72721969191026936, 25, 9, 6},
    {"opencv-calib-outputs2/hpfily/out_camera_data.xml", 0.85561914171043119, 8, 9, 6},
    {"opencv-calib-outputs2/ntu-mecatron/out_camera_data.xml", 0.55612728570502168, 20, 15, 10},
};

// The stored numbers are float32 (the per-view errors) or computed from float32 pixels and
// projections (the average): reproduced to 1e-5 relative. The sample's projections are
// float (Point2f): each coordinate rounded by up to half a float's step, 1.2e-4 px at
// 3000 px, which moves a view's RMS over its few dozen corners by up to ~1e-5 px (8.5e-6
// measured, shamisen00's view 4): the per-view errors to that too.
constexpr double kFloatStorage = 1e-5;
constexpr double kFloatProjectionPx = 2e-5;

// The first of `names` the file has (the sample's keys, or its 2011 spellings).
cv::FileNode node_of(const cv::FileStorage& storage, std::initializer_list<const char*> names) {
    for (const char* name : names) {
        const cv::FileNode node = storage[name];
        if (!node.empty()) return node;
    }
    return {};
}

// The sample's projections of every corner of every view, by OpenCV itself from the
// file as cv::FileStorage reads it: row v holds view v's corners.
struct OpenCvProjections {
    cv::Mat image_points;                     // views x corners, CV_32FC2
    std::vector<std::vector<cv::Point2d>> projected;
};

std::vector<cv::Point3d> board_of(const cv::FileStorage& storage) {
    std::vector<cv::Point3f> grid;
    if (!storage["grid_points"].empty()) {
        storage["grid_points"] >> grid;
    } else {
        // calcBoardCornerPositions for a chessboard, in float as the sample does it.
        const int width = static_cast<int>(node_of(storage, {"board_width", "board_Width"}));
        const int height = static_cast<int>(node_of(storage, {"board_height", "board_Height"}));
        const float square = static_cast<float>(node_of(storage, {"square_size", "square_Size"}));
        for (int i = 0; i < height; ++i)
            for (int j = 0; j < width; ++j) grid.emplace_back(static_cast<float>(j) * square, static_cast<float>(i) * square, 0.0f);
    }
    return {grid.begin(), grid.end()};
}

OpenCvProjections project_with_opencv(const std::filesystem::path& path) {
    const cv::FileStorage storage(path.string(), cv::FileStorage::READ);
    REQUIRE(storage.isOpened());
    cv::Mat K, dist, extrinsics;
    OpenCvProjections out;
    node_of(storage, {"camera_matrix", "Camera_Matrix"}) >> K;
    node_of(storage, {"distortion_coefficients", "Distortion_Coefficients"}) >> dist;
    node_of(storage, {"extrinsic_parameters", "Extrinsic_Parameters"}) >> extrinsics;
    node_of(storage, {"image_points", "Image_points"}) >> out.image_points;
    const bool fisheye = !storage["fisheye_model"].empty() && static_cast<int>(storage["fisheye_model"]) == 1;
    const std::vector<cv::Point3d> board = board_of(storage);
    REQUIRE(static_cast<int>(board.size()) == out.image_points.cols);
    for (int v = 0; v < out.image_points.rows; ++v) {
        cv::Mat rotation, translation;
        if (extrinsics.cols == 6) {
            rotation = extrinsics(cv::Range(v, v + 1), cv::Range(0, 3)).clone().reshape(1, 3);
            translation = extrinsics(cv::Range(v, v + 1), cv::Range(3, 6)).clone().reshape(1, 3);
        } else {  // 3 x 4 [R | t] blocks: projectPoints takes a rotation matrix for rvec
            rotation = extrinsics(cv::Range(3 * v, 3 * v + 3), cv::Range(0, 3)).clone();
            translation = extrinsics(cv::Range(3 * v, 3 * v + 3), cv::Range(3, 4)).clone();
        }
        std::vector<cv::Point2d> projected;
        if (fisheye) {
            cv::Mat rvec;
            if (rotation.rows == 3 && rotation.cols == 3) cv::Rodrigues(rotation, rvec); else rvec = rotation;
            cv::fisheye::projectPoints(board, projected, rvec, translation, K, dist);
        } else {
            cv::projectPoints(board, rotation, translation, K, dist, projected);
        }
        out.projected.push_back(projected);
    }
    return out;
}

}  // namespace

TEST_CASE("OpenCV's calibration sample: read_observations reproduces its avg and per-view errors") {
    for (const SampleOutput& sample : kSampleOutputs) {
        const std::filesystem::path path = test::real_data_path(sample.path);
        if (!test::real_data_present(path)) continue;
        INFO(sample.path);
        const ObservationSet set = read_observations(path);
        CHECK(set.tool == ObservationTool::OpenCvCalibration);
        REQUIRE(set.cameras.size() == 1);
        REQUIRE(set.views.size() == sample.views);
        CHECK(set.views.front().name == "view 0");
        REQUIRE(set.board);
        CHECK(set.board->width == sample.board_width);
        CHECK(set.board->height == sample.board_height);
        const auto corners = static_cast<std::size_t>(sample.board_width * sample.board_height);
        CHECK(set.points.size() == corners);
        CHECK(set.observations.size() == sample.views * corners);
        CHECK(set.pixel_offset == Vec2::Zero());
        REQUIRE(set.reported.size() == 1);
        CHECK(set.reported[0].value == sample.stored_avg);
        CHECK(set.reported[0].measure == ReportedMeasure::RmsOverObservations);
        REQUIRE(set.reported_per_view.size() == sample.views);

        const Reprojection r = reproject(set);
        // Every corner projects, the degenerate jrebort-mcc lens's among them (checked
        // on its own below), and every one is on the image.
        CHECK(r.summary.outside_domain == 0);
        CHECK(r.summary.behind_camera == 0);
        CHECK(r.summary.outside_image == 0);
        CHECK(r.summary.all.stats.count == set.observations.size());
        CHECK(r.summary.reported[0].recomputed == Approx(sample.stored_avg).epsilon(kFloatStorage));
        REQUIRE(r.summary.per_view.size() == sample.views);
        for (std::size_t v = 0; v < sample.views; ++v) {
            INFO("view " << v);
            CHECK(r.summary.per_view[v].residuals.stats.rms_px == Approx(set.reported_per_view[v]).epsilon(kFloatStorage).margin(kFloatProjectionPx));
        }
        REQUIRE(r.summary.per_view_reported);
        CHECK(r.summary.per_view_reported->compared == sample.views);
    }
}

TEST_CASE("OpenCV's calibration sample: every projection equals cv::projectPoints' to 1e-9 px") {
    for (const SampleOutput& sample : kSampleOutputs) {
        const std::filesystem::path path = test::real_data_path(sample.path);
        if (!test::real_data_present(path)) continue;
        INFO(sample.path);
        const ObservationSet set = read_observations(path);
        const Reprojection r = reproject(set);
        const OpenCvProjections opencv = project_with_opencv(path);
        REQUIRE(static_cast<std::size_t>(opencv.image_points.rows) == set.views.size());
        const auto corners = static_cast<std::size_t>(opencv.image_points.cols);
        double largest_difference = 0.0;
        std::size_t pixels_differing = 0;
        for (std::size_t i = 0; i < set.observations.size(); ++i) {
            const Observation& o = set.observations[i];
            REQUIRE(static_cast<std::size_t>(o.point) == i % corners);
            const cv::Point2f stored = opencv.image_points.at<cv::Vec2f>(o.view, o.point);
            if (o.pixel != Vec2(stored.x, stored.y)) ++pixels_differing;
            const cv::Point2d expected = opencv.projected[static_cast<std::size_t>(o.view)][static_cast<std::size_t>(o.point)];
            const double difference = (r.residuals[i].projected - Vec2(expected.x, expected.y)).norm();
            largest_difference = std::max(largest_difference, std::isnan(difference) ? INFINITY : difference);
        }
        CHECK(pixels_differing == 0);  // the float OpenCV reads, bit for bit
        CHECK(largest_difference <= 1e-9);
    }
}

TEST_CASE("OpenCV's calibration sample: the stored errors recomputed by OpenCV's rule, corners past the domain counted") {
    // BeyondCloud's fisheye_cali: a wide lens fitted as OPENCV5 (fx 243 px on 640 x 480,
    // k1 -0.253) whose radial part folds over inside the image; 3 of its 1200 corners lie
    // past the fold. OpenCV counts every corner: its avg_reprojection_error and per-view
    // errors are recomputed here with cv::projectPoints, independently of libcam.
    const std::filesystem::path path =
        test::real_cameras_folder("opencv-calib-sample-outputs/fisheye_cali/out_camera_data.xml");
    if (!test::real_data_present(path)) return;
    const ObservationSet set = read_observations(path);
    REQUIRE(set.reported.size() == 1);
    CHECK(set.reported[0].value == 3.0766923253942005);  // as stored
    const OpenCvProjections opencv = project_with_opencv(path);
    const auto corners = static_cast<std::size_t>(opencv.image_points.cols);
    double sum_squares = 0.0;
    std::vector<double> view_sums(set.views.size(), 0.0);
    for (const Observation& o : set.observations) {
        const cv::Point2d p = opencv.projected[static_cast<std::size_t>(o.view)][static_cast<std::size_t>(o.point)];
        const double squared = (Vec2(p.x, p.y) - o.pixel).squaredNorm();
        sum_squares += squared;
        view_sums[static_cast<std::size_t>(o.view)] += squared;
    }
    const double opencv_avg = std::sqrt(sum_squares / static_cast<double>(set.observations.size()));

    const Reprojection r = reproject(set);
    // libcam's own statistics set the 3 apart, and say so.
    CHECK(r.summary.outside_domain == 3);
    CHECK(r.summary.all.stats.count == 1197);
    // The stored number, by OpenCV's rule: every corner, those past the domain at the
    // pixel the formula gives there, which is cv::projectPoints' pixel.
    CHECK(r.summary.reported_past_domain == 3);
    REQUIRE(r.summary.reported.size() == 1);
    CHECK(r.summary.reported[0].recomputed == Approx(opencv_avg).epsilon(1e-12));
    CHECK(r.summary.reported[0].recomputed == Approx(3.0766923253942005).epsilon(kFloatStorage));
    for (std::size_t i = 0; i < r.residuals.size(); ++i) {
        if (r.residuals[i].status != ResidualStatus::OutsideDomain) continue;
        const Observation& o = set.observations[i];
        const cv::Point2d p = opencv.projected[static_cast<std::size_t>(o.view)][static_cast<std::size_t>(o.point)];
        CHECK((r.residuals[i].past_domain_projected - Vec2(p.x, p.y)).norm() < 1e-9);
    }
    // Each view's, against OpenCV's and against the stored float.
    REQUIRE(r.summary.per_view_reported);
    CHECK(r.summary.per_view_reported->compared == 25);
    CHECK(r.summary.per_view_reported->max_abs_difference < kFloatStorage);
    for (std::size_t v = 0; v < set.views.size(); ++v) {
        const double opencv_view = std::sqrt(view_sums[v] / static_cast<double>(corners));
        CHECK(opencv_view == Approx(set.reported_per_view[v]).epsilon(kFloatStorage).margin(kFloatProjectionPx));
    }
}

TEST_CASE("OpenCV's calibration sample: jrebort-mcc's degenerate lens (k3 = -19949) and its domain") {
    const std::filesystem::path path =
        test::real_data_path("opencv-calib-outputs2/jrebort-mcc/out_camera_data.xml");
    if (!test::real_data_present(path)) return;
    const ObservationSet set = read_observations(path);
    const Camera& camera = set.cameras.front().camera;
    REQUIRE(camera.lens.type == LensType::OpenCv5);
    CHECK(camera.lens.coefficients[4] == -1.9949502044254805e+04);
    // The radial part d(r) = r (1 + k1 r^2 + k2 r^4 + k3 r^6) folds over where
    // 1 + 3 k1 s + 5 k2 s^2 + 7 k3 s^3 = 0 (s = r^2): its first root, by bisection here.
    const std::vector<double>& k = camera.lens.coefficients;
    const auto slope = [&](double s) { return 1 + 3 * k[0] * s + 5 * k[1] * s * s + 7 * k[4] * s * s * s; };
    double low = 0.0, high = 1.0;
    REQUIRE(slope(high) < 0);
    for (int step = 0; step < 200; ++step) (slope(0.5 * (low + high)) > 0 ? low : high) = 0.5 * (low + high);
    const double fold_radius = std::sqrt(low);
    // Every corner the sample saw lies inside it, so inside the lens's valid domain: none
    // is left out of the statistics.
    double largest_radius = 0.0;
    for (const Observation& o : set.observations) {
        const Vec3 p = set.views[static_cast<std::size_t>(o.view)].pose.camera_from_world(set.points[static_cast<std::size_t>(o.point)]);
        largest_radius = std::max(largest_radius, std::hypot(p.x() / p.z(), p.y() / p.z()));
    }
    INFO("fold-over at r = " << fold_radius << ", corners out to r = " << largest_radius);
    CHECK(largest_radius < fold_radius);
    const Reprojection r = reproject(set);
    CHECK(r.summary.outside_domain == 0);
    CHECK(r.summary.all.stats.count == set.observations.size());
}

namespace {

// A small output of the sample, made by hand: a 2x2 board (square 10), two views, with
// `replace` applied to the text (a key's line swapped for a malformed one).
std::string hand_made_output(const std::string& from = {}, const std::string& to = {}) {
    std::string text =
        "%YAML:1.0\r\n---\r\n"
        "image_width: 640\r\nimage_height: 480\r\n"
        "board_width: 2\r\nboard_height: 2\r\nsquare_size: 10.\r\n"
        "camera_matrix: !!opencv-matrix\r\n   rows: 3\r\n   cols: 3\r\n   dt: d\r\n"
        "   data: [ 500., 0., 320., 0., 500., 240., 0., 0., 1. ]\r\n"
        "distortion_coefficients: !!opencv-matrix\r\n   rows: 5\r\n   cols: 1\r\n   dt: d\r\n"
        "   data: [ 0., 0., 0., 0., 0. ]\r\n"
        "avg_reprojection_error: 0.5\r\n"
        "per_view_reprojection_errors: !!opencv-matrix\r\n   rows: 2\r\n   cols: 1\r\n   dt: f\r\n"
        "   data: [ 0.5, 0.5 ]\r\n"
        "extrinsic_parameters: !!opencv-matrix\r\n   rows: 2\r\n   cols: 6\r\n   dt: d\r\n"
        "   data: [ 0., 0., 0., 0., 0., 100., 0., 0., 0., -10., 0., 50. ]\r\n"
        "image_points: !!opencv-matrix\r\n   rows: 2\r\n   cols: 4\r\n   dt: \"2f\"\r\n"
        "   data: [ 320.5, 240., 370., 240.5, 320., 290., 370., 290.,\r\n"
        "       220., 240., 320., 240., 220., 340., 320., 340. ]\r\n";
    if (!from.empty()) {
        const std::size_t at = text.find(from);
        REQUIRE(at != std::string::npos);
        text.replace(at, from.size(), to);
    }
    return text;
}

std::filesystem::path write_hand_made(const std::string& name, const std::string& text) {
    const std::filesystem::path path = std::filesystem::temp_directory_path() / ("libcam_test_opencv_outputs_" + name);
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

std::string error_reading(const std::filesystem::path& path) {
    try {
        (void)read_observations(path);
    } catch (const FileError& error) {
        return error.what();
    }
    return "(no error)";
}

}  // namespace

TEST_CASE("OpenCV's calibration sample: a hand-made output, worked by hand") {
    // View 0: the board 100 in front, corners (0,0,100) (10,0,100) (0,10,100) (10,10,100)
    // project to (320,240) (370,240) (320,290) (370,290); the file's pixels are off by
    // (0.5, 0), (0, 0.5), 0, 0: |d|^2 = 0.25 + 0.25 = 0.5 over 4, RMS sqrt(0.125).
    // View 1: t = (-10, 0, 50): corners at x = -10, 0 -> 220, 320 and y = 0, 10 -> 240, 340:
    // exact. Overall sqrt(0.5 / 8) = 0.25.
    const std::filesystem::path path = write_hand_made("good.yml", hand_made_output());
    const ObservationSet set = read_observations(path);
    REQUIRE(set.observations.size() == 8);
    CHECK(set.points[3] == Vec3(10.0, 10.0, 0.0));
    CHECK(set.observations[1].pixel == Vec2(370.0, 240.5));
    CHECK(set.views[1].pose.t == Vec3(-10.0, 0.0, 50.0));
    const Reprojection r = reproject(set);
    CHECK(r.residuals[0].residual.x() == Approx(-0.5).margin(1e-12));
    CHECK(r.summary.per_view[0].residuals.stats.rms_px == Approx(std::sqrt(0.125)).epsilon(1e-12));
    CHECK(r.summary.per_view[1].residuals.stats.rms_px == Approx(0.0).margin(1e-12));
    CHECK(r.summary.reported[0].recomputed == Approx(0.25).epsilon(1e-12));
    std::filesystem::remove(path);
}

TEST_CASE("OpenCV's calibration sample: malformed outputs give one line naming the file, field and value") {
    struct Case {
        const char* name;
        std::string from, to;
        std::vector<std::string> said;  // what the message must hold
    };
    const Case cases[] = {
        {"points-per-view.yml", "board_width: 2", "board_width: 3",
         {"\"image_points\"", "4 points per view", "6 corners"}},
        {"extrinsic-rows.yml", "   rows: 2\r\n   cols: 6\r\n   dt: d\r\n   data: [ 0., 0., 0., 0., 0., 100.,",
         "   rows: 3\r\n   cols: 6\r\n   dt: d\r\n   data: [ 0., 0., 0., 0., 0., 100., 0., 0., 0., 0., 0., 100.,",
         {"\"extrinsic_parameters\"", "is 3x6", "expected 2x6", "the 2 views of image_points"}},
        {"extrinsic-count.yml", "   rows: 2\r\n   cols: 6", "   rows: 3\r\n   cols: 6",
         {"\"extrinsic_parameters.data\"", "holds 12 numbers", "3x6"}},
        {"extrinsic-shape.yml", "   rows: 2\r\n   cols: 6\r\n   dt: d\r\n   data: [ 0., 0., 0., 0., 0., 100., 0., 0., 0., -10., 0., 50. ]",
         "   rows: 3\r\n   cols: 4\r\n   dt: d\r\n   data: [ 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 100. ]",
         {"\"extrinsic_parameters\"", "is 3x4", "expected 2x6", "or 6x4"}},
        {"non-numeric.yml", "370., 290.,\r\n", "370., abc,\r\n", {"line 33", "\"image_points.data\"[7]", "'abc'"}},
        {"per-view-count.yml", "   data: [ 0.5, 0.5 ]", "   data: [ 0.5 ]",
         {"\"per_view_reprojection_errors", "1 numbers", "rows x cols is 2x1"}},
        {"one-channel.yml", "   cols: 4\r\n   dt: \"2f\"", "   cols: 8\r\n   dt: f", {"\"image_points\"", "2-channel", "1 channel"}},
        {"no-points.yml", "image_points:", "other_points:", {"\"image_points\": missing", "no observations"}},
        {"square.yml", "square_size: 10.", "square_size: -1.", {"\"square_size\"", "must be > 0", "-1."}},
    };
    for (const Case& c : cases) {
        INFO(c.name);
        const std::filesystem::path path = write_hand_made(c.name, hand_made_output(c.from, c.to));
        const std::string message = error_reading(path);
        INFO(message);
        CHECK(message.find(path.string() + ":") == 0);
        CHECK(message.find('\n') == std::string::npos);
        for (const std::string& part : c.said) CHECK(message.find(part) != std::string::npos);
        std::filesystem::remove(path);
    }
}

TEST_CASE("OpenCV's calibration sample: fisheye_model 1 reads cv::fisheye's lens, projected as cv::fisheye::projectPoints") {
    const std::string text = hand_made_output(
        "distortion_coefficients: !!opencv-matrix\r\n   rows: 5\r\n   cols: 1\r\n   dt: d\r\n   data: [ 0., 0., 0., 0., 0. ]",
        "fisheye_model: 1\r\ndistortion_coefficients: !!opencv-matrix\r\n   rows: 4\r\n   cols: 1\r\n   dt: d\r\n"
        "   data: [ 0.05, -0.01, 0.002, 0. ]");
    const std::filesystem::path path = write_hand_made("fisheye.yml", text);
    const ObservationSet set = read_observations(path);
    CHECK(set.cameras.front().camera.lens.type == LensType::Fisheye);
    const Reprojection r = reproject(set);
    const OpenCvProjections opencv = project_with_opencv(path);
    for (std::size_t i = 0; i < set.observations.size(); ++i) {
        const Observation& o = set.observations[i];
        const cv::Point2d expected = opencv.projected[static_cast<std::size_t>(o.view)][static_cast<std::size_t>(o.point)];
        CHECK((r.residuals[i].projected - Vec2(expected.x, expected.y)).norm() <= 1e-9);
    }
    std::filesystem::remove(path);
}
