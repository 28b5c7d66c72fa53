#include "libcam/report/bench_plot.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>

#include "libcam/camera/simd.hpp"
#include "libcam/error.hpp"
#include "libcam/report/detail/cv_image.hpp"

namespace libcam {

namespace {

constexpr int kPanelWidth = 1000, kPanelHeight = 700;
constexpr int kLeft = 110, kRight = 40, kTop = 60, kBottom = 70;  // plot area margins in a panel
constexpr double kErrorFloor = 1e-16;  // an error of 0 is drawn here
const cv::Scalar kBlack(0, 0, 0), kGrey(215, 215, 215), kWhite(255, 255, 255);

cv::Scalar library_colour(const std::string& library) {
    if (library == "libcam") return {200, 90, 20};  // BGR: blue
    if (library == "opencv") return {40, 40, 220};  // red
    return {40, 150, 40};                           // green: mrcal
}

// Decades spanning [low, high] (values > 0), a little margin around them.
struct LogRange {
    double low, high;  // log10
};

LogRange decades_around(double low, double high) {
    return {std::floor(std::log10(low) - 0.05), std::ceil(std::log10(high) + 0.05)};
}

struct Axes {
    cv::Rect area;
    LogRange x, y;

    cv::Point at(double ns, double px) const {
        const double fx = (std::log10(ns) - x.low) / (x.high - x.low);
        const double fy = (std::log10(std::max(px, kErrorFloor)) - y.low) / (y.high - y.low);
        return {area.x + static_cast<int>(std::lround(fx * area.width)),
                area.y + area.height - static_cast<int>(std::lround(fy * area.height))};
    }
};

void put_text(cv::Mat& image, const std::string& text, cv::Point origin, double scale, const cv::Scalar& colour) {
    cv::putText(image, text, origin, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

std::string decade_label(int exponent) { return "1e" + std::to_string(exponent); }

void draw_axes(cv::Mat& panel, const Axes& axes, const std::string& title) {
    for (int e = static_cast<int>(axes.x.low); e <= static_cast<int>(axes.x.high); ++e) {
        const cv::Point p = axes.at(std::pow(10.0, e), std::pow(10.0, axes.y.low));
        cv::line(panel, {p.x, axes.area.y}, {p.x, axes.area.y + axes.area.height}, kGrey);
        put_text(panel, decade_label(e), {p.x - 18, axes.area.y + axes.area.height + 24}, 0.5, kBlack);
    }
    for (int e = static_cast<int>(axes.y.low); e <= static_cast<int>(axes.y.high); ++e) {
        const cv::Point p = axes.at(std::pow(10.0, axes.x.low), std::pow(10.0, e));
        cv::line(panel, {axes.area.x, p.y}, {axes.area.x + axes.area.width, p.y}, kGrey);
        put_text(panel, decade_label(e), {axes.area.x - 62, p.y + 5}, 0.5, kBlack);
    }
    cv::rectangle(panel, axes.area, kBlack);
    put_text(panel, "time per point, ns (log)", {axes.area.x + axes.area.width / 2 - 100, kPanelHeight - 18}, 0.6, kBlack);
    put_text(panel, "worst error, px (log)", {8, kTop - 14}, 0.55, kBlack);
    put_text(panel, title, {kLeft + 100, 28}, 0.65, kBlack);
}

std::string point_label(const BenchRow& row) {
    std::string label = row.library + " " + row.method;
    if (row.scalar == "float") label += " (float)";
    if (row.invalid_fraction > 0) {
        label += " [" + std::to_string(static_cast<int>(std::lround(100 * row.invalid_fraction))) + "% no ray]";
    }
    return label;
}

// Labels placed next to their point where they overlap no other label and no marker:
// right, left, above or below it, then further down with a leader line back to it.
class LabelPlacer {
public:
    LabelPlacer(std::vector<cv::Point> markers, cv::Rect bounds) : markers_(std::move(markers)), bounds_(bounds) {}

    // The text's bottom-left origin; `leader` is set when it had to move away.
    cv::Point place(const std::string& text, cv::Point point, bool& leader) {
        int baseline = 0;
        const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, kTextScale, 1, &baseline);
        const int h = size.height + baseline;
        const cv::Point offsets[] = {{10, -h / 2}, {-10 - size.width, -h / 2}, {-size.width / 2, -h - 8},
                                     {-size.width / 2, 10}, {10, -h - 6}, {10, 6}, {-10 - size.width, -h - 6},
                                     {-10 - size.width, 6}};
        leader = false;
        for (const cv::Point& offset : offsets) {
            const cv::Rect box(point + offset, cv::Size(size.width, h));
            if (fits(box)) return keep(box, size);
        }
        leader = true;
        cv::Rect box(point + offsets[0], cv::Size(size.width, h));
        for (int tries = 0; tries < 60 && !fits(box); ++tries) box.y += h + 2;
        return keep(box, size);
    }

    static constexpr double kTextScale = 0.45;

private:
    bool fits(const cv::Rect& box) const {
        if ((box & bounds_) != box) return false;
        const auto hits = [&](const cv::Rect& r) { return (r & box).area() > 0; };
        const auto on_marker = [&](const cv::Point& m) { return hits(cv::Rect(m.x - 7, m.y - 7, 14, 14)); };
        return std::none_of(placed_.begin(), placed_.end(), hits) && std::none_of(markers_.begin(), markers_.end(), on_marker);
    }
    cv::Point keep(const cv::Rect& box, const cv::Size& size) {
        placed_.push_back(box);
        return {box.x, box.y + size.height};
    }

    std::vector<cv::Point> markers_;
    cv::Rect bounds_;
    std::vector<cv::Rect> placed_;
};

void draw_marker(cv::Mat& panel, const BenchRow& row, cv::Point p) {
    const cv::Scalar colour = library_colour(row.library);
    if (row.scalar == "float") {
        cv::rectangle(panel, {p.x - 5, p.y - 5}, {p.x + 5, p.y + 5}, colour, cv::FILLED);
    } else {
        cv::circle(panel, p, 6, colour, cv::FILLED, cv::LINE_AA);
    }
}

// One line in the top margin, right-aligned: markers for the scalar, colours for the library.
void draw_legend(cv::Mat& panel, const Axes& axes) {
    const int x = axes.area.x + axes.area.width - 330, y = kTop - 12;
    const double scale = LabelPlacer::kTextScale;
    cv::circle(panel, {x + 4, y - 5}, 6, kBlack, cv::FILLED, cv::LINE_AA);
    put_text(panel, "double", {x + 14, y}, scale, kBlack);
    cv::rectangle(panel, {x + 74, y - 10}, {x + 84, y}, kBlack, cv::FILLED);
    put_text(panel, "float", {x + 90, y}, scale, kBlack);
    put_text(panel, "libcam", {x + 145, y}, scale, library_colour("libcam"));
    put_text(panel, "OpenCV", {x + 205, y}, scale, library_colour("opencv"));
    put_text(panel, "mrcal", {x + 275, y}, scale, library_colour("mrcal"));
}

void draw_points(cv::Mat& panel, const Axes& axes, const std::vector<const BenchRow*>& rows) {
    std::vector<cv::Point> markers;
    for (const BenchRow* row : rows) markers.push_back(axes.at(row->ns_per_point, row->error->max_px));
    for (std::size_t i = 0; i < rows.size(); ++i) draw_marker(panel, *rows[i], markers[i]);
    LabelPlacer labels(markers, axes.area);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const std::string text = point_label(*rows[i]);
        bool leader = false;
        const cv::Point origin = labels.place(text, markers[i], leader);
        const cv::Scalar colour = library_colour(rows[i]->library);
        if (leader) cv::line(panel, markers[i], {origin.x - 2, origin.y - 4}, colour, 1, cv::LINE_AA);
        put_text(panel, text, origin, LabelPlacer::kTextScale, colour);
    }
}

cv::Mat draw_panel(const std::string& camera, const std::vector<const BenchRow*>& rows) {
    cv::Mat panel(kPanelHeight, kPanelWidth, CV_8UC3, kWhite);
    double ns_low = 1e300, ns_high = 0, px_low = 1e300, px_high = 0;
    for (const BenchRow* row : rows) {
        ns_low = std::min(ns_low, row->ns_per_point);
        ns_high = std::max(ns_high, row->ns_per_point);
        px_low = std::min(px_low, std::max(row->error->max_px, kErrorFloor));
        px_high = std::max(px_high, std::max(row->error->max_px, kErrorFloor));
    }
    // Room on the right for the labels of the slowest points.
    const Axes axes{cv::Rect(kLeft, kTop, kPanelWidth - kLeft - kRight, kPanelHeight - kTop - kBottom),
                    decades_around(ns_low, ns_high * 8), decades_around(px_low, px_high)};
    draw_axes(panel, axes, camera + " (" + rows.front()->model + "): unprojection, 1 thread");
    draw_legend(panel, axes);
    draw_points(panel, axes, rows);
    return panel;
}

// Whether a row ran on another instruction set than the one in use (a forced one).
bool forced_instruction_set(const BenchRow& row) {
    return simd_target_from_name(row.simd).has_value() && row.simd != simd_target_name(simd_target());
}

// The rows each panel shows: unprojection on one thread with a measured error, libcam's
// on the instruction set in use.
std::vector<std::vector<const BenchRow*>> panels_of(const std::vector<BenchRow>& rows) {
    std::vector<std::vector<const BenchRow*>> panels;
    std::vector<std::string> cameras;
    for (const BenchRow& row : rows) {
        if (row.op != "unproject" || row.threads != 1 || !row.error || row.error->count == 0 ||
            !std::isfinite(row.error->max_px) || !(row.ns_per_point > 0) || forced_instruction_set(row)) {
            continue;
        }
        const auto found = std::find(cameras.begin(), cameras.end(), row.camera);
        if (found == cameras.end()) {
            cameras.push_back(row.camera);
            panels.emplace_back();
        }
        panels[static_cast<std::size_t>(std::find(cameras.begin(), cameras.end(), row.camera) - cameras.begin())].push_back(&row);
    }
    return panels;
}

}  // namespace

Image plot_speed_accuracy(const std::vector<BenchRow>& rows) {
    const std::vector<std::vector<const BenchRow*>> panels = panels_of(rows);
    if (panels.empty()) throw Error("speed/accuracy plot: no unprojection rows on one thread with a measured error to draw");
    const int columns = panels.size() > 1 ? 2 : 1;
    const int lines = static_cast<int>((panels.size() + static_cast<std::size_t>(columns) - 1) / static_cast<std::size_t>(columns));
    cv::Mat image(lines * kPanelHeight, columns * kPanelWidth, CV_8UC3, kWhite);
    for (std::size_t i = 0; i < panels.size(); ++i) {
        const int column = static_cast<int>(i) % columns, line = static_cast<int>(i) / columns;
        draw_panel(panels[i].front()->camera, panels[i]).copyTo(image(cv::Rect(column * kPanelWidth, line * kPanelHeight, kPanelWidth, kPanelHeight)));
    }
    return detail::to_image(image);
}

}  // namespace libcam
