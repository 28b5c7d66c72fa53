// The calibration from board images rendered through known lenses: the truth's model
// chosen, K near the truth, and the projection at least as near the truth as OpenCV's
// own calibration of the same images; OpenCV's own sample images against OpenCV's stored
// calibration.

#include <catch2/catch.hpp>

#include <filesystem>
#include <sstream>
#include <limits>
#include <numeric>
#include <random>

#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>

#include "libcam/calibrate/calibrate.hpp"
#include "libcam/calibrate/mrcal_solve.hpp"
#include "libcam/calibrate/opencv_flags.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/mrcal.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/observations.hpp"
#include "libcam/uncertainty/uncertainty_map.hpp"
#include "temp_dir.hpp"
#include "synthetic_sets.hpp"
#include "truth_distance.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

std::vector<BoardDetection> detect_views(const std::vector<SyntheticView>& views, const BoardSpec& board,
                                         const ImageSize& size) {
    std::vector<BoardDetection> out;
    for (std::size_t v = 0; v < views.size(); ++v) {
        BoardDetection found = detect_board_in(views[v].image.data, size, board);
        found.image = "view" + std::to_string(v) + ".png";
        out.push_back(std::move(found));
    }
    return out;
}

std::string describe(const Calibration& c) {
    std::ostringstream out;
    for (const ObservationCandidate& candidate : c.fit.candidates) {
        out << candidate.candidate.name << " rms " << candidate.rms_px << " held-out " << candidate.heldout_rms_px << "; ";
    }
    const Intrinsics& k = c.chosen().camera.intrinsics;
    out << "chosen " << c.chosen().candidate.name << " K " << k.fx << " " << k.fy << " " << k.cx << " " << k.cy
        << ", outliers " << c.outliers << ", noise " << c.noise_px << " px, " << c.views.size() << " views used";
    for (const RejectedImage& r : c.rejected) out << "; rejected " << r.image << ": " << r.why;
    return out.str();
}

// K within a stated reach of the truth. Over 20 redraws of 0.08 px of white noise on the
// true corners of the OPENCV5 set (the noise its fits show), the OPENCV5 fit's fx and fy
// spread by 0.37 px, cx by 0.10 px and cy by 0.25 px (one standard deviation). The focal
// lengths are held to 0.3% (four of those) and the principal point to 1 px: the corners
// a detector finds are not white noise (their errors follow the blur and the lens's curve
// at each corner), and the principal point trades against a common turn of the boards,
// which the distance from the truth below takes out.
void check_near_truth(const Intrinsics& k, const Intrinsics& truth) {
    CHECK(std::abs(k.fx / truth.fx - 1.0) < 0.003);
    CHECK(std::abs(k.fy / truth.fy - 1.0) < 0.003);
    CHECK(std::abs(k.cx - truth.cx) < 1.0);
    CHECK(std::abs(k.cy - truth.cy) < 1.0);
}

std::size_t view_number(const std::string& image) { return static_cast<std::size_t>(std::stoul(image.substr(4))); }

// libcam's calibration against the truth (truth_distance.hpp), over the views it used.
double distance_from_truth(const Calibration& c, const std::vector<SyntheticView>& views, const Camera& truth) {
    std::vector<Pose> true_poses;
    std::vector<SolvedView> solved;
    for (std::size_t v = 0; v < c.views.size(); ++v) {
        const CalibrationView& view = c.views[v];
        true_poses.push_back(true_pose_as_numbered(truth, views[view_number(view.image)].pose, c.board, view.ids[0],
                                                   view.pixels[0]));
        solved.push_back({view.ids, c.chosen().poses[v]});
    }
    return rms_from_truth(truth, true_poses, solved, c.board, projection_of(c.chosen().camera));
}

// Corners as OpenCV's calibration functions take them: those OpenCV's calibration sample
// finds (findChessboardCorners, then cornerSubPix in its 11 x 11 window), or libcam's.
struct OpenCvViews {
    std::vector<std::size_t> views;  // the rendered view each came from
    std::vector<std::vector<int>> ids;
    std::vector<std::vector<cv::Point3f>> object_points;
    std::vector<std::vector<cv::Point2f>> image_points;

