#pragma once
// A calibrated pair (calibrate_pair.hpp) as the files rig tools read: OpenCV's stereo_calib
// sample's intrinsics.yml (M1 D1 M2 D2, and the image size) and extrinsics.yml (R T), which
// `libcam rectify` takes; and `libcam calibrate --json`'s report of the pair.

#include <string>
#include <vector>

#include "libcam/calibrate/calibrate_pair.hpp"

namespace libcam {

struct OpenCvStereoFiles {
    std::string intrinsics;  // M1 D1 M2 D2, image_width, image_height
    std::string extrinsics;  // R T
};

// Throws NotRepresentable, naming the camera and its model, when a camera's model is not
// one of OpenCV's pinhole models (PINHOLE, OPENCV4, OPENCV5, OPENCV8).
OpenCvStereoFiles format_opencv_stereo(const PairCalibration& pair);

// Each camera's projection uncertainty in the pair's solve (solved_pair; points at
// infinity), at `pixels` (OpenCV's; empty: the image centre). `failure` says why there is
// none (too few views to pin the solve down), the sigmas then NaN.
struct PairUncertainty {
    std::vector<Vec2> pixels;
    std::vector<double> sigma_px;
    double noise_px = 0.0;  // the noise the pair's residuals imply, per coordinate
    std::string failure;
};
PairUncertainty pair_uncertainty(const PairCalibration& pair, int side, const std::vector<Vec2>& pixels);

// The JSON text: `pairs` (the views both cameras used: their places in the image lists,
// from 0), `rms_px`, `noise_px`, `R` and `T` (X_second = R X_first + T, OpenCV's
// stereoCalibrate convention), `cameras` [{`name` ("left", "right"), `model`,
// `image_size`, `K`, `dist` (jointly refined), `uncertainty` [{`pixel`, `sigma_px`}]
// (pair_uncertainty at `at`; with `uncertainty_failure` where there is none)}], `views`
// [{`left`, `right` (the images), `rvec`, `tvec` (the board's pose in the left camera:
// X_left = R(rvec) X_board + tvec)}], and `left` and `right`: each camera's own
// calibration as `libcam calibrate --json` reports it.
std::string pair_calibration_json(const PairCalibration& pair, const std::vector<Vec2>& at = {});

}  // namespace libcam
