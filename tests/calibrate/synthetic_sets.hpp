#pragma once
// The synthetic calibration sets the tests share: a chessboard and a ChArUco board seen
// through an OPENCV5 lens, and a chessboard through a fisheye (T265-like: Kannala-Brandt,
// about 160 degrees across), at 640x480, in poses that spread the corners over the image.

#include <vector>

#include "board_images.hpp"

namespace libcam::test {

// A barrel lens whose k3 is strong enough that OPENCV4 cannot stand in for it.
inline Camera opencv5_truth() {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {520.0, 522.0, 322.3, 241.7, 0.0};
    camera.lens = {LensType::OpenCv5, {-0.30, 0.10, 0.0012, -0.0008, 0.10}};
    return camera;
}

// Intel RealSense T265's published fisheye coefficients, its focal length scaled from
// 848 to 640 pixels across.
inline Camera fisheye_truth() {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {215.0, 215.3, 318.6, 243.2, 0.0};
    camera.lens = {LensType::Fisheye, {-0.0066, 0.0419, -0.0397, 0.0075}};
    return camera;
}

struct PoseSpec {
    Vec3 centre;
    Vec3 tilt;
};

// Board poses for the OPENCV5 lens (f 520 px), as a careful calibration takes them: one
// facing the camera at the middle; four in the image's corners, near and turned 0.5 rad
// on both axes, so that the corners reach 380 px from the centre, where k3 shows; and
// four at the middle turned 0.5 to 0.7 rad, whose foreshortening pins the focal length
// against the radial coefficients. With the boards kept to the middle third of the image
// and turned 0.45 rad at most, a focal length 1% short (OPENCV4's) and a k1 to match it
// fitted the corners within 5% of the truth's model held out, and the truth's model's
// own focal length spread by 0.25% over redraws of the corners' noise.
inline std::vector<PoseSpec> opencv5_poses() {
    return {{{0.0, 0.0, 0.55}, {0.0, 0.0, 0.05}},
            {{-0.1248, -0.0936, 0.4}, {0.5, -0.5, 0.1}}, {{-0.1232, 0.0924, 0.4}, {-0.5, -0.5, -0.1}},
            {{0.1216, -0.0912, 0.4}, {0.5, 0.5, -0.1}},  {{0.12, 0.09, 0.4}, {-0.5, 0.5, 0.1}},
            {{0.0, 0.0, 0.45}, {0.65, 0.0, 0.0}},        {{0.0, 0.0, 0.45}, {0.0, 0.7, 0.0}},
            {{0.0, 0.0, 0.45}, {-0.5, -0.5, 0.2}},       {{0.0, 0.0, 0.45}, {0.5, -0.5, -0.3}}};
}

// The fisheye sees 160 degrees: the boards come closer and further out to the sides.
inline std::vector<PoseSpec> fisheye_poses() {
    return {{{0.0, 0.0, 0.25}, {0.0, 0.0, 0.05}},      {{-0.22, -0.1, 0.2}, {0.3, -0.7, 0.1}},
            {{0.22, -0.1, 0.2}, {0.3, 0.7, -0.1}},     {{-0.22, 0.1, 0.2}, {-0.3, -0.7, 0.05}},
            {{0.22, 0.1, 0.2}, {-0.3, 0.7, 0.0}},      {{0.0, -0.12, 0.2}, {0.7, 0.0, 0.1}},
            {{0.0, 0.15, 0.2}, {-0.8, 0.0, 0.0}},      {{-0.3, 0.0, 0.17}, {0.0, -0.9, 0.2}}};
}

struct SyntheticView {
    Pose pose;
    cv::Mat image;
};

// `whole_boards`: every corner must fall inside the image (a chessboard is found whole or
// not at all); a ChArUco board may run off the image's edges, as it does in a calibration
// that pushes the board into the image's corners.
inline std::vector<SyntheticView> render_views(const Camera& truth, const BoardSpec& board, const BoardTexture& texture,
                                               const std::vector<PoseSpec>& poses, const RenderOptions& options = {},
                                               bool whole_boards = true) {
    std::vector<SyntheticView> out;
    unsigned seed = options.seed;
    for (const PoseSpec& spec : poses) {
        Camera camera = truth;
        camera.pose = board_pose(board, spec.centre, spec.tilt);
        RenderOptions these = options;
        these.seed = seed++;
        out.push_back({camera.pose, render_board(camera, texture, these)});
        for (const Vec2& corner : true_corners(camera, board)) {
            if (!whole_boards) break;
            if (!(corner.x() > 5 && corner.y() > 5 && corner.x() < truth.size.width - 6 && corner.y() < truth.size.height - 6)) {
                throw std::logic_error("a test's board pose puts a corner outside the image");
            }
        }
    }
    return out;
}

}  // namespace libcam::test