    void add(std::size_t view, const BoardSpec& board, const std::vector<int>& corner_ids,
             const std::vector<cv::Point2f>& pixels) {
        const std::vector<Vec3> corners = board.corner_points();
        views.push_back(view);
        ids.push_back(corner_ids);
        object_points.emplace_back();
        for (const int id : corner_ids) {
            const Vec3& p = corners[static_cast<std::size_t>(id)];
            object_points.back().emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), 0.0f);
        }
        image_points.push_back(pixels);
    }
};

OpenCvViews opencv_sample_corners(const std::vector<SyntheticView>& views, const BoardSpec& board) {
    OpenCvViews out;
    std::vector<int> ids(static_cast<std::size_t>(board.columns * board.rows));
    std::iota(ids.begin(), ids.end(), 0);
    for (std::size_t v = 0; v < views.size(); ++v) {
        std::vector<cv::Point2f> corners;
        if (!cv::findChessboardCorners(views[v].image, cv::Size(board.columns, board.rows), corners,
                                       cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) {
            continue;
        }
        cv::cornerSubPix(views[v].image, corners, cv::Size(11, 11), cv::Size(-1, -1),
                         cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.0001));
        out.add(v, board, ids, corners);
    }
    return out;
}

OpenCvViews corners_of(const Calibration& c) {
    OpenCvViews out;
    for (const CalibrationView& view : c.views) {
        std::vector<cv::Point2f> pixels;
        for (const Vec2& p : view.pixels) pixels.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
        out.add(view_number(view.image), c.board, view.ids, pixels);
    }
    return out;
}

// OpenCV's calibration (its K, distortion and board poses) against the truth, measured as libcam's is.
double distance_from_truth(const OpenCvViews& found, const cv::Mat& K, const cv::Mat& dist,
                           const std::vector<cv::Mat>& rvecs, const std::vector<cv::Mat>& tvecs, bool fisheye,
                           const std::vector<SyntheticView>& views, const Camera& truth, const BoardSpec& board) {
    std::vector<Pose> true_poses;
    std::vector<SolvedView> solved;
    for (std::size_t v = 0; v < found.views.size(); ++v) {
        const cv::Point2f& first = found.image_points[v][0];
        true_poses.push_back(true_pose_as_numbered(truth, views[found.views[v]].pose, board, found.ids[v][0],
                                                   Vec2(first.x, first.y)));
        const cv::Vec3d r = rvecs[v], t = tvecs[v];
        solved.push_back({found.ids[v], Pose::from_rvec({r[0], r[1], r[2]}, {t[0], t[1], t[2]})});
    }
    const SolvedProjection project = [&](const Pose& pose, const std::vector<Vec3>& points) {
        std::vector<cv::Point3d> object;
        for (const Vec3& p : points) object.emplace_back(p.x(), p.y(), p.z());
        const Vec3 r = pose.rvec();
        const cv::Vec3d rvec(r.x(), r.y(), r.z()), tvec(pose.t.x(), pose.t.y(), pose.t.z());
        std::vector<cv::Point2d> image;
        if (fisheye) {
            cv::fisheye::projectPoints(object, image, rvec, tvec, K, dist);
        } else {
            cv::projectPoints(object, rvec, tvec, K, dist, image);
        }
        std::vector<Vec2> pixels;
        for (const cv::Point2d& q : image) pixels.emplace_back(q.x, q.y);
        return pixels;
    };
    return rms_from_truth(truth, true_poses, solved, board, project);
}

// OpenCV's calibrateCamera (k1 k2 p1 p2 k3, its defaults), or cv::fisheye::calibrate as
// its users call it, on these corners, against the truth.
double opencv_distance(const OpenCvViews& found, bool fisheye, const std::vector<SyntheticView>& views,
                       const Camera& truth, const BoardSpec& board) {
    cv::Mat K, dist;
    std::vector<cv::Mat> rvecs, tvecs;
    const cv::Size size(static_cast<int>(truth.size.width), static_cast<int>(truth.size.height));
    if (fisheye) {
        cv::fisheye::calibrate(found.object_points, found.image_points, size, K, dist, rvecs, tvecs,
                               cv::fisheye::CALIB_RECOMPUTE_EXTRINSIC | cv::fisheye::CALIB_FIX_SKEW);
    } else {
        cv::calibrateCamera(found.object_points, found.image_points, size, K, dist, rvecs, tvecs);
    }
    return distance_from_truth(found, K, dist, rvecs, tvecs, fisheye, views, truth, board);
}

