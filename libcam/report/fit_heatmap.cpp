#include "libcam/report/fit_heatmap.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "libcam/fit/error_map.hpp"
#include "libcam/report/detail/colour_scale.hpp"
#include "libcam/report/detail/cv_image.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

constexpr int kScaleBarWidth = 150;
constexpr int kCaptionHeight = 40;

const cv::Vec3b kNoRay(128, 128, 128);
const cv::Vec3b kOverTolerance(0, 0, 255);  // BGR red
const cv::Scalar kWhite(255, 255, 255);

cv::Mat colour_errors(const FitErrorMap& map, double tolerance_px) {
    const cv::Size size(static_cast<int>(map.columns), static_cast<int>(map.rows));
    cv::Mat level(size, CV_8UC1);
    for (int i = 0; i < size.area(); ++i) {
        const double e = map.error_px[static_cast<std::size_t>(i)];
        level.at<std::uint8_t>(i) = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(std::isfinite(e) ? e / tolerance_px : 0.0, 0.0, 1.0)));
    }
    cv::Mat colour = detail::colour_levels(level);
    for (int i = 0; i < size.area(); ++i) {
        const double e = map.error_px[static_cast<std::size_t>(i)];
        if (std::isnan(e) || std::isinf(e)) colour.at<cv::Vec3b>(i) = kNoRay;
        else if (e > tolerance_px) colour.at<cv::Vec3b>(i) = kOverTolerance;
    }
    return colour;
}

// The scene's outline in the picture's pixels: `tile` source pixels per picture pixel.
void draw_outline(cv::Mat& image, const Scene& scene, const Camera& source, const Vec2& tile) {
    // Far outside the picture a point only has to keep its direction; clamping keeps it an int.
    const double reach = 10.0 * std::max(image.cols, image.rows);
    std::vector<cv::Point> points;
    for (const Vec2& p : scene.outline(PreparedCamera(source))) {
        const Vec2 q = (((p.array() + 0.5) / tile.array() - 0.5).max(-reach).min(reach)).matrix();
        points.emplace_back(cvRound(q.x()), cvRound(q.y()));
    }
    cv::polylines(image, std::vector<std::vector<cv::Point>>{points}, false, kWhite, 2, cv::LINE_AA);
}

void draw_text(cv::Mat& image, const std::string& text, cv::Point at, double size = 0.45) {
    cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, size, kWhite, 1, cv::LINE_AA);
}

// The colour scale from 0 (bottom) to the tolerance (top), and the legend.
void draw_scale_bar(cv::Mat& canvas, int left, int height, double tolerance_px) {
    const int top = 20, bottom = std::max(top + 40, height - 90), bar_width = 20;
    detail::draw_colour_ramp(canvas, cv::Rect(left, top, bar_width, bottom - top));
    draw_text(canvas, format_short(tolerance_px) + " px", {left + bar_width + 6, top + 10});
    draw_text(canvas, "0 px", {left + bar_width + 6, bottom});
    canvas(cv::Rect(left, bottom + 16, bar_width, 14)) = cv::Scalar(kOverTolerance[0], kOverTolerance[1], kOverTolerance[2]);
    draw_text(canvas, "> tolerance", {left + bar_width + 6, bottom + 28});
    canvas(cv::Rect(left, bottom + 40, bar_width, 14)) = cv::Scalar(kNoRay[0], kNoRay[1], kNoRay[2]);
    draw_text(canvas, "no ray / no", {left + bar_width + 6, bottom + 52});
    draw_text(canvas, "projection", {left + bar_width + 6, bottom + 68});
}

}  // namespace

Image fit_heatmap(const Camera& source, const Scene& scene, const FitOptions& options, const CandidateReport& chosen) {
    // One picture pixel per tile; the tiles as square as whole numbers allow.
    const long width = std::min<long>(kFitHeatmapMaxWidth, source.size.width);
    const double scale = static_cast<double>(source.size.width) / static_cast<double>(width);
    const long height = std::max(1L, std::lround(static_cast<double>(source.size.height) / scale));
    const FitErrorMap map = fit_error_map(source, chosen.fit, options.depths, width, height);
    const Vec2 tile(static_cast<double>(source.size.width) / static_cast<double>(width),
                    static_cast<double>(source.size.height) / static_cast<double>(height));
    const double tolerance_px = options.tolerance_px;

    const int map_width = static_cast<int>(width), map_height = static_cast<int>(height);
    cv::Mat canvas(std::max(map_height, 200) + kCaptionHeight, map_width + kScaleBarWidth, CV_8UC3, cv::Scalar(0, 0, 0));
    cv::Mat picture = canvas(cv::Rect(0, 0, map_width, map_height));
    colour_errors(map, tolerance_px).copyTo(picture);
    draw_outline(picture, scene, source, tile);
    draw_scale_bar(canvas, map_width + 12, std::max(map_height, 200), tolerance_px);
    draw_text(canvas,
              std::string(chosen.fit.candidate.name) + " against the source: max " + format_short(chosen.max_px) +
                  " px in the scene (outlined), tolerance " + format_short(tolerance_px) + " px",
              {8, canvas.rows - 14}, 0.5);
    return detail::to_image(canvas);
}

}  // namespace libcam
