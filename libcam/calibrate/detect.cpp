#include "libcam/calibrate/detect.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <thread>

#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace libcam {

namespace {

static_assert(cv::aruco::DICT_4X4_50 == 0 && cv::aruco::DICT_5X5_100 == 5 && cv::aruco::DICT_ARUCO_ORIGINAL == 16 &&
                  cv::aruco::DICT_APRILTAG_36h11 == 20,
              "aruco_dictionaries() holds OpenCV 4.6's numbering");

std::string size_text(const BoardSpec& board) { return std::to_string(board.columns) + "x" + std::to_string(board.rows); }

// The half-width of the window cornerSubPix may search around each corner: `clear`
// squares (inside the corner's own squares, short of its neighbours and of a ChArUco
// board's markers). The scale in pixels per square is the smallest of the distances to
// the other corners found, each over its distance on the board in squares; corner k is
// at column k mod `across`, row k div `across`.
std::vector<int> refinement_windows(const std::vector<cv::Point2f>& corners, const std::vector<int>& ids, int across,
                                    double clear) {
    std::vector<int> windows;
    for (std::size_t a = 0; a < corners.size(); ++a) {
        double pixels_per_square = std::numeric_limits<double>::infinity();
        for (std::size_t b = 0; b < corners.size(); ++b) {
            if (a == b) continue;
            const double squares = std::hypot(ids[a] % across - ids[b] % across, ids[a] / across - ids[b] / across);
            const double pixels = std::hypot(corners[a].x - corners[b].x, corners[a].y - corners[b].y);
            pixels_per_square = std::min(pixels_per_square, pixels / squares);
        }
        const double window = std::isfinite(pixels_per_square) ? std::floor(clear * pixels_per_square) : 2.0;
        windows.push_back(static_cast<int>(std::clamp(window, 2.0, 12.0)));
    }
    return windows;
}

// Each corner again by cv::cornerSubPix from where the detector put it: the saddle point
// of the image's grey levels, in OpenCV's convention whatever the detector's own
// refinement did (OpenCV 4.6's ChArUco corners are moved by +0.5 px after refining). A
// corner the search moves further than its window was no saddle there: it is dropped.
void refine_corners(const cv::Mat& grey, const std::vector<int>& windows, std::vector<cv::Point2f>& corners,
                    std::vector<int>& ids) {
    std::vector<cv::Point2f> kept_corners;
    std::vector<int> kept_ids;
    const cv::TermCriteria until(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-4);
    for (std::size_t k = 0; k < corners.size(); ++k) {
        std::vector<cv::Point2f> point = {corners[k]};
        cv::cornerSubPix(grey, point, cv::Size(windows[k], windows[k]), cv::Size(-1, -1), until);
        if (std::hypot(point[0].x - corners[k].x, point[0].y - corners[k].y) > windows[k]) continue;
        kept_corners.push_back(point[0]);
        kept_ids.push_back(ids[k]);
    }
    corners = std::move(kept_corners);
    ids = std::move(kept_ids);
}

// A chessboard by OpenCV's sector-based detector (CALIB_CB_EXHAUSTIVE tries harder on a
// board seen steeply), its corners then refined by cornerSubPix in a window of 0.4 square
// around each. The sector detector's own sub-pixel corners are off the truth by 0.05 to
// 0.2 px on boards rendered through a known lens, enough to put a calibration four times
// further from the truth than OpenCV's calibration sample (findChessboardCorners +
// cornerSubPix) on the same images; the saddle point found by cornerSubPix is not.
void detect_chessboard(const cv::Mat& grey, const BoardSpec& board, BoardDetection& out) {
    std::vector<cv::Point2f> corners;
    const int flags = cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_EXHAUSTIVE | cv::CALIB_CB_ACCURACY;
    if (!cv::findChessboardCornersSB(grey, cv::Size(board.columns, board.rows), corners, flags)) {
        out.rejected = "no " + size_text(board) + " chessboard found (its inner corners, all of them, must be seen)";
        return;
    }
    std::vector<int> ids(corners.size());
    for (std::size_t k = 0; k < corners.size(); ++k) ids[k] = static_cast<int>(k);
    refine_corners(grey, refinement_windows(corners, ids, board.columns, 0.4), corners, ids);
    if (ids.size() != corners.size() || ids.size() != static_cast<std::size_t>(board.columns * board.rows)) {
        out.rejected = "the " + size_text(board) + " chessboard's corners are not all sharp enough to measure";
        return;
    }
    for (std::size_t k = 0; k < corners.size(); ++k) {
        out.ids.push_back(ids[k]);
        out.pixels.emplace_back(corners[k].x, corners[k].y);
    }
}

// OpenCV's calibration sample's corners (CornerMethod::OpenCvSample).
void detect_chessboard_as_opencv_sample(const cv::Mat& grey, const BoardSpec& board, BoardDetection& out) {
    std::vector<cv::Point2f> corners;
    const int flags = cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_FAST_CHECK | cv::CALIB_CB_NORMALIZE_IMAGE;
    if (!cv::findChessboardCorners(grey, cv::Size(board.columns, board.rows), corners, flags)) {
        out.rejected = "no " + size_text(board) + " chessboard found (its inner corners, all of them, must be seen)";
        return;
    }
    cv::cornerSubPix(grey, corners, cv::Size(11, 11), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.1));
    for (std::size_t k = 0; k < corners.size(); ++k) {
        out.ids.push_back(static_cast<int>(k));
        out.pixels.emplace_back(corners[k].x, corners[k].y);
    }
}

