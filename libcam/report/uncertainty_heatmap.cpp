#include "libcam/report/uncertainty_heatmap.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "libcam/report/detail/colour_scale.hpp"
#include "libcam/report/detail/cv_image.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

constexpr int kMaxWidth = 640;
constexpr int kScaleBarWidth = 130;
constexpr int kCaptionHeight = 40;
constexpr double kDecades = 2.0;  // the colour scale spans a factor of 100

const cv::Vec3b kNoRay(128, 128, 128);
const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kBlack(0, 0, 0);

// The scale's bottom: 0.01 px, or lower where the map is lower, at a power of ten.
double scale_bottom(const UncertaintyMap& map) {
    double smallest = 0.01;
    for (const double s : map.sigma_px) {
        if (std::isfinite(s) && s > 0.0) smallest = std::min(smallest, s);
    }
    return std::pow(10.0, std::floor(std::log10(smallest)));
}

// log10(sigma) as a level 0..255 of the scale from `bottom` up kDecades decades.
std::uint8_t level_of(double sigma, double bottom) {
    const double t = std::log10(sigma / bottom) / kDecades;
    return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(t, 0.0, 1.0)));
}

// The map's tiles, one picture pixel each, then resized to the picture.
cv::Mat colour_map(const UncertaintyMap& map, double bottom, const cv::Size& picture) {
    const cv::Size size(static_cast<int>(map.columns), static_cast<int>(map.rows));
    cv::Mat level(size, CV_8UC1);
    for (int i = 0; i < size.area(); ++i) {
        const double s = map.sigma_px[static_cast<std::size_t>(i)];
        level.at<std::uint8_t>(i) = std::isfinite(s) ? level_of(s, bottom) : 255;
    }
    cv::Mat colour = detail::colour_levels(level);
    for (int i = 0; i < size.area(); ++i) {
        if (!std::isfinite(map.sigma_px[static_cast<std::size_t>(i)])) colour.at<cv::Vec3b>(i) = kNoRay;
    }
    cv::Mat resized;
    cv::resize(colour, resized, picture, 0, 0, cv::INTER_NEAREST);
    return resized;
}

// The contour where sigma crosses `at`: the boundary of the tiles below it, smoothed to the picture.
void draw_contour(cv::Mat& picture, const UncertaintyMap& map, double at) {
    const cv::Size size(static_cast<int>(map.columns), static_cast<int>(map.rows));
    cv::Mat below(size, CV_8UC1);
    for (int i = 0; i < size.area(); ++i) {
        below.at<std::uint8_t>(i) = map.sigma_px[static_cast<std::size_t>(i)] < at ? 255 : 0;
    }
    cv::Mat smooth;
    cv::resize(below, smooth, picture.size(), 0, 0, cv::INTER_LINEAR);
    cv::threshold(smooth, smooth, 127, 255, cv::THRESH_BINARY);
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(smooth, contours, cv::RETR_LIST, cv::CHAIN_APPROX_SIMPLE);
    cv::drawContours(picture, contours, -1, kWhite, 1, cv::LINE_AA);
}

void draw_text(cv::Mat& image, const std::string& text, cv::Point at, double size = 0.45) {
    cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, size, kWhite, 1, cv::LINE_AA);
}

void draw_scale_bar(cv::Mat& canvas, int left, int height, double bottom) {
    const int top = 20, low = std::max(top + 40, height - 50), bar_width = 20;
    detail::draw_colour_ramp(canvas, cv::Rect(left, top, bar_width, low - top));
    for (int decade = 0; decade <= static_cast<int>(kDecades); ++decade) {
        const int y = low - static_cast<int>(std::lround((low - top) * decade / kDecades));
        draw_text(canvas, format_short(bottom * std::pow(10.0, decade)) + " px", {left + bar_width + 6, y + 4});
    }
    canvas(cv::Rect(left, low + 16, bar_width, 14)) = cv::Scalar(kNoRay[0], kNoRay[1], kNoRay[2]);
    draw_text(canvas, "no ray", {left + bar_width + 6, low + 28});
}

}  // namespace

Image uncertainty_heatmap(const UncertaintyMap& map, const std::vector<Vec2>& observed,
                          const std::vector<Vec2>& region, const std::string& caption) {
    const int width = static_cast<int>(std::min<long>(kMaxWidth, map.image.width));
    const double scale = static_cast<double>(width) / static_cast<double>(map.image.width);
    const int height = std::max(1, static_cast<int>(std::lround(static_cast<double>(map.image.height) * scale)));
    const double bottom = scale_bottom(map);
    cv::Mat canvas(std::max(height, 200) + kCaptionHeight, width + kScaleBarWidth, CV_8UC3, kBlack);
    cv::Mat picture = canvas(cv::Rect(0, 0, width, height));
    colour_map(map, bottom, picture.size()).copyTo(picture);
    draw_contour(picture, map, 0.1);
    draw_contour(picture, map, 1.0);
    // OpenCV's pixel (x, y) spans [x - 0.5, x + 0.5]: scaled about the image's corner.
    const auto to_picture = [&](const Vec2& p) {
        return cv::Point(cvRound((p.x() + 0.5) * scale - 0.5), cvRound((p.y() + 0.5) * scale - 0.5));
    };
    for (const Vec2& p : observed) cv::circle(picture, to_picture(p), 1, kBlack, cv::FILLED);
    std::vector<cv::Point> outline;
    for (const Vec2& p : region) outline.push_back(to_picture(p));
    if (!outline.empty()) cv::polylines(picture, std::vector<std::vector<cv::Point>>{outline}, true, kWhite, 1, cv::LINE_AA);
    draw_scale_bar(canvas, width + 12, std::max(height, 200), bottom);
    draw_text(canvas, caption, {8, canvas.rows - 14}, 0.45);
    return detail::to_image(canvas);
}

}  // namespace libcam
