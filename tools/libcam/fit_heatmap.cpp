#include "fit_heatmap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "libcam/error.hpp"
#include "libcam/interop/heatmap.hpp"

namespace libcam::cli {

namespace {

// The picture is at most this wide: enough to see the error's shape, cheap to compute.
constexpr int kMaxHeatmapWidth = 640;
constexpr int kScaleBarWidth = 150;
constexpr int kCaptionHeight = 40;

const cv::Vec3b kNoRay(128, 128, 128);
const cv::Vec3b kOverTolerance(0, 0, 255);  // BGR red
const cv::Scalar kWhite(255, 255, 255);

std::string short_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

// The source pixel at the centre of each heatmap pixel, row by row.
std::vector<Vec2> heatmap_pixels(const ImageSize& size, const cv::Size& heatmap) {
    const double scale = static_cast<double>(size.width) / heatmap.width;
    std::vector<Vec2> pixels;
    pixels.reserve(static_cast<std::size_t>(heatmap.area()));
    for (int v = 0; v < heatmap.height; ++v) {
        for (int u = 0; u < heatmap.width; ++u) pixels.emplace_back((u + 0.5) * scale - 0.5, (v + 0.5) * scale - 0.5);
    }
    return pixels;
}

// The largest error over the depths at each pixel; NaN where the source has no ray.
std::vector<double> errors_at(const Camera& source, const FittedModel& chosen, const std::vector<Vec2>& pixels,
                              const std::vector<double>& depths) {
    std::vector<double> worst(pixels.size(), std::nan(""));
    ScenePixels rays;
    std::vector<std::size_t> index_of;
    const std::vector<Unprojection> unprojected = PreparedCamera(source).unproject(pixels);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        if (!unprojected[i].valid) continue;
        rays.pixels.push_back(pixels[i]);
        rays.directions.push_back(unprojected[i].direction.normalized());
        index_of.push_back(i);
    }
    if (index_of.empty()) return worst;
    // observations_of lists every pixel at the first depth, then at the next, ...
    const std::vector<double> errors = reprojection_errors(chosen.camera, observations_of(rays, depths));
    for (std::size_t k = 0; k < errors.size(); ++k) {
        double& cell = worst[index_of[k % index_of.size()]];
        cell = std::isnan(cell) ? errors[k] : std::max(cell, errors[k]);
    }
    return worst;
}

cv::Mat colour_errors(const std::vector<double>& errors, const cv::Size& size, double tolerance_px) {
    cv::Mat level(size, CV_8UC1);
    for (int i = 0; i < size.area(); ++i) {
        const double e = errors[static_cast<std::size_t>(i)];
        level.at<std::uint8_t>(i) = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(std::isfinite(e) ? e / tolerance_px : 0.0, 0.0, 1.0)));
    }
    cv::Mat colour = colour_levels(level);
    for (int i = 0; i < size.area(); ++i) {
        const double e = errors[static_cast<std::size_t>(i)];
        if (std::isnan(e) || std::isinf(e)) colour.at<cv::Vec3b>(i) = kNoRay;
        else if (e > tolerance_px) colour.at<cv::Vec3b>(i) = kOverTolerance;
    }
    return colour;
}

void draw_outline(cv::Mat& image, const Scene& scene, const Camera& source, double scale) {
    // Far outside the picture a point only has to keep its direction; clamping keeps it an int.
    const double reach = 10.0 * std::max(image.cols, image.rows);
    std::vector<cv::Point> points;
    for (const Vec2& p : scene.outline(PreparedCamera(source))) {
        const Vec2 q = (((p.array() + 0.5) / scale - 0.5).max(-reach).min(reach)).matrix();
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
    draw_colour_ramp(canvas, cv::Rect(left, top, bar_width, bottom - top));
    draw_text(canvas, short_number(tolerance_px) + " px", {left + bar_width + 6, top + 10});
    draw_text(canvas, "0 px", {left + bar_width + 6, bottom});
    canvas(cv::Rect(left, bottom + 16, bar_width, 14)) = cv::Scalar(kOverTolerance[0], kOverTolerance[1], kOverTolerance[2]);
    draw_text(canvas, "> tolerance", {left + bar_width + 6, bottom + 28});
    canvas(cv::Rect(left, bottom + 40, bar_width, 14)) = cv::Scalar(kNoRay[0], kNoRay[1], kNoRay[2]);
    draw_text(canvas, "no ray / no", {left + bar_width + 6, bottom + 52});
    draw_text(canvas, "projection", {left + bar_width + 6, bottom + 68});
}

}  // namespace

std::string fit_heatmap_png(const Camera& source, const Scene& scene, const FittedModel& chosen,
                            const std::vector<double>& depths, double tolerance_px, double max_in_scene_px) {
    const int width = static_cast<int>(std::min<long>(kMaxHeatmapWidth, source.size.width));
    const double scale = static_cast<double>(source.size.width) / width;
    const cv::Size size(width, std::max(1, static_cast<int>(std::lround(static_cast<double>(source.size.height) / scale))));
    const std::vector<double> errors = errors_at(source, chosen, heatmap_pixels(source.size, size), depths);

    cv::Mat canvas(std::max(size.height, 200) + kCaptionHeight, size.width + kScaleBarWidth, CV_8UC3, cv::Scalar(0, 0, 0));
    cv::Mat map = canvas(cv::Rect(0, 0, size.width, size.height));
    colour_errors(errors, size, tolerance_px).copyTo(map);
    draw_outline(map, scene, source, scale);
    draw_scale_bar(canvas, size.width + 12, std::max(size.height, 200), tolerance_px);
    draw_text(canvas,
              std::string(chosen.candidate.name) + " against the source: max " + short_number(max_in_scene_px) +
                  " px in the scene (outlined), tolerance " + short_number(tolerance_px) + " px",
              {8, canvas.rows - 14}, 0.5);

    std::vector<std::uint8_t> png;
    if (!cv::imencode(".png", canvas, png)) throw FileError("heatmap: OpenCV could not encode the PNG");
    return std::string(png.begin(), png.end());
}

}  // namespace libcam::cli
