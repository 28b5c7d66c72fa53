#pragma once
// A calibrated pair (calibrate_pair.hpp) as the files rig tools read: OpenCV's stereo_calib
// sample's intrinsics.yml (M1 D1 M2 D2, and the image size) and extrinsics.yml (R T), which
// `libcam rectify` takes; and `libcam calibrate --json`'s report of the pair.

#include <string>

#include "libcam/calibrate/calibrate_pair.hpp"

namespace libcam {

struct OpenCvStereoFiles {
    std::string intrinsics;  // M1 D1 M2 D2, image_width, image_height
    std::string extrinsics;  // R T
};

// Throws NotRepresentable, naming the camera and its model, when a camera's model is not
// one of OpenCV's pinhole models (PINHOLE, OPENCV4, OPENCV5, OPENCV8).
OpenCvStereoFiles format_opencv_stereo(const PairCalibration& pair);

// The JSON text: `pairs` (the views both cameras used: their places in the image lists,
// from 0), `rms_px`, `R` and `T` (X_second =
// R X_first + T, OpenCV's stereoCalibrate convention), `cameras` [{`name` ("left",
// "right"), `model`, `image_size`, `K`, `dist`}] (jointly refined), and `left` and `right`:
// each camera's own calibration as `libcam calibrate --json` reports it.
std::string pair_calibration_json(const PairCalibration& pair);

}  // namespace libcam
