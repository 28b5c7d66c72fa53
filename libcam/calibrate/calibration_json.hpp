#pragma once
// The report of a calibration as `libcam calibrate --json` prints it and libcam.calibrate
// returns it in Python: one implementation of its keys (docs/calibrate.md, Output).

#include <string>
#include <vector>

#include "libcam/calibrate/calibrate.hpp"

namespace libcam {

// The chosen model's projection uncertainty (points at infinity) at each pixel; NaN where
// it could not be computed.
std::vector<double> chosen_sigma_px(const Calibration& c, const std::vector<Vec2>& pixels);

// The JSON text (indented by 2), with the chosen model's uncertainty at `at` (the pixels
// and their chosen_sigma_px).
std::string calibration_json(const Calibration& c, const std::vector<Vec2>& at, const std::vector<double>& at_sigma_px);

}  // namespace libcam