// A chessboard set calibrated by libcam and by OpenCV (its sample's corners, and libcam's),
// each measured against the truth.
struct ChessboardRun {
    Calibration calibration;
    double libcam = 0.0, opencv = 0.0, opencv_on_ours = 0.0;
    std::size_t opencv_views = 0;

    std::string describe_it() const {
        std::ostringstream out;
        out << describe(calibration) << "; from the truth over the observed boards: libcam " << libcam
            << " px, OpenCV on its sample's corners (" << opencv_views << " views) " << opencv
            << " px, on libcam's " << opencv_on_ours << " px";
        return out.str();
    }
};

ChessboardRun run_chessboard_set(const Camera& truth, const std::vector<PoseSpec>& poses, bool fisheye) {
    const BoardSpec board = parse_board_spec("chessboard:9x6:0.03");
    const std::vector<SyntheticView> views = render_views(truth, board, chessboard_texture(board), poses);
    ChessboardRun run{calibrate(detect_views(views, board, truth.size), board, {})};
    run.libcam = distance_from_truth(run.calibration, views, truth);
    const OpenCvViews sample = opencv_sample_corners(views, board);
    run.opencv_views = sample.views.size();
    run.opencv = opencv_distance(sample, fisheye, views, truth, board);
    run.opencv_on_ours = opencv_distance(corners_of(run.calibration), fisheye, views, truth, board);
    return run;
}

const ObservationCandidate& candidate_of(const Calibration& c, const std::string& name) {
    for (const ObservationCandidate& candidate : c.fit.candidates) {
        if (candidate.candidate.name == name) return candidate;
    }
    throw std::logic_error("no candidate " + name);
}

}  // namespace

// The set's poses reach the image's corners and turn the boards up to 0.7 rad
// (synthetic_sets.hpp): over boards kept to the middle third, OPENCV4 was chosen with a
// focal length 1% short, its k1 making up for the k3 it lacks.
TEST_CASE("Calibrate: a chessboard through an OPENCV5 lens gives OPENCV5, nearer the truth than OpenCV's",
          "[sweep][calibrate][fit]") {
    const Camera truth = opencv5_truth();
    const ChessboardRun run = run_chessboard_set(truth, opencv5_poses(), false);
    const Calibration& c = run.calibration;
    const double libcam = run.libcam;
    INFO(run.describe_it());
    CHECK(c.rejected.empty());
    CHECK(c.chosen().candidate.name == "OPENCV5");
    CHECK(candidate_of(c, "OPENCV5").heldout_rms_px < candidate_of(c, "OPENCV4").heldout_rms_px / (1.0 + c.fit.margin));
    check_near_truth(c.chosen().camera.intrinsics, truth.intrinsics);
    // Within the corners' noise of the truth wherever the boards were seen; no further from
    // it than calibrateCamera on the same corners; and within 10% of OpenCV's sample on its
    // own corners. Both are a third of the noise from the truth (0.0128 and 0.0117 px here):
    // the sample's cornerSubPix window is 11 px whatever the squares' size, libcam's 0.4 of
    // a square, which a fisheye's curved edges need (with 11 px, libcam's fisheye below
    // lands 0.055 px from the truth instead of 0.02 px and OPENCV8 is chosen).
    CHECK(libcam < c.noise_px);
    CHECK(run.opencv_views >= 7);
    CHECK(libcam <= run.opencv * 1.1);
    CHECK(libcam <= run.opencv_on_ours * 1.001);
}