void detect_charuco(const cv::Mat& grey, const BoardSpec& board, BoardDetection& out) {
    const cv::Ptr<cv::aruco::Dictionary> dictionary = cv::aruco::getPredefinedDictionary(board.dictionary_id);
    const cv::Ptr<cv::aruco::CharucoBoard> charuco = cv::aruco::CharucoBoard::create(
        board.columns, board.rows, static_cast<float>(board.square), static_cast<float>(board.marker), dictionary);
    std::vector<std::vector<cv::Point2f>> marker_corners;
    std::vector<int> marker_ids;
    cv::aruco::detectMarkers(grey, dictionary, marker_corners, marker_ids);
    if (marker_ids.empty()) {
        out.rejected = "no marker of " + board.dictionary + " found";
        return;
    }
    std::vector<cv::Point2f> corners;
    std::vector<int> ids;
    cv::aruco::interpolateCornersCharuco(marker_corners, marker_ids, grey, charuco, corners, ids);
    // Short of the markers in the white squares: they start (square - marker) / 2 from the corner.
    const double clear = 0.8 * 0.5 * (board.square - board.marker) / board.square;
    refine_corners(grey, refinement_windows(corners, ids, board.columns - 1, clear), corners, ids);
    if (corners.size() < kMinCornersPerView) {
        out.rejected = std::to_string(corners.size()) + " corners of the " + size_text(board) +
                       " ChArUco board found, fewer than " + std::to_string(kMinCornersPerView);
        return;
    }
    for (std::size_t k = 0; k < corners.size(); ++k) {
        out.ids.push_back(ids[k]);
        out.pixels.emplace_back(corners[k].x, corners[k].y);
    }
}

BoardDetection detect_in(const cv::Mat& grey, const BoardSpec& board, CornerMethod method) {
    BoardDetection out;
    out.size = {grey.cols, grey.rows};
    try {
        if (board.kind == BoardKind::Chessboard && method == CornerMethod::OpenCvSample) {
            detect_chessboard_as_opencv_sample(grey, board, out);
        } else if (board.kind == BoardKind::Chessboard) {
            detect_chessboard(grey, board, out);
        } else {
            detect_charuco(grey, board, out);
        }
    } catch (const cv::Exception& error) {
        out.rejected = "OpenCV's detector failed: " + error.err;
    }
    if (!out.rejected.empty()) {
        out.ids.clear();
        out.pixels.clear();
    }
    return out;
}

}  // namespace

BoardDetection detect_board_in(const unsigned char* grey, const ImageSize& size, const BoardSpec& board,
                               CornerMethod method) {
    const cv::Mat image(static_cast<int>(size.height), static_cast<int>(size.width), CV_8UC1,
                        const_cast<unsigned char*>(grey));
    return detect_in(image, board, method);
}

BoardDetection detect_board(const std::filesystem::path& image, const BoardSpec& board, CornerMethod method) {
    cv::Mat grey;
    try {
        grey = cv::imread(image.string(), cv::IMREAD_GRAYSCALE);
    } catch (const cv::Exception&) {
        grey = cv::Mat();
    }
    BoardDetection out;
    if (grey.empty()) {
        out.image = image.string();
        out.rejected = "cannot be read as an image";
        return out;
    }
    out = detect_in(grey, board, method);
    out.image = image.string();
    return out;
}

std::vector<BoardDetection> detect_boards(const std::vector<std::filesystem::path>& images, const BoardSpec& board,
                                          int threads, const std::function<void(std::size_t)>& done,
                                          CornerMethod method) {
    std::vector<BoardDetection> out(images.size());
    const unsigned machine = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t workers =
        std::min<std::size_t>(images.size(), threads > 0 ? static_cast<std::size_t>(threads) : machine);
    std::atomic<std::size_t> next{0};
    std::size_t finished = 0;
    std::mutex report;
    const auto work = [&] {
        for (std::size_t i = next++; i < images.size(); i = next++) {
            out[i] = detect_board(images[i], board, method);
            const std::lock_guard<std::mutex> lock(report);
            ++finished;
            if (done) done(finished);
        }
    };
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < workers; ++t) pool.emplace_back(work);
    work();
    for (std::thread& thread : pool) thread.join();
    return out;
}

}  // namespace libcam
