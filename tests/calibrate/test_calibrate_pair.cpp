// A stereo pair calibrated from board images rendered through two known lenses at a known
// pose from each other: the pair's R and T against the truth and against
// cv::stereoCalibrate on the same corners.

#include <catch2/catch.hpp>

#include <opencv2/calib3d.hpp>

#include "libcam/calibrate/calibrate_pair.hpp"
#include "libcam/calibrate/pair_list.hpp"
#include "libcam/error.hpp"
#include "synthetic_sets.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

// The second camera: another OPENCV5 lens, 6 cm to the right of the first and turned a
// little (X_second = R X_first + T).
Camera second_truth() {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {515.0, 516.5, 318.2, 238.9, 0.0};
    camera.lens = {LensType::OpenCv5, {-0.28, 0.08, -0.0006, 0.0010, 0.12}};
    return camera;
}
const Pose kSecondFromFirst = Pose::from_rvec({0.012, -0.025, 0.006}, {-0.06, 0.0015, 0.0008});

struct RenderedPair {
    std::vector<BoardDetection> first, second;
};

// The views of opencv5_poses() (the board's pose in the first camera) seen by both cameras.
RenderedPair render_pair(const BoardSpec& board) {
    const BoardTexture texture = chessboard_texture(board);
    RenderedPair out;
    unsigned seed = 11;
    for (const PoseSpec& spec : opencv5_poses()) {
        Camera first = opencv5_truth(), second = second_truth();
        first.pose = board_pose(board, spec.centre, spec.tilt);
        second.pose = kSecondFromFirst.after(first.pose);
        for (Camera* camera : {&first, &second}) {
            RenderOptions options;
            options.seed = seed++;
            const cv::Mat image = render_board(*camera, texture, options);
            BoardDetection found = detect_board_in(image.data, camera->size, board);
            found.image = (camera == &first ? "first" : "second") + std::to_string(seed) + ".png";
            (camera == &first ? out.first : out.second).push_back(std::move(found));
        }
    }
    return out;
}

std::vector<cv::Point2f> cv_pixels(const BoardDetection& found) {
    std::vector<cv::Point2f> out;
    for (const Vec2& p : found.pixels) out.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
    return out;
}

}  // namespace

