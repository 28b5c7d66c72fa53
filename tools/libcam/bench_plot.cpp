#include "bench_plot.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "libcam/error.hpp"

namespace libcam::cli {

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
    put_text(panel, title, {kLeft + 150, 30}, 0.65, kBlack);
}

std::string point_label(const BenchRow& row) {
    std::string label = row.library + " " + row.method;
    if (row.scalar == "float") label += " (float)";
    if (row.invalid_fraction > 0) {
        label += " [" + std::to_string(static_cast<int>(std::lround(100 * row.invalid_fraction))) + "% no ray]";
    }
    return label;
}

// Labels right of their point, moved down past any label already placed.
class LabelPlacer {
public:
    cv::Point place(const std::string& text, cv::Point point, const cv::Rect& bounds) {
        int baseline = 0;
        const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, 0.45, 1, &baseline);
        cv::Rect box(point.x + 8, point.y - size.height / 2, size.width, size.height + baseline);
        if (box.x + box.width > bounds.x + bounds.width) box.x = point.x - 8 - size.width;  // no room on the right
        for (int tries = 0; tries < 40 && overlaps(box); ++tries) box.y += size.height + 2;
        placed_.push_back(box);
        return {box.x, box.y + size.height};
    }

private:
    bool overlaps(const cv::Rect& box) const {
        return std::any_of(placed_.begin(), placed_.end(), [&](const cv::Rect& r) { return (r & box).area() > 0; });
    }
    std::vector<cv::Rect> placed_;
};

void draw_points(cv::Mat& panel, const Axes& axes, const std::vector<const BenchRow*>& rows) {
    LabelPlacer labels;
    for (const BenchRow* row : rows) {
        const cv::Point p = axes.at(row->ns_per_point, row->error->max_px);
        const cv::Scalar colour = library_colour(row->library);
        if (row->scalar == "float") {
            cv::rectangle(panel, {p.x - 5, p.y - 5}, {p.x + 5, p.y + 5}, colour, cv::FILLED);
        } else {
            cv::circle(panel, p, 6, colour, cv::FILLED, cv::LINE_AA);
        }
        put_text(panel, point_label(*row), labels.place(point_label(*row), p, axes.area), 0.45, colour);
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
    draw_points(panel, axes, rows);
    return panel;
}

// The rows each panel shows: unprojection on one thread with a measured error.
std::vector<std::vector<const BenchRow*>> panels_of(const std::vector<BenchRow>& rows) {
    std::vector<std::vector<const BenchRow*>> panels;
    std::vector<std::string> cameras;
    for (const BenchRow& row : rows) {
        if (row.op != "unproject" || row.threads != 1 || !row.error || !(row.ns_per_point > 0)) continue;
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

std::vector<unsigned char> plot_speed_accuracy(const std::vector<BenchRow>& rows) {
    const std::vector<std::vector<const BenchRow*>> panels = panels_of(rows);
    if (panels.empty()) throw Error("--plot: no unprojection rows to draw");
    const int columns = panels.size() > 1 ? 2 : 1;
    const int lines = static_cast<int>((panels.size() + static_cast<std::size_t>(columns) - 1) / static_cast<std::size_t>(columns));
    cv::Mat image(lines * kPanelHeight, columns * kPanelWidth, CV_8UC3, kWhite);
    for (std::size_t i = 0; i < panels.size(); ++i) {
        const int column = static_cast<int>(i) % columns, line = static_cast<int>(i) / columns;
        draw_panel(panels[i].front()->camera, panels[i]).copyTo(image(cv::Rect(column * kPanelWidth, line * kPanelHeight, kPanelWidth, kPanelHeight)));
    }
    std::vector<unsigned char> png;
    if (!cv::imencode(".png", image, png)) throw Error("--plot: OpenCV could not encode the PNG");
    return png;
}

}  // namespace libcam::cli