TEST_CASE("Calibrate: a ChArUco board through an OPENCV5 lens gives OPENCV5, nearer the truth than OpenCV's",
          "[sweep][calibrate][fit]") {
    const BoardSpec board = parse_board_spec("charuco:10x8:0.03:0.022:DICT_4X4_50");
    const Camera truth = opencv5_truth();
    const std::vector<SyntheticView> views =
        render_views(truth, board, charuco_texture(board), opencv5_poses(), {}, false);
    const Calibration c = calibrate(detect_views(views, board, truth.size), board, {});
    const double libcam = distance_from_truth(c, views, truth);

    // OpenCV's own ChArUco pipeline on the same images: its markers, its corners
    // (interpolateCornersCharuco), calibrateCameraCharuco.
    const cv::Ptr<cv::aruco::CharucoBoard> charuco = cv::aruco::CharucoBoard::create(
        board.columns, board.rows, static_cast<float>(board.square), static_cast<float>(board.marker),
        cv::aruco::getPredefinedDictionary(board.dictionary_id));
    OpenCvViews found;
    std::vector<cv::Mat> corner_sets, id_sets;
    for (std::size_t v = 0; v < views.size(); ++v) {
        std::vector<std::vector<cv::Point2f>> markers;
        std::vector<int> marker_ids, ids;
        std::vector<cv::Point2f> corners;
        cv::aruco::detectMarkers(views[v].image, charuco->dictionary, markers, marker_ids);
        if (marker_ids.empty()) continue;
        cv::aruco::interpolateCornersCharuco(markers, marker_ids, views[v].image, charuco, corners, ids);
        if (ids.size() < kMinCornersPerView) continue;
        found.add(v, board, ids, corners);
        corner_sets.push_back(cv::Mat(corners).clone());
        id_sets.push_back(cv::Mat(ids).clone());
    }
    cv::Mat K, dist;
    std::vector<cv::Mat> rvecs, tvecs;
    cv::aruco::calibrateCameraCharuco(corner_sets, id_sets, charuco, cv::Size(640, 480), K, dist, rvecs, tvecs);
    const double opencv = distance_from_truth(found, K, dist, rvecs, tvecs, false, views, truth, board);
    INFO(describe(c) << "; " << c.corners() << " corners; from the truth: libcam " << libcam << " px, OpenCV "
                     << opencv << " px (" << found.views.size() << " views)");
    CHECK(c.rejected.empty());
    CHECK(c.chosen().candidate.name == "OPENCV5");
    check_near_truth(c.chosen().camera.intrinsics, truth.intrinsics);
    CHECK(libcam < c.noise_px);
    CHECK(libcam <= opencv);
}

TEST_CASE("Calibrate: a chessboard through a fisheye gives FISHEYE, nearer the truth than OpenCV's fisheye",
          "[sweep][calibrate][fit]") {
    const ChessboardRun run = run_chessboard_set(fisheye_truth(), fisheye_poses(), true);
    INFO(run.describe_it());
    CHECK(run.calibration.rejected.empty());
    CHECK(run.calibration.chosen().candidate.name == "FISHEYE");
    CHECK(run.libcam < run.calibration.noise_px);
    CHECK(run.libcam <= run.opencv);
    CHECK(run.libcam <= run.opencv_on_ours * 1.001);
}

// OpenCV's sample images of the left camera, as its calibration sample's list names them
// (the folder is absent: an empty list).
std::vector<std::filesystem::path> opencv_left_images() {
    const std::filesystem::path folder = std::filesystem::path(LIBCAM_REAL_DATA) / "opencv-stereo-samples";
    std::vector<std::filesystem::path> images;
    if (!std::filesystem::is_directory(folder)) return images;
    for (const char* name : {"01", "02", "03", "04", "05", "06", "07", "08", "09", "11", "12", "13", "14"}) {
        images.push_back(folder / ("left" + std::string(name) + ".jpg"));
    }
    return images;
}

// calibrateCamera's problem: OPENCV5, every corner kept (no outlier dropped).
CalibrationOptions as_calibrate_camera() {
    CalibrationOptions options;
    options.candidates = {candidate_named("OPENCV5")};
    options.outlier_sigmas = std::numeric_limits<double>::infinity();
    return options;
}

