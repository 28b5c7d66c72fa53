#pragma once
// A calibration's corners and board poses as OpenCV's calibration sample writes them
// (io/detail/opencv_observations.hpp reads them back): the camera, board_width,
// board_height, square_size, image_points, extrinsic_parameters, the RMS over every
// corner and each view's. `libcam reproject` reads it and reproduces the RMS.
//
// The sample's file holds every corner of the board in every view: the views where part
// of the board was not seen (a ChArUco board's partial views) are left out. The corners
// dropped as outliers are written with their view (they are what the detector found):
// the file's RMS counts them.

#include <cstddef>
#include <string>

#include "libcam/calibrate/calibrate.hpp"

namespace libcam {

struct ObservationsText {
    std::string text;
    std::size_t views = 0;       // written
    std::size_t left_out = 0;    // views that saw part of the board
};

// Throws NotRepresentable when the chosen model is not one OpenCV's file holds (OPENCV4
// to 14, FISHEYE, PINHOLE), or when no view saw the whole board.
ObservationsText format_opencv_observations(const Calibration& calibration);

}  // namespace libcam
