#pragma once
// What libcam's error heatmaps share (report/verify_heatmap.cpp for `libcam verify
// --heatmap`, report/fit_heatmap.cpp for `libcam fit --heatmap`): the colour scale,
// chosen in one place. Each picture maps its own errors to levels (a log scale for
// verify, a linear one up to the tolerance for fit). Inside libcam::report only: not
// installed, so that report's headers stay free of OpenCV.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace libcam::detail {

// Levels 0 (the bottom of the scale) to 255 (the top), CV_8U, in colour (BGR): viridis,
// which reads in order on screen and in grey.
inline cv::Mat colour_levels(const cv::Mat& levels) {
    cv::Mat coloured;
    cv::applyColorMap(levels, coloured, cv::COLORMAP_VIRIDIS);
    return coloured;
}

// The scale as a vertical bar filling `bar` of `canvas`: the top colour at the top.
inline void draw_colour_ramp(cv::Mat& canvas, const cv::Rect& bar) {
    cv::Mat ramp(bar.height, 1, CV_8U);
    for (int y = 0; y < bar.height; ++y) {
        ramp.at<std::uint8_t>(y) =
            static_cast<std::uint8_t>(std::lround(255.0 * (bar.height - 1 - y) / std::max(1, bar.height - 1)));
    }
    cv::Mat widened;
    cv::resize(colour_levels(ramp), widened, bar.size(), 0, 0, cv::INTER_NEAREST);
    widened.copyTo(canvas(bar));
}

}  // namespace libcam::detail