// A calibration's corners as calibrateCamera takes them.
struct OpenCvPoints {
    std::vector<std::vector<cv::Point3f>> object;
    std::vector<std::vector<cv::Point2f>> image;
};
OpenCvPoints opencv_points(const Calibration& c) {
    OpenCvPoints out;
    const std::vector<Vec3> corners = c.board.corner_points();
    for (const CalibrationView& view : c.views) {
        out.object.emplace_back();
        out.image.emplace_back();
        for (std::size_t k = 0; k < view.ids.size(); ++k) {
            const Vec3& p = corners[static_cast<std::size_t>(view.ids[k])];
            out.object.back().emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), 0.0f);
            out.image.back().emplace_back(static_cast<float>(view.pixels[k].x()), static_cast<float>(view.pixels[k].y()));
        }
    }
    return out;
}

TEST_CASE("Calibrate OpenCV's sample images: OpenCV's model, against calibrateCamera and OpenCV's stored calibration",
          "[calibrate][real]") {
    const std::vector<std::filesystem::path> images = opencv_left_images();
    if (images.empty()) {
        WARN("skipped: no folder opencv-stereo-samples in " LIBCAM_REAL_DATA);
        return;
    }
    const BoardSpec board = parse_board_spec("chessboard:9x6:0.025");
    const std::vector<BoardDetection> found = detect_boards(images, board, 0);
    CalibrationOptions options = as_calibrate_camera();
    const Calibration c = calibrate(found, board, options);
    REQUIRE(c.views.size() == 13);
    REQUIRE(c.corners() == 13 * 54);

    // cv::calibrateCamera on the same corners, OPENCV5 with fx and fy free: the same
    // problem, solved by OpenCV.
    const OpenCvPoints points = opencv_points(c);
    const auto& object_points = points.object;
    const auto& image_points = points.image;
    cv::Mat K, dist;
    std::vector<cv::Mat> rvecs, tvecs;
    const double opencv_rms = cv::calibrateCamera(object_points, image_points, cv::Size(640, 480), K, dist, rvecs, tvecs);
    const Camera& ours = c.chosen().camera;
    INFO("libcam: fx " << ours.intrinsics.fx << " fy " << ours.intrinsics.fy << " cx " << ours.intrinsics.cx << " cy "
                       << ours.intrinsics.cy << " rms " << c.chosen().rms_px << "; OpenCV: " << K << " " << dist
                       << " rms " << opencv_rms);
    CHECK(c.chosen().rms_px == Approx(opencv_rms).epsilon(1e-4));
    CHECK(std::abs(ours.intrinsics.fx - K.at<double>(0, 0)) < 0.01);
    CHECK(std::abs(ours.intrinsics.fy - K.at<double>(1, 1)) < 0.01);
    CHECK(std::abs(ours.intrinsics.cx - K.at<double>(0, 2)) < 0.01);
    CHECK(std::abs(ours.intrinsics.cy - K.at<double>(1, 2)) < 0.01);
    for (int i = 0; i < 5; ++i) CHECK(std::abs(ours.lens.coefficients[static_cast<std::size_t>(i)] - dist.at<double>(i)) < 1e-4);

    // OpenCV's stored calibration (its sample: findChessboardCorners + cornerSubPix corners,
    // fx = fy held equal): fx 535.9157, cx 342.2832, cy 235.5708, RMS 0.3926. The corners
    // differ (findChessboardCornersSB's, more accurate: the RMS is lower) and so does the
    // aspect ratio's freedom: K agrees to 1% in focal length and 3 px in the principal point.
    CHECK(std::abs(ours.intrinsics.fx / 535.9157 - 1.0) < 0.01);
    CHECK(std::abs(ours.intrinsics.fy / 535.9157 - 1.0) < 0.01);
    CHECK(std::abs(ours.intrinsics.cx - 342.2832) < 3.0);
    CHECK(std::abs(ours.intrinsics.cy - 235.5708) < 3.0);
    CHECK(c.chosen().rms_px < 0.3926);
}


