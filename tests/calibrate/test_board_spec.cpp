// --board SPEC: what a spec holds, where each corner sits on the board (against OpenCV's
// own board), and the one-line refusals.

#include <catch2/catch.hpp>

#include <opencv2/aruco/charuco.hpp>

#include "libcam/calibrate/board.hpp"
#include "libcam/error.hpp"

using namespace libcam;
using Catch::Matchers::Equals;

TEST_CASE("A chessboard spec: C x R inner corners, corner (i, j) at (i s, j s, 0)", "[calibrate][board]") {
    const BoardSpec board = parse_board_spec("chessboard:9x6:0.025");
    CHECK(board.kind == BoardKind::Chessboard);
    CHECK(board.columns == 9);
    CHECK(board.rows == 6);
    CHECK(board.square == 0.025);
    REQUIRE(board.corner_count() == 54);
    const std::vector<Vec3> corners = board.corner_points();
    CHECK(corners[10] == Vec3(0.025, 0.025, 0.0));  // column 1, row 1
    CHECK(corners[53] == Vec3(8 * 0.025, 5 * 0.025, 0.0));
    CHECK(board.text() == "chessboard:9x6:0.025");
}

TEST_CASE("A ChArUco spec: its corners are OpenCV 4.6's chessboardCorners", "[calibrate][board]") {
    const BoardSpec board = parse_board_spec("charuco:7x5:0.04:0.031:DICT_4X4_50");
    CHECK(board.kind == BoardKind::Charuco);
    CHECK(board.marker == 0.031);
    CHECK(board.dictionary == "DICT_4X4_50");
    const cv::Ptr<cv::aruco::CharucoBoard> opencv = cv::aruco::CharucoBoard::create(
        7, 5, 0.04f, 0.031f, cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50));
    const std::vector<Vec3> corners = board.corner_points();
    REQUIRE(corners.size() == opencv->chessboardCorners.size());
    for (std::size_t k = 0; k < corners.size(); ++k) {
        const cv::Point3f& p = opencv->chessboardCorners[k];
        CHECK(std::abs(corners[k].x() - p.x) < 1e-6);
        CHECK(std::abs(corners[k].y() - p.y) < 1e-6);
        CHECK(corners[k].z() == p.z);
    }
    CHECK(board.text() == "charuco:7x5:0.04:0.031:DICT_4X4_50");
}

TEST_CASE("Board specs that do not parse: one line naming the spec and the part", "[calibrate][board]") {
    const auto message = [](const std::string& spec) {
        try {
            parse_board_spec(spec);
        } catch (const InvalidArgument& error) {
            return std::string(error.what());
        }
        return std::string("(accepted)");
    };
    CHECK_THAT(message("circles:4x11:0.02"), Equals("board 'circles:4x11:0.02': kind: expected chessboard or charuco, got 'circles'"));
    CHECK_THAT(message("chessboard:9x6"),
               Equals("board 'chessboard:9x6': form: expected chessboard:CxR:SQUARE (inner corners, square side in "
                      "metres), got 2 parts"));
    CHECK_THAT(message("chessboard:9by6:0.03"),
               Equals("board 'chessboard:9by6:0.03': size: expected COLUMNSxROWS (9x6), got '9by6'"));
    CHECK_THAT(message("chessboard:2x6:0.03"),
               Equals("board 'chessboard:2x6:0.03': size: expected a whole number from 3 to 1000, got '2'"));
    CHECK_THAT(message("chessboard:9x6:-1"),
               Equals("board 'chessboard:9x6:-1': square: expected a length in metres above 0, got '-1'"));
    CHECK_THAT(message("chessboard:9x6:nan"),
               Equals("board 'chessboard:9x6:nan': square: expected a length in metres above 0, got 'nan'"));
    CHECK_THAT(message("charuco:5x7:0.04:0.05:DICT_5X5_100"),
               Equals("board 'charuco:5x7:0.04:0.05:DICT_5X5_100': marker: a marker (0.05 m) must be smaller than its "
                      "square (0.04 m)"));
    CHECK_THAT(message("charuco:5x7:0.04:0.03:DICT_5X5"),
               Catch::Matchers::StartsWith("board 'charuco:5x7:0.04:0.03:DICT_5X5': dictionary: 'DICT_5X5' is not one "
                                           "of OpenCV's: DICT_4X4_50, "));
    CHECK_THAT(message("charuco:20x20:0.04:0.03:DICT_4X4_50"),
               Equals("board 'charuco:20x20:0.04:0.03:DICT_4X4_50': dictionary: DICT_4X4_50 holds 50 markers, a "
                      "20x20 board needs 200"));
    CHECK_THAT(message("chessboard:9x6:0.03\n"),
               Equals("board 'chessboard:9x6:0.03\\n': square: expected a length in metres above 0, got '0.03\\n'"));
}
