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

// Board centres and tilts for the OPENCV5 lens (f 520 px): the board fills a third of the
// image, at its middle, sides and corners, tilted up to 0.45 rad.
inline std::vector<PoseSpec> opencv5_poses() {
    return {{{0.0, 0.0, 0.55}, {0.0, 0.0, 0.05}},      {{-0.17, -0.11, 0.52}, {0.35, -0.3, 0.1}},
            {{0.17, -0.11, 0.52}, {0.3, 0.35, -0.1}},  {{-0.17, 0.11, 0.52}, {-0.35, -0.3, 0.05}},
            {{0.17, 0.11, 0.52}, {-0.3, 0.35, 0.0}},   {{0.0, -0.13, 0.5}, {0.45, 0.0, 0.0}},
            {{0.17, 0.0, 0.52}, {0.0, 0.35, 0.0}},     {{-0.19, 0.02, 0.5}, {-0.2, -0.2, -0.3}},
            {{0.0, 0.13, 0.5}, {-0.4, 0.1, 0.1}}};
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

inline std::vector<SyntheticView> render_views(const Camera& truth, const BoardSpec& board, const BoardTexture& texture,
                                               const std::vector<PoseSpec>& poses, const RenderOptions& options = {}) {
    std::vector<SyntheticView> out;
    unsigned seed = options.seed;
    for (const PoseSpec& spec : poses) {
        Camera camera = truth;
        camera.pose = board_pose(board, spec.centre, spec.tilt);
        RenderOptions these = options;
        these.seed = seed++;
        out.push_back({camera.pose, render_board(camera, texture, these)});
        for (const Vec2& corner : true_corners(camera, board)) {
            if (!(corner.x() > 5 && corner.y() > 5 && corner.x() < truth.size.width - 6 && corner.y() < truth.size.height - 6)) {
                throw std::logic_error("a test's board pose puts a corner outside the image");
            }
        }
    }
    return out;
}

}  // namespace libcam::test
