#include "libcam/report/verify_heatmap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/report/detail/colour_scale.hpp"
#include "libcam/report/detail/cv_image.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

using detail::colour_levels;
using detail::draw_colour_ramp;

constexpr double kInf = std::numeric_limits<double>::infinity();

const cv::Scalar kWhite(255, 255, 255), kBlack(0, 0, 0);
const cv::Scalar kUnmeasuredGrey(176, 176, 176);
const cv::Vec3b kHatchLight(224, 224, 224), kHatchDark(96, 96, 96);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kFontScale = 0.45;
constexpr int kMargin = 16, kLineHeight = 20, kBarWidth = 20;

// The decades (log10 px) at the bottom and top of the colour scale: from the smallest
// positive error to the largest, at most 16 decades (smaller errors, and exact zeros,
// take the bottom colour; infinite ones the top).
struct Decades {
    int low = -16;
    int high = -15;
};

Decades decades_of(const std::vector<double>& errors) {
    double smallest = kInf, largest = 0.0;
    for (double e : errors) {
        if (!std::isfinite(e) || e <= 0.0) continue;
        smallest = std::min(smallest, e);
        largest = std::max(largest, e);
    }
    if (largest == 0.0) return {};
    Decades d;
    d.high = static_cast<int>(std::ceil(std::log10(largest)));
    d.low = std::max(static_cast<int>(std::floor(std::log10(smallest))), d.high - 16);
    if (d.low == d.high) --d.low;
    return d;
}

// 0 at the bottom of the scale, 255 at the top.
std::uint8_t colour_level(double error, const Decades& d) {
    const double t = (std::log10(error) - d.low) / static_cast<double>(d.high - d.low);
    return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(std::isnan(t) ? 1.0 : t, 0.0, 1.0)));
}

cv::Size map_size(const ImageSize& image) {
    const double scale = kHeatmapMapSide / static_cast<double>(std::max(image.width, image.height));
    return {std::max(1, static_cast<int>(std::lround(scale * static_cast<double>(image.width)))),
            std::max(1, static_cast<int>(std::lround(scale * static_cast<double>(image.height))))};
}

// The error per grid pixel in colour, scaled up to `size`, with the pixels libcam has no
// ray through hatched and the unmeasured ones grey.
cv::Mat draw_map(const VerifyReport& report, const VerifyCheck& check, const Decades& decades, cv::Size size) {
    const int columns = static_cast<int>(report.options.grid_columns), rows = static_cast<int>(report.options.grid_rows);
    cv::Mat levels(rows, columns, CV_8U), no_ray(rows, columns, CV_8U), unmeasured(rows, columns, CV_8U);
    for (int i = 0; i < rows * columns; ++i) {
        const double error = check.pixel_error_px[static_cast<std::size_t>(i)];
        levels.data[i] = std::isnan(error) ? 0 : colour_level(error, decades);
        no_ray.data[i] = report.pixel_valid[static_cast<std::size_t>(i)] ? 0 : 255;
        unmeasured.data[i] = std::isnan(error) && !no_ray.data[i] ? 255 : 0;
    }
    cv::Mat map, no_ray_big, unmeasured_big;
    cv::resize(colour_levels(levels), map, size, 0, 0, cv::INTER_NEAREST);
    cv::resize(no_ray, no_ray_big, size, 0, 0, cv::INTER_NEAREST);
    cv::resize(unmeasured, unmeasured_big, size, 0, 0, cv::INTER_NEAREST);
    map.setTo(kUnmeasuredGrey, unmeasured_big);
    for (int y = 0; y < size.height; ++y) {
        for (int x = 0; x < size.width; ++x) {
            if (no_ray_big.at<std::uint8_t>(y, x)) map.at<cv::Vec3b>(y, x) = (x + y) % 8 < 2 ? kHatchDark : kHatchLight;
        }
    }
    return map;
}

void put_text(cv::Mat& canvas, const std::string& text, cv::Point origin) {
    cv::putText(canvas, text, origin, kFont, kFontScale, kBlack, 1, cv::LINE_AA);
}

int text_width(const std::string& text) {
    int baseline = 0;
    return cv::getTextSize(text, kFont, kFontScale, 1, &baseline).width;
}

std::string decade_label(int decade) { return "1e" + std::to_string(decade); }

