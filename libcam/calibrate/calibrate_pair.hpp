#pragma once
// A stereo pair from two cameras' images of the same board views (`libcam calibrate --left
// IMAGES --right IMAGES`): each camera calibrated alone as `libcam calibrate` does (its
// model chosen by held-out views, outliers dropped), then both refined together on the
// views both cameras used: both intrinsics, the second camera's pose from the first and
// one board pose per view (Ceres, libcam::fit's solve_pair), as cv::stereoCalibrate
// refines them.
//
// The pose is OpenCV's stereoCalibrate convention: X_second = R X_first + T, in the
// board's unit.

#include <cstddef>
#include <string>
#include <vector>

#include "libcam/calibrate/calibrate.hpp"

namespace libcam {

struct PairCalibration {
    Calibration first, second;  // each camera alone
    // The views both cameras used (indices into the image lists) and their board poses in
    // the first camera, after the joint fit.
    std::vector<std::size_t> pairs;
    std::vector<Pose> board_poses;
    Camera first_camera;   // jointly refined, pose identity
    Camera second_camera;  // jointly refined, pose = the pair's: X_second = R X_first + T
    double rms_px = 0.0;   // over both cameras' corners in the pairs
    // The corners each camera saw in the pairs (board points, pixels), as the joint fit
    // took them; views in the order of `pairs`, each with its board pose in that camera.
    std::vector<FitView> first_views, second_views;
    // Where each of `pairs` is in each camera's own calibration (indices into first.views
    // and second.views): its corners' ids and outliers.
    std::vector<std::size_t> first_view_of_pair, second_view_of_pair;
};

// `first[i]` and `second[i]` are the same board view seen by each camera. Throws Error, in
// one line, when either camera cannot be calibrated or fewer than two views were used by
// both.
PairCalibration calibrate_pair(const std::vector<BoardDetection>& first, const std::vector<BoardDetection>& second,
                               const BoardSpec& board, const CalibrationOptions& options);

// The joint fit as projection uncertainty takes it (uncertainty/projection_uncertainty.hpp):
// camera `side` (0 the first, 1 the second) in the solve of both, as mrcal takes a camera of
// a solve of several cameras. Both cameras' intrinsics, the second camera's pose and the
// board poses the two share are free; every corner of both counts.
SolvedCalibration solved_pair(const PairCalibration& pair, int side);

}  // namespace libcam