namespace {

// OpenCV's calibration sample's output (left_intrinsics.yml): K, the distortion, each
// view's pose and its RMS.
struct StoredCalibration {
    cv::Mat K, dist, extrinsics;
    double rms = 0.0;
    int flags = 0;
};
StoredCalibration stored_left_calibration() {
    const std::string path = std::string(LIBCAM_REAL_DATA) + "/opencv-stereo-samples/left_intrinsics.yml";
    cv::FileStorage file(path, cv::FileStorage::READ);
    REQUIRE(file.isOpened());
    StoredCalibration out;
    file["camera_matrix"] >> out.K;
    file["distortion_coefficients"] >> out.dist;
    file["extrinsic_parameters"] >> out.extrinsics;
    file["avg_reprojection_error"] >> out.rms;
    file["flags"] >> out.flags;
    return out;
}

// The RMS of the corners' distances from where the stored calibration projects the board.
double rms_under(const StoredCalibration& stored, const OpenCvPoints& points) {
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t v = 0; v < points.image.size(); ++v) {
        const cv::Mat pose = stored.extrinsics.row(static_cast<int>(v));
        std::vector<cv::Point2f> projected;
        cv::projectPoints(points.object[v], pose.colRange(0, 3), pose.colRange(3, 6), stored.K, stored.dist, projected);
        for (std::size_t k = 0; k < projected.size(); ++k) {
            const cv::Point2f d = projected[k] - points.image[v][k];
            sum += d.x * d.x + d.y * d.y;
            ++count;
        }
    }
    return std::sqrt(sum / static_cast<double>(count));
}

}  // namespace

TEST_CASE("Calibrate OpenCV's sample images with OpenCV's flags: its stored calibration reproduced",
          "[calibrate][real]") {
    const std::vector<std::filesystem::path> images = opencv_left_images();
    if (images.empty()) {
        WARN("skipped: no folder opencv-stereo-samples in " LIBCAM_REAL_DATA);
        return;
    }
    const StoredCalibration stored = stored_left_calibration();
    REQUIRE(stored.flags == cv::CALIB_FIX_ASPECT_RATIO);
    const BoardSpec board = parse_board_spec("chessboard:9x6:0.025");
    const std::vector<BoardDetection> found = detect_boards(images, board, 0, {}, CornerMethod::OpenCvSample);
    CalibrationOptions options = as_calibrate_camera();
    options.held = held_by_opencv_flags(std::to_string(stored.flags));
    const Calibration c = calibrate(found, board, options);
    REQUIRE(c.views.size() == 13);
    REQUIRE(c.corners() == 13 * 54);
    const OpenCvPoints points = opencv_points(c);

    // The same corners as OpenCV's sample found: under OpenCV's stored calibration (its K,
    // distortion and each view's pose) their RMS is the one it stored for its own corners.
    const double corners_rms = rms_under(stored, points);
    INFO("the corners under OpenCV's stored calibration: RMS " << corners_rms << " px, stored " << stored.rms);
    CHECK(std::abs(corners_rms / stored.rms - 1.0) < 1e-3);

    // libcam's fit with fx = fy against OpenCV's standard deviations (calibrateCameraExtended
    // on the same corners with the stored flags) and its stored numbers.
    cv::Mat K = cv::Mat::eye(3, 3, CV_64F), dist, deviations, pose_deviations, view_errors;
    std::vector<cv::Mat> rvecs, tvecs;
    const double opencv_rms = cv::calibrateCamera(points.object, points.image, cv::Size(640, 480), K, dist, rvecs,
                                                          tvecs, deviations, pose_deviations, view_errors, stored.flags);
    const Camera& ours = c.chosen().camera;
    const Intrinsics& k = ours.intrinsics;
    INFO("libcam: fx " << k.fx << " fy " << k.fy << " cx " << k.cx << " cy " << k.cy << " dist "
                       << Eigen::Map<const Eigen::VectorXd>(ours.lens.coefficients.data(), 5).transpose() << " rms "
                       << c.chosen().rms_px << "; OpenCV now: " << K << " " << dist.t() << " rms " << opencv_rms
                       << " std " << deviations.rowRange(0, 9).t() << "; stored: " << stored.K << " " << stored.dist.t());
    CHECK(k.fx == k.fy);
    const double ours_k[4] = {k.fx, k.fy, k.cx, k.cy};
    const int where[4][2] = {{0, 0}, {1, 1}, {0, 2}, {1, 2}};
    for (int i = 0; i < 4; ++i) {
        // OpenCV reports fx's deviation as 0 (it holds fx / fy): fx is fy, with fy's.
        const double deviation = deviations.at<double>(i == 0 ? 1 : i);
        CHECK(std::abs(ours_k[i] - K.at<double>(where[i][0], where[i][1])) < deviation);
        CHECK(std::abs(ours_k[i] - stored.K.at<double>(where[i][0], where[i][1])) < deviation);
    }
    for (int i = 0; i < 5; ++i) {
        const double deviation = deviations.at<double>(4 + i);
        CHECK(std::abs(ours.lens.coefficients[static_cast<std::size_t>(i)] - dist.at<double>(i)) < deviation);
        CHECK(std::abs(ours.lens.coefficients[static_cast<std::size_t>(i)] - stored.dist.at<double>(i)) < deviation);
    }
    CHECK(std::abs(c.chosen().rms_px / stored.rms - 1.0) < 0.01);

    // The fx = fy fit's own standard deviations against OpenCV's: the same linearisation,
    // the noise estimated differently. libcam's (mrcal's) per coordinate: S / 2N over the N
    // corners' 2N residuals (S their sum of squares); OpenCV's S / (N - p), p the free
    // parameters (8 intrinsics, 6 per view): its deviations are sqrt(2N / (N - p)) times
    // libcam's, 1.51 here.
    const std::vector<ParameterSpread> spread = c.uncertainty[*c.fit.chosen].parameters;
    REQUIRE(spread.size() == 9);
    CHECK(spread[0].stdev == Approx(spread[1].stdev).epsilon(1e-9));
    const double corners = static_cast<double>(c.corners());
    const double opencv_scale = std::sqrt(2.0 * corners / (corners - (8.0 + 6.0 * 13.0)));
    for (int i = 1; i < 9; ++i) {
        const ParameterSpread& p = spread[static_cast<std::size_t>(i)];
        INFO(p.name << ": libcam " << p.stdev << ", OpenCV " << deviations.at<double>(i));
        CHECK(p.stdev * opencv_scale == Approx(deviations.at<double>(i)).epsilon(0.01));
    }
}