// A vertical bar from the top decade (top) to the bottom one, a tick and label per
// decade (every other one, or fewer, when there are many).
void draw_scale_bar(cv::Mat& canvas, cv::Rect bar, const Decades& d) {
    draw_colour_ramp(canvas, bar);
    cv::rectangle(canvas, bar, kBlack, 1);
    put_text(canvas, "error, px", {bar.x - 8, bar.y - 14});
    const int span = d.high - d.low, step = (span + 7) / 8;
    for (int decade = d.low; decade <= d.high; decade += step) {
        const int y = bar.y + bar.height - 1 - static_cast<int>(std::lround((bar.height - 1.0) * (decade - d.low) / span));
        cv::line(canvas, {bar.x + bar.width, y}, {bar.x + bar.width + 5, y}, kBlack, 1);
        const std::string label = (decade == d.low ? "<=" : "") + decade_label(decade);
        put_text(canvas, label, {bar.x + bar.width + 8, y + 5});
    }
}

std::vector<std::string> title_lines(const VerifyReport& report, const VerifyCheck& check) {
    const ErrorStats& s = check.stats;
    const std::string verdict = check.informational() ? "informational"
                                : "tolerance " + format_short(*check.tolerance_px) + " px, " + (check.pass() ? "pass" : "FAIL");
    return {
        check.name + ": " + check.library,
        "median " + format_short(s.median_px) + "  p99 " + format_short(s.p99_px) + "  max " + format_short(s.max_px) + " px  (" + verdict + ")",
        std::string(lens_info(report.lens_type).name) + " " + std::to_string(report.image_size.width) + "x" +
            std::to_string(report.image_size.height) + ", grid " + std::to_string(report.options.grid_columns) + "x" +
            std::to_string(report.options.grid_rows) + " pixels; each shows the worst of its points",
    };
}

void draw_legend(cv::Mat& canvas, cv::Point at) {
    const cv::Rect hatch(at.x, at.y, 24, 14), plain(at.x + 300, at.y, 24, 14);
    for (int y = 0; y < hatch.height; ++y) {
        for (int x = 0; x < hatch.width; ++x) {
            canvas.at<cv::Vec3b>(hatch.y + y, hatch.x + x) = (x + y) % 8 < 2 ? kHatchDark : kHatchLight;
        }
    }
    cv::rectangle(canvas, plain, kUnmeasuredGrey, cv::FILLED);
    put_text(canvas, "no ray (libcam: invalid)", {hatch.x + hatch.width + 6, at.y + 12});
    put_text(canvas, "not measured by this check", {plain.x + plain.width + 6, at.y + 12});
}

}  // namespace

Image verify_heatmap(const VerifyReport& report, std::string_view check_name) {
    const VerifyCheck* check = report.find(check_name);
    if (check == nullptr) throw InvalidArgument("check: no check named '" + std::string(check_name) + "'");
    if (check->skipped()) throw Error("check " + check->name + " was skipped: " + *check->skipped_because);

    const Decades decades = decades_of(check->pixel_error_px);
    const cv::Mat map = draw_map(report, *check, decades, map_size(report.image_size));
    const std::vector<std::string> title = title_lines(report, *check);

    const int top = kMargin + kLineHeight * static_cast<int>(title.size()) + 16;
    const int body_height = std::max(map.rows, 300);
    const cv::Rect bar(kMargin + map.cols + 28, top, kBarWidth, body_height);
    int width = bar.x + bar.width + 8 + text_width("<=1e-16") + kMargin;
    for (const std::string& line : title) width = std::max(width, 2 * kMargin + text_width(line));
    width = std::max(width, 2 * kMargin + 560);  // the legend
    const int legend_y = top + body_height + 16;

    cv::Mat canvas(legend_y + 14 + kMargin, width, CV_8UC3, kWhite);
    for (std::size_t i = 0; i < title.size(); ++i) {
        put_text(canvas, title[i], {kMargin, kMargin + 12 + kLineHeight * static_cast<int>(i)});
    }
    map.copyTo(canvas(cv::Rect(kMargin, top, map.cols, map.rows)));
    cv::rectangle(canvas, cv::Rect(kMargin - 1, top - 1, map.cols + 2, map.rows + 2), kBlack, 1);
    draw_scale_bar(canvas, bar, decades);
    draw_legend(canvas, {kMargin, legend_y});
    return detail::to_image(canvas);
}

}  // namespace libcam