TEST_CASE("Calibrate a pair rendered through two known lenses: R and T recovered, as near the truth as "
          "cv::stereoCalibrate",
          "[sweep][calibrate][pair]") {
    const BoardSpec board = parse_board_spec("chessboard:9x6:0.03");
    const RenderedPair rendered = render_pair(board);
    CalibrationOptions options;
    options.candidates = {candidate_named("OPENCV5")};
    options.outlier_sigmas = std::numeric_limits<double>::infinity();
    options.folds = 2;  // the choice of model is not under test here
    const PairCalibration pair = calibrate_pair(rendered.first, rendered.second, board, options);

    // cv::stereoCalibrate on the same corners of the views both cameras saw whole, from
    // each camera's calibrateCamera (OpenCV's stereo_calib sample's way, intrinsics free).
    std::vector<std::vector<cv::Point3f>> objects;
    std::vector<std::vector<cv::Point2f>> first_pixels, second_pixels;
    std::vector<cv::Point3f> corners;
    for (const Vec3& p : board.corner_points()) {
        corners.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
    }
    for (std::size_t i = 0; i < rendered.first.size(); ++i) {
        if (!rendered.first[i].rejected.empty() || !rendered.second[i].rejected.empty()) continue;
        objects.push_back(corners);
        first_pixels.push_back(cv_pixels(rendered.first[i]));
        second_pixels.push_back(cv_pixels(rendered.second[i]));
    }
    REQUIRE(pair.pairs.size() == objects.size());
    REQUIRE(objects.size() >= 5);
    const cv::Size size(640, 480);
    cv::Mat K1, D1, K2, D2, R, T, E, F;
    std::vector<cv::Mat> unused_r, unused_t;
    cv::calibrateCamera(objects, first_pixels, size, K1, D1, unused_r, unused_t);
    cv::calibrateCamera(objects, second_pixels, size, K2, D2, unused_r, unused_t);
    const double opencv_rms = cv::stereoCalibrate(objects, first_pixels, second_pixels, K1, D1, K2, D2, size, R, T, E, F,
                                                  cv::CALIB_USE_INTRINSIC_GUESS);
    cv::Mat opencv_rvec;
    cv::Rodrigues(R, opencv_rvec);
    const Vec3 opencv_r(opencv_rvec.at<double>(0), opencv_rvec.at<double>(1), opencv_rvec.at<double>(2));
    const Vec3 opencv_t(T.at<double>(0), T.at<double>(1), T.at<double>(2));

    const Pose& ours = pair.second_camera.pose;
    const double our_turn = (ours.rvec() - kSecondFromFirst.rvec()).norm();
    const double our_shift = (ours.t - kSecondFromFirst.t).norm();
    const double opencv_turn = (opencv_r - kSecondFromFirst.rvec()).norm();
    const double opencv_shift = (opencv_t - kSecondFromFirst.t).norm();
    INFO(pair.pairs.size() << " pairs; libcam rms " << pair.rms_px << ", from the truth: turn " << our_turn
                           << " rad, shift " << our_shift << " m; cv::stereoCalibrate rms " << opencv_rms << ": turn "
                           << opencv_turn << " rad, shift " << opencv_shift << " m");
    // Within the noise: corners found to about 0.05 px over a board 250 px across turn its
    // pose by about 1e-4 rad; the baseline is 6 cm.
    CHECK(our_turn < 1e-3);
    CHECK(our_shift < 6e-4);
    CHECK(our_turn <= 1.5 * opencv_turn + 1e-4);
    CHECK(our_shift <= 1.5 * opencv_shift + 1e-4);
    // The same problem as OpenCV's (both intrinsics, R, T, a board pose per view): the same RMS.
    CHECK(pair.rms_px == Approx(opencv_rms).epsilon(1e-4));
    CHECK(std::abs(pair.second_camera.intrinsics.fx - 515.0) < 2.0);
    CHECK(std::abs(pair.first_camera.intrinsics.fx - 520.0) < 2.0);
}

TEST_CASE("Calibrate a pair refuses image lists of different lengths in one line", "[calibrate][pair]") {
    const BoardSpec board = parse_board_spec("chessboard:9x6:0.03");
    std::vector<BoardDetection> two(2), three(3);
    CHECK_THROWS_WITH(calibrate_pair(two, three, board, CalibrationOptions{}),
                      "calibrate: 2 images of the first camera and 3 of the second: a pair needs one of each per view");
}

TEST_CASE("A pair's image list as OpenCV's stereo_calib reads it: left and right in turn, beside the list",
          "[calibrate][pair]") {
    // stereo_calib.xml's form, as OpenCV's sample ships it.
    const std::string xml = "<?xml version=\"1.0\"?>\n<opencv_storage>\n<imagelist>\n\"left01.jpg\"\n\"right01.jpg\"\n"
                            "\"left02.jpg\"\n\"/data/right02.jpg\"\n</imagelist>\n</opencv_storage>\n";
    const PairList list = parse_pair_list(xml, "/data/pairs/stereo_calib.xml");
    REQUIRE(list.left.size() == 2);
    REQUIRE(list.right.size() == 2);
    CHECK(list.left[0] == std::filesystem::path("/data/pairs/left01.jpg"));
    CHECK(list.right[0] == std::filesystem::path("/data/pairs/right01.jpg"));
    CHECK(list.right[1] == std::filesystem::path("/data/right02.jpg"));
    const PairList yaml = parse_pair_list("%YAML:1.0\nimagelist:\n  - a.png\n  - b.png\n", "list.yml");
    CHECK(yaml.left == std::vector<std::filesystem::path>{"a.png"});
    CHECK_THROWS_WITH(parse_pair_list("%YAML:1.0\nimagelist:\n  - a.png\n", "list.yml"),
                      "list.yml: imagelist: 1 names, an odd count: the list holds left and right images in turn");
    CHECK_THROWS_WITH(parse_pair_list("%YAML:1.0\nimages:\n  - a.png\n", "list.yml"),
                      "list.yml: imagelist: missing, or not a list of image names");
    CHECK_THROWS_AS(parse_pair_list("<opencv_storage><imagelist>", "list.xml"), FileError);
}