TEST_CASE("Calibrate with OpenCV's flags: p1 p2 and k3 held at 0 as calibrateCamera holds them", "[calibrate][real]") {
    const std::vector<std::filesystem::path> images = opencv_left_images();
    if (images.empty()) {
        WARN("skipped: no folder opencv-stereo-samples in " LIBCAM_REAL_DATA);
        return;
    }
    const BoardSpec board = parse_board_spec("chessboard:9x6:0.025");
    const std::vector<BoardDetection> found = detect_boards(images, board, 0);
    CalibrationOptions options = as_calibrate_camera();
    options.held = held_by_opencv_flags("CALIB_FIX_ASPECT_RATIO, zero_tangent_dist,FIX_K3");
    const Calibration c = calibrate(found, board, options);
    const OpenCvPoints points = opencv_points(c);
    cv::Mat K = cv::Mat::eye(3, 3, CV_64F), dist;
    std::vector<cv::Mat> rvecs, tvecs;
    const double opencv_rms =
        cv::calibrateCamera(points.object, points.image, cv::Size(640, 480), K, dist, rvecs, tvecs,
                            cv::CALIB_FIX_ASPECT_RATIO | cv::CALIB_ZERO_TANGENT_DIST | cv::CALIB_FIX_K3);
    const Camera& ours = c.chosen().camera;
    INFO("libcam: " << ours.intrinsics.fx << " " << ours.intrinsics.cx << " " << ours.intrinsics.cy << " rms "
                    << c.chosen().rms_px << "; OpenCV: " << K << " " << dist.t() << " rms " << opencv_rms);
    CHECK(ours.intrinsics.fx == ours.intrinsics.fy);
    CHECK(ours.lens.coefficients[2] == 0.0);
    CHECK(ours.lens.coefficients[3] == 0.0);
    CHECK(ours.lens.coefficients[4] == 0.0);
    CHECK(c.chosen().rms_px == Approx(opencv_rms).epsilon(1e-4));
    CHECK(std::abs(ours.intrinsics.fx - K.at<double>(0, 0)) < 0.01);
    CHECK(std::abs(ours.intrinsics.cx - K.at<double>(0, 2)) < 0.01);
    CHECK(std::abs(ours.intrinsics.cy - K.at<double>(1, 2)) < 0.01);
    for (int i = 0; i < 2; ++i) CHECK(std::abs(ours.lens.coefficients[static_cast<std::size_t>(i)] - dist.at<double>(i)) < 1e-4);
}

