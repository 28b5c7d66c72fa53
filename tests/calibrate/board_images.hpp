#pragma once
// Board images rendered through a known camera, for the calibration tests: the board's
// picture (a texture, drawn here for a chessboard, by OpenCV's aruco module for ChArUco)
// is carried to each pixel by libcam's own unprojection and the board's plane, at twice
// the resolution, and averaged down (each pixel the mean of its four sub-pixels, whose
// centres sit at +-0.25 px around the pixel's centre). The true corners are the board's
// corners projected through the same camera: in OpenCV's convention, pixel centres at
// integers, the convention every step here keeps.

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "libcam/calibrate/board.hpp"
#include "libcam/camera/camera.hpp"

namespace libcam::test {

// A picture of a board: texture pixel (u, v) covers the board's square
// [origin + (u, v) / pixels_per_metre, origin + (u + 1, v + 1) / pixels_per_metre].
struct BoardTexture {
    cv::Mat image;  // 8-bit grey
    double pixels_per_metre = 0.0;
    Vec2 origin = Vec2::Zero();  // the board point at the texture's top-left pixel edge
};

// A chessboard of (C + 1) x (R + 1) squares around its C x R inner corners (corner (0, 0)
// at the board's origin), and a white margin of one square; `square_px` texture pixels
// per square.
inline BoardTexture chessboard_texture(const BoardSpec& board, int square_px = 40) {
    const int squares_x = board.columns + 1, squares_y = board.rows + 1;
    BoardTexture texture;
    texture.image = cv::Mat((squares_y + 2) * square_px, (squares_x + 2) * square_px, CV_8UC1, cv::Scalar(255));
    for (int y = 0; y < squares_y; ++y) {
        for (int x = 0; x < squares_x; ++x) {
            if ((x + y) % 2 == 0) {
                texture.image(cv::Rect((x + 1) * square_px, (y + 1) * square_px, square_px, square_px)).setTo(20);
            }
        }
    }
    texture.pixels_per_metre = square_px / board.square;
    texture.origin = Vec2(-2 * board.square, -2 * board.square);
    return texture;
}

// OpenCV's own drawing of the ChArUco board (CharucoBoard::draw), with a margin of one
// square; the board's origin at its top-left square's outer corner.
inline BoardTexture charuco_texture(const BoardSpec& board, int square_px = 60) {
    const cv::Ptr<cv::aruco::CharucoBoard> charuco = cv::aruco::CharucoBoard::create(
        board.columns, board.rows, static_cast<float>(board.square), static_cast<float>(board.marker),
        cv::aruco::getPredefinedDictionary(board.dictionary_id));
    BoardTexture texture;
    charuco->draw(cv::Size((board.columns + 2) * square_px, (board.rows + 2) * square_px), texture.image, square_px, 1);
    texture.pixels_per_metre = square_px / board.square;
    texture.origin = Vec2(-board.square, -board.square);
    return texture;
}

struct RenderOptions {
    double blur_sigma_px = 0.7;
    double noise_sigma = 2.0;  // grey levels
    unsigned seed = 1;
};

// The board at `camera.pose` (board to camera), seen through `camera`; grey 128 where the
// board is not.
inline cv::Mat render_board(const Camera& camera, const BoardTexture& texture, const RenderOptions& options = {}) {
    Camera at_origin = camera;
    at_origin.pose = Pose{};
    const PreparedCamera prepared(at_origin);
    const Mat3 Rt = camera.pose.R.transpose();
    const Vec3 centre_on_board = -(Rt * camera.pose.t);  // the camera centre in the board's frame
    const int width = static_cast<int>(2 * camera.size.width), height = static_cast<int>(2 * camera.size.height);
    cv::Mat map_x(height, width, CV_32FC1), map_y(height, width, CV_32FC1);
    for (int v = 0; v < height; ++v) {
        for (int u = 0; u < width; ++u) {
            map_x.at<float>(v, u) = -1e6f;
            map_y.at<float>(v, u) = -1e6f;
            // This sub-pixel's centre in the image's pixels: sub-pixel u spans [u/2 - 0.5, u/2].
            const Unprojection ray = prepared.unproject(Vec2(0.5 * u - 0.25, 0.5 * v - 0.25));
            if (!ray.valid) continue;
            const Vec3 direction = Rt * ray.direction;
            const double along = -centre_on_board.z() / direction.z();
            if (!(along > 0.0)) continue;
            const Vec3 point = centre_on_board + along * direction;
            // The texture's pixel centres at integers, as cv::remap takes them.
            map_x.at<float>(v, u) = static_cast<float>((point.x() - texture.origin.x()) * texture.pixels_per_metre - 0.5);
            map_y.at<float>(v, u) = static_cast<float>((point.y() - texture.origin.y()) * texture.pixels_per_metre - 0.5);
        }
    }
    cv::Mat fine, image;
    cv::remap(texture.image, fine, map_x, map_y, cv::INTER_LINEAR,
              cv::BORDER_CONSTANT, cv::Scalar(128));
    cv::resize(fine, image, cv::Size(static_cast<int>(camera.size.width), static_cast<int>(camera.size.height)), 0, 0,
               cv::INTER_AREA);
    if (options.blur_sigma_px > 0) cv::GaussianBlur(image, image, cv::Size(0, 0), options.blur_sigma_px);
    cv::Mat noise(image.size(), CV_32FC1);
    cv::RNG rng(options.seed);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, options.noise_sigma);
    cv::Mat noisy;
    image.convertTo(noisy, CV_32FC1);
    noisy += noise;
    noisy.convertTo(image, CV_8UC1);  // rounded and clipped to 0..255
    return image;
}

// The board's corners through the camera (board to camera: camera.pose), by corner index.
inline std::vector<Vec2> true_corners(const Camera& camera, const BoardSpec& board) {
    const PreparedCamera prepared(camera);
    std::vector<Vec2> out;
    for (const Vec3& p : board.corner_points()) out.push_back(prepared.project(p).pixel);
    return out;
}

// A board pose: the board's centre at `centre` (camera frame, metres), turned by `tilt`
// (a Rodrigues vector) about that centre.
inline Pose board_pose(const BoardSpec& board, const Vec3& centre, const Vec3& tilt) {
    const int inset = board.kind == BoardKind::Charuco ? 0 : 1;
    const Vec3 middle(0.5 * (board.columns - inset) * board.square, 0.5 * (board.rows - inset) * board.square, 0.0);
    const Mat3 R = rotation_from_rvec(tilt);
    return {R, centre - R * middle};
}

}  // namespace libcam::test
