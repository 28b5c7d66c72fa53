#include "libcam/report/reprojection_heatmap.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/report/detail/colour_scale.hpp"
#include "libcam/report/detail/cv_image.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

constexpr int kMapSide = 720;        // the longer side of the image in the picture
constexpr int kRegionsAlongLonger = 16;
constexpr int kScaleBarWidth = 130;
constexpr int kTitleHeight = 30;
constexpr int kBarChartHeight = 170;
const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kEmpty(45, 45, 45);
const cv::Scalar kArrow(255, 255, 255);
const cv::Scalar kLine(0, 0, 255);  // BGR red

void draw_text(cv::Mat& image, const std::string& text, cv::Point at, double size = 0.45) {
    cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, size, kWhite, 1, cv::LINE_AA);
}

// The camera most of the counted observations belong to.
int busiest_camera(const ObservationSet& set, const Reprojection& r) {
    std::vector<std::size_t> counted(set.cameras.size(), 0);
    for (std::size_t i = 0; i < r.residuals.size(); ++i) {
        if (r.residuals[i].status != ResidualStatus::Counted) continue;
        ++counted[static_cast<std::size_t>(set.views[static_cast<std::size_t>(set.observations[i].view)].camera)];
    }
    return static_cast<int>(std::max_element(counted.begin(), counted.end()) - counted.begin());
}

struct Region {
    double sum_squares = 0.0;
    Vec2 sum = Vec2::Zero();
    std::size_t count = 0;
};

struct RegionGrid {
    int columns = 0;
    int rows = 0;
    std::vector<Region> regions;
};

RegionGrid regions_of(const ObservationSet& set, const Reprojection& r, int camera) {
    const ImageSize size = set.cameras[static_cast<std::size_t>(camera)].camera.size;
    const double side = static_cast<double>(std::max(size.width, size.height)) / kRegionsAlongLonger;
    RegionGrid grid;
    grid.columns = std::max(1, static_cast<int>(std::ceil(static_cast<double>(size.width) / side)));
    grid.rows = std::max(1, static_cast<int>(std::ceil(static_cast<double>(size.height) / side)));
    grid.regions.resize(static_cast<std::size_t>(grid.columns * grid.rows));
    for (std::size_t i = 0; i < r.residuals.size(); ++i) {
        const Observation& o = set.observations[i];
        if (r.residuals[i].status != ResidualStatus::Counted ||
            set.views[static_cast<std::size_t>(o.view)].camera != camera) {
            continue;
        }
        // Counted observations lie on the image (within half a pixel of its outer centres).
        const int column = std::clamp(static_cast<int>((o.pixel.x() + 0.5) / side), 0, grid.columns - 1);
        const int row = std::clamp(static_cast<int>((o.pixel.y() + 0.5) / side), 0, grid.rows - 1);
        Region& region = grid.regions[static_cast<std::size_t>(row * grid.columns + column)];
        region.sum_squares += r.residuals[i].residual.squaredNorm();
        region.sum += r.residuals[i].residual;
        ++region.count;
    }
    return grid;
}

double region_rms(const Region& region) { return std::sqrt(region.sum_squares / static_cast<double>(region.count)); }

// The regions coloured, with their arrows, into `map` (`scale` picture pixels per image
// pixel); returns the arrows' factor: an arrow is that many times the mean residual,
// both in image pixels.
double draw_regions(cv::Mat& map, const RegionGrid& grid, double top_rms, double scale) {
    const double cell_w = static_cast<double>(map.cols) / grid.columns;
    const double cell_h = static_cast<double>(map.rows) / grid.rows;
    double longest_mean = 0.0;
    for (const Region& region : grid.regions) {
        if (region.count > 0) longest_mean = std::max(longest_mean, (region.sum / static_cast<double>(region.count)).norm());
    }
    // The longest arrow spans about one region: the factor is a round number.
    double factor = 1.0;
    if (longest_mean > 0.0) {
        const double wanted = 0.9 * std::min(cell_w, cell_h) / (scale * longest_mean);
        factor = std::pow(10.0, std::floor(std::log10(wanted)));
        for (const double step : {5.0, 2.0}) {
            if (factor * step <= wanted) {
                factor *= step;
                break;
            }
        }
    }
    for (int row = 0; row < grid.rows; ++row) {
        for (int column = 0; column < grid.columns; ++column) {
            const Region& region = grid.regions[static_cast<std::size_t>(row * grid.columns + column)];
            const cv::Rect cell(static_cast<int>(column * cell_w), static_cast<int>(row * cell_h),
                                static_cast<int>((column + 1) * cell_w) - static_cast<int>(column * cell_w),
                                static_cast<int>((row + 1) * cell_h) - static_cast<int>(row * cell_h));
            if (region.count == 0) {
                map(cell) = kEmpty;
                continue;
            }
            cv::Mat level(1, 1, CV_8U);
            level.at<std::uint8_t>(0) =
                static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(region_rms(region) / top_rms, 0.0, 1.0)));
            const cv::Vec3b colour = detail::colour_levels(level).at<cv::Vec3b>(0);
            map(cell) = cv::Scalar(colour[0], colour[1], colour[2]);
            const Vec2 mean = region.sum / static_cast<double>(region.count);
            const cv::Point2d centre(cell.x + cell.width / 2.0, cell.y + cell.height / 2.0);
            const cv::Point2d tip(centre.x + scale * factor * mean.x(), centre.y + scale * factor * mean.y());
            cv::arrowedLine(map, centre, tip, kArrow, 1, cv::LINE_AA, 0, 0.25);
        }
    }
    return factor;
}