TEST_CASE("Calibrate: a ChArUco solve kept as mrcal's reads back whole, its board one square in, views partial",
          "[calibrate][mrcal]") {
    // Corners projected through the OPENCV5 truth (no images: the solve's form is under
    // test), 0.1 px of noise, some corners of each view unseen as on a partial ChArUco view.
    const BoardSpec board = parse_board_spec("charuco:10x8:0.03:0.022:DICT_4X4_50");
    Camera truth = opencv5_truth();
    std::mt19937 random(11);
    std::normal_distribution<double> noise(0.0, 0.1);
    std::vector<BoardDetection> detections;
    const std::vector<PoseSpec> poses = opencv5_poses();
    for (std::size_t v = 0; v < poses.size(); ++v) {
        truth.pose = board_pose(board, poses[v].centre, poses[v].tilt);
        const std::vector<Vec2> corners = true_corners(truth, board);
        BoardDetection detection{"view" + std::to_string(v) + ".png", truth.size, {}, {}, ""};
        for (std::size_t k = 0; k < corners.size(); ++k) {
            if ((k + v) % 9 == 0) continue;
            detection.ids.push_back(static_cast<int>(k));
            detection.pixels.push_back(corners[k] + Vec2(noise(random), noise(random)));
        }
        detections.push_back(std::move(detection));
    }
    CalibrationOptions options;
    options.candidates = {candidate_named("OPENCV5")};
    options.folds = 2;
    const Calibration c = calibrate(detections, board, options);

    const TempDir dir;
    const std::filesystem::path model = dir.path() / "charuco.cameramodel";
    write_file_atomically(model, format_cameramodel(c.chosen().camera, mrcal_solve_inputs(c), 0));
    const ObservationSet set = read_observations(model);
    // mrcal's board: 9 x 7 inner corners from its first, which libcam's board puts one square in.
    REQUIRE(set.board.has_value());
    CHECK(set.board->width == 9);
    CHECK(set.board->height == 7);
    REQUIRE(set.views.size() == c.views.size());
    std::size_t inliers = 0;
    for (const Observation& o : set.observations) inliers += o.inlier ? 1 : 0;
    CHECK(inliers == c.corners());
    // Each view's corners land where the calibration put them: the board poses moved by
    // the square, the residuals the same.
    for (std::size_t v = 0; v < set.views.size(); ++v) {
        Camera camera = set.cameras[0].camera;
        camera.pose = set.views[v].pose;
        const PreparedCamera prepared(camera);
        const std::vector<double> errors = c.view_errors(v);
        std::size_t k = 0;
        for (const Observation& o : set.observations) {
            if (o.view != static_cast<int>(v) || !o.inlier) continue;
            const Vec2 projected = prepared.project(set.points[static_cast<std::size_t>(o.point)]).pixel;
            CHECK((projected - o.pixel).norm() == Approx(errors[k++]).margin(1e-9));
        }
        CHECK(k == errors.size());
    }
    // And its projection uncertainty is the calibration's own.
    const std::vector<Vec2> pixels{Vec2(319.5, 239.5), Vec2(100.0, 80.0)};
    const std::vector<double> expected = ProjectionUncertainty(c.solved(*c.fit.chosen)).sigma_px(pixels);
    const std::vector<double> got = ProjectionUncertainty(solved_calibration(set, 0)).sigma_px(pixels);
    for (std::size_t i = 0; i < pixels.size(); ++i) CHECK(got[i] == Approx(expected[i]).epsilon(1e-9));
}
