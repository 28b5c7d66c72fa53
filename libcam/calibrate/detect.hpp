#pragma once
// The board's corners in each image, found with OpenCV: a chessboard by
// cv::findChessboardCornersSB, a ChArUco board by its markers (cv::aruco::detectMarkers)
// and the corners between them (cv::aruco::interpolateCornersCharuco), partial boards
// included. Images are read and searched in parallel.
//
// Pixels are OpenCV's: the centre of the top-left pixel at (0, 0). Every corner is
// refined by libcam on the image itself (cv::cornerSubPix, which measures in that
// convention), so the result does not depend on the convention a detector's own
// refinement used (OpenCV 4.6's interpolateCornersCharuco returns its corners half a
// pixel off it).

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "libcam/calibrate/board.hpp"
#include "libcam/geometry/image_size.hpp"

namespace libcam {

// The fewest corners a view must have to enter a calibration: six points pin down a
// board's pose (six unknowns) with room to spare for the intrinsics they share.
inline constexpr std::size_t kMinCornersPerView = 6;

// How a chessboard's corners are found. Libcam: cv::findChessboardCornersSB, each corner
// then refined by cv::cornerSubPix in a window of 0.4 square around it. OpenCvSample: as
// OpenCV's calibration sample finds them (cv::findChessboardCorners with its adaptive
// threshold, fast check and normalised image; cornerSubPix in an 11 x 11 window, 30
// iterations or a step under 0.1 px), so that its results can be reproduced: a window of
// fixed size reaches past the corner's own squares on small boards, which moves the
// corners (on OpenCV's 640 x 480 samples the calibration's RMS is twice libcam's).
// ChArUco boards are found one way.
enum class CornerMethod { Libcam, OpenCvSample };

struct BoardDetection {
    std::string image;  // the image's path as given
    ImageSize size;     // zero where it could not be read
    std::vector<int> ids;       // corner indices on the board (BoardSpec::corner_points)
    std::vector<Vec2> pixels;   // where each was seen
    std::string rejected;       // why the image cannot be used; empty when it can
};

// The corners of `board` in one image; never throws for a bad image (rejected says why).
BoardDetection detect_board(const std::filesystem::path& image, const BoardSpec& board,
                            CornerMethod method = CornerMethod::Libcam);

// The same for every image, on `threads` threads (0: as many as the machine has), in the
// images' order. `done` (optional) is called after each image, with the count so far,
// from whichever thread finished it, one call at a time.
std::vector<BoardDetection> detect_boards(const std::vector<std::filesystem::path>& images, const BoardSpec& board,
                                          int threads, const std::function<void(std::size_t)>& done = {},
                                          CornerMethod method = CornerMethod::Libcam);

// Detection on an image already in memory (8-bit grey, rows of `size.width` bytes):
// what the tests render.
BoardDetection detect_board_in(const unsigned char* grey, const ImageSize& size, const BoardSpec& board,
                               CornerMethod method = CornerMethod::Libcam);

}  // namespace libcam
