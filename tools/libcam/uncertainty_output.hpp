#pragma once
// What `libcam uncertainty` and `libcam calibrate` print about the projection uncertainty
// (libcam/uncertainty/): the --at pixels, the summary lines, the parameters, the heatmap.

#include <string>
#include <vector>

#include "json_output.hpp"
#include "libcam/uncertainty/uncertainty_map.hpp"

namespace libcam::cli {

// --at's pixels ("x,y", OpenCV's pixels); UsageError naming the flag and the pixel when one
// does not parse or lies off the image.
std::vector<Vec2> at_pixels(const std::vector<std::string>& texts, const ImageSize& size);

// [{pixel [x, y], sigma_px}] (sigma null where the pixel has no ray).
Json at_json(const std::vector<Vec2>& pixels, const std::vector<double>& sigma_px);
// "  at (x, y): sigma 0.0123 px", one a line.
std::string at_lines(const std::vector<Vec2>& pixels, const std::vector<double>& sigma_px);

// "points at infinity" or "points 2 m away".
std::string distance_words(double distance);

// The summary lines: the worst sigma inside the region the corners covered and the
// image's share under 0.1 px and under 1 px.
std::string summary_lines(const UncertaintySummary& summary);

// Each intrinsic parameter with its standard deviation, one a line, those the data do not
// pin down (standard deviation above their size) said.
std::string parameter_lines(const std::vector<ParameterSpread>& parameters);
Json parameters_json(const std::vector<ParameterSpread>& parameters);

// The heatmap PNG (report/uncertainty_heatmap.hpp) of `map`, with the observed pixels.
void write_uncertainty_heatmap(const std::string& path, const UncertaintyMap& map, const SolvedCalibration& solved,
                               const std::string& caption);

}  // namespace libcam::cli