void draw_scale_bar(cv::Mat& canvas, int left, int top, int height, double top_rms) {
    constexpr int bar_width = 20;
    detail::draw_colour_ramp(canvas, cv::Rect(left, top, bar_width, height));
    draw_text(canvas, format_short(top_rms) + " px", {left + bar_width + 6, top + 10});
    draw_text(canvas, "0 px", {left + bar_width + 6, top + height});
    draw_text(canvas, "region RMS", {left, top + height + 20});
    cv::Mat empty = canvas(cv::Rect(left, top + height + 30, bar_width, 14));
    empty = kEmpty;
    draw_text(canvas, "none seen", {left + bar_width + 6, top + height + 42});
}

// A bar per view (its RMS), the RMS of every view as a red line.
void draw_view_bars(cv::Mat& canvas, const cv::Rect& area, const ReprojectionSummary& summary) {
    double top = summary.all.stats.rms_px;
    for (const GroupResiduals& view : summary.per_view) {
        if (view.residuals.stats.count > 0) top = std::max(top, view.residuals.stats.rms_px);
    }
    if (!(top > 0.0) || !std::isfinite(top)) return;
    const int plot_top = area.y + 22, plot_bottom = area.y + area.height - 8;
    const double bar_width = static_cast<double>(area.width) / static_cast<double>(std::max<std::size_t>(1, summary.per_view.size()));
    const auto y_of = [&](double rms) { return plot_bottom - static_cast<int>(std::lround((plot_bottom - plot_top) * rms / top)); };
    for (std::size_t v = 0; v < summary.per_view.size(); ++v) {
        const ResidualStats& stats = summary.per_view[v].residuals;
        if (stats.stats.count == 0 || !std::isfinite(stats.stats.rms_px)) continue;
        const int x0 = area.x + static_cast<int>(v * bar_width);
        const int x1 = std::max(x0 + 1, area.x + static_cast<int>((v + 1) * bar_width) - (bar_width > 4 ? 1 : 0));
        cv::rectangle(canvas, cv::Point(x0, y_of(stats.stats.rms_px)), cv::Point(x1 - 1, plot_bottom),
                      cv::Scalar(200, 160, 60), cv::FILLED);
    }
    const int line_y = y_of(summary.all.stats.rms_px);
    cv::line(canvas, {area.x, line_y}, {area.x + area.width, line_y}, kLine, 1, cv::LINE_AA);
    draw_text(canvas,
              "RMS per view, " + std::to_string(summary.per_view.size()) + " views in the file's order (tallest " +
                  format_short(top) + " px; red: every view, " + format_short(summary.all.stats.rms_px) + " px)",
              {area.x, area.y + 14});
}

}  // namespace

Image reprojection_heatmap(const ObservationSet& set, const Reprojection& reprojection) {
    const ReprojectionSummary& summary = reprojection.summary;
    if (summary.all.stats.count == 0) throw Error(set.source + ": no observation counted: nothing to draw");
    const int camera = busiest_camera(set, reprojection);
    const ImageSize size = set.cameras[static_cast<std::size_t>(camera)].camera.size;
    const double scale = static_cast<double>(kMapSide) / static_cast<double>(std::max(size.width, size.height));
    const int map_width = std::max(1, static_cast<int>(std::lround(size.width * scale)));
    const int map_height = std::max(1, static_cast<int>(std::lround(size.height * scale)));

    const RegionGrid grid = regions_of(set, reprojection, camera);
    double top_rms = 0.0;
    for (const Region& region : grid.regions) {
        if (region.count > 0) top_rms = std::max(top_rms, region_rms(region));
    }
    if (!(top_rms > 0.0)) top_rms = 1.0;

    const int map_area_height = std::max(map_height, 220);
    cv::Mat canvas(kTitleHeight + map_area_height + kBarChartHeight, map_width + kScaleBarWidth, CV_8UC3,
                   cv::Scalar(0, 0, 0));
    cv::Mat map = canvas(cv::Rect(0, kTitleHeight, map_width, map_height));
    const double factor = draw_regions(map, grid, top_rms, scale);
    draw_scale_bar(canvas, map_width + 12, kTitleHeight + 10, std::max(60, map_area_height - 90), top_rms);
    draw_text(canvas,
              std::string(to_string(set.tool)) + ", camera " + set.cameras[static_cast<std::size_t>(camera)].name +
                  " (" + std::string(lens_info(set.cameras[static_cast<std::size_t>(camera)].camera.lens.type).name) +
                  "): " + std::to_string(summary.all.stats.count) + " residuals, RMS " +
                  format_short(summary.all.stats.rms_px, 4) + " px; arrows: mean residual x" + format_short(factor, 3),
              {8, 20}, 0.5);
    draw_view_bars(canvas, cv::Rect(8, kTitleHeight + map_area_height + 4, canvas.cols - 16, kBarChartHeight - 8),
                   summary);
    return detail::to_image(canvas);
}

}  // namespace libcam
