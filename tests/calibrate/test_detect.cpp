// The board's corners, found in images rendered through a known camera: where they are
// against the corners projected by the same camera, in OpenCV's pixel convention.

#include <catch2/catch.hpp>

#include <numeric>

#include "libcam/calibrate/detect.hpp"
#include "synthetic_sets.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

struct Offset {
    Vec2 mean = Vec2::Zero();
    double rms = 0.0;  // about the true corners
    std::size_t count = 0;
};

Offset offset_from_truth(const std::vector<int>& ids, const std::vector<Vec2>& pixels, const std::vector<Vec2>& truth) {
    Offset out;
    double sum = 0.0;
    for (std::size_t k = 0; k < ids.size(); ++k) {
        const Vec2 d = pixels[k] - truth[static_cast<std::size_t>(ids[k])];
        out.mean += d;
        sum += d.squaredNorm();
    }
    out.count = ids.size();
    out.mean /= static_cast<double>(ids.size());
    out.rms = std::sqrt(sum / static_cast<double>(ids.size()));
    return out;
}

Camera pinhole_640() {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {600.0, 600.0, 319.5, 239.5, 0.0};
    camera.lens = {LensType::Pinhole, {}};
    return camera;
}

}  // namespace

TEST_CASE("A chessboard's corners (findChessboardCornersSB) are where the camera puts them, in OpenCV's pixels",
          "[calibrate][detect]") {
    const BoardSpec board = parse_board_spec("chessboard:9x6:0.03");
    Camera camera = opencv5_truth();
    camera.pose = board_pose(board, {0.02, -0.01, 0.5}, {0.3, -0.25, 0.1});
    const cv::Mat image = render_board(camera, chessboard_texture(board));
    const BoardDetection found = detect_board_in(image.data, camera.size, board);
    REQUIRE(found.rejected.empty());
    REQUIRE(found.ids.size() == 54);
    // The detector may number the corners from either end: the board turned half a turn,
    // the same board to a calibration. The numbering is the one nearer the truth.
    const std::vector<Vec2> truth = true_corners(camera, board);
    const std::vector<Vec2> turned(truth.rbegin(), truth.rend());
    const Offset as_numbered = offset_from_truth(found.ids, found.pixels, truth);
    const Offset offset = as_numbered.rms < 1.0 ? as_numbered : offset_from_truth(found.ids, found.pixels, turned);
    INFO("mean offset " << offset.mean.transpose() << ", rms " << offset.rms);
    // A half-pixel convention error would show as a mean offset of 0.5 px on each axis;
    // blur and noise leave the corners scattered by about 0.05 px.
    CHECK(offset.mean.norm() < 0.05);
    CHECK(offset.rms < 0.15);
}

TEST_CASE("ChArUco corners: OpenCV 4.6's interpolateCornersCharuco is half a pixel off, libcam's corners are not",
          "[calibrate][detect]") {
    const BoardSpec board = parse_board_spec("charuco:8x6:0.04:0.03:DICT_5X5_100");
    Camera camera = pinhole_640();
    camera.pose = board_pose(board, {0.0, 0.0, 0.55}, {0.25, -0.2, 0.05});
    const cv::Mat image = render_board(camera, charuco_texture(board));
    const std::vector<Vec2> truth = true_corners(camera, board);

    // OpenCV's own corners, as its detector returns them.
    const cv::Ptr<cv::aruco::Dictionary> dictionary = cv::aruco::getPredefinedDictionary(board.dictionary_id);
    const cv::Ptr<cv::aruco::CharucoBoard> charuco = cv::aruco::CharucoBoard::create(8, 6, 0.04f, 0.03f, dictionary);
    std::vector<std::vector<cv::Point2f>> marker_corners;
    std::vector<int> marker_ids, ids;
    std::vector<cv::Point2f> corners;
    cv::aruco::detectMarkers(image, dictionary, marker_corners, marker_ids);
    cv::aruco::interpolateCornersCharuco(marker_corners, marker_ids, image, charuco, corners, ids);
    REQUIRE(ids.size() == 35);
    std::vector<Vec2> opencv_pixels;
    for (const cv::Point2f& p : corners) opencv_pixels.emplace_back(p.x, p.y);
    const Offset opencv = offset_from_truth(ids, opencv_pixels, truth);

    const BoardDetection found = detect_board_in(image.data, camera.size, board);
    REQUIRE(found.rejected.empty());
    REQUIRE(found.ids.size() == 35);
    const Offset libcam = offset_from_truth(found.ids, found.pixels, truth);
    INFO("OpenCV's mean offset " << opencv.mean.transpose() << " (rms " << opencv.rms << "); libcam's "
                                 << libcam.mean.transpose() << " (rms " << libcam.rms << ")");
    // The detector's shift (this OpenCV's): half a pixel on each axis, give or take the noise.
    CHECK(std::abs(opencv.mean.x() - 0.5) < 0.1);
    CHECK(std::abs(opencv.mean.y() - 0.5) < 0.1);
    CHECK(libcam.mean.norm() < 0.05);
    CHECK(libcam.rms < 0.15);
}

TEST_CASE("ChArUco: a board partly outside the image gives the corners seen, each where it should be",
          "[calibrate][detect]") {
    const BoardSpec board = parse_board_spec("charuco:8x6:0.04:0.03:DICT_5X5_100");
    Camera camera = pinhole_640();
    camera.pose = board_pose(board, {0.2, 0.05, 0.45}, {0.1, 0.2, 0.0});
    const cv::Mat image = render_board(camera, charuco_texture(board));
    const BoardDetection found = detect_board_in(image.data, camera.size, board);
    REQUIRE(found.rejected.empty());
    CHECK(found.ids.size() >= kMinCornersPerView);
    CHECK(found.ids.size() < 35);
    const Offset offset = offset_from_truth(found.ids, found.pixels, true_corners(camera, board));
    INFO(found.ids.size() << " corners, mean offset " << offset.mean.transpose() << ", rms " << offset.rms);
    CHECK(offset.mean.norm() < 0.08);
    CHECK(offset.rms < 0.2);
}

TEST_CASE("Images without a usable board are rejected with the reason", "[calibrate][detect]") {
    const BoardSpec chessboard = parse_board_spec("chessboard:9x6:0.03");
    const cv::Mat blank(480, 640, CV_8UC1, cv::Scalar(128));
    CHECK(detect_board_in(blank.data, {640, 480}, chessboard).rejected ==
          "no 9x6 chessboard found (its inner corners, all of them, must be seen)");
    const BoardSpec charuco = parse_board_spec("charuco:8x6:0.04:0.03:DICT_5X5_100");
    CHECK(detect_board_in(blank.data, {640, 480}, charuco).rejected == "no marker of DICT_5X5_100 found");
    CHECK(detect_board("/nonexistent/board.png", chessboard).rejected == "cannot be read as an image");
}
