#include "uncertainty_output.hpp"

#include <cmath>
#include <sstream>

#include "libcam/report/uncertainty_heatmap.hpp"
#include "libcam/text/number_format.hpp"
#include "parse.hpp"

namespace libcam::cli {

std::vector<Vec2> at_pixels(const std::vector<std::string>& texts, const ImageSize& size) {
    std::vector<Vec2> pixels;
    for (const std::string& text : texts) {
        const Vec2 pixel = parse_vec2("--at", text);
        if (!on_image(pixel.x(), pixel.y(), size)) {
            throw UsageError("--at: pixel (" + format_short(pixel.x()) + ", " + format_short(pixel.y()) +
                             ") is off the " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                             " image (OpenCV's pixels: x from -0.5 to " + format_short(size.width - 0.5) +
                             ", y from -0.5 to " + format_short(size.height - 0.5) + ")");
        }
        pixels.push_back(pixel);
    }
    return pixels;
}

Json at_json(const std::vector<Vec2>& pixels, const std::vector<double>& sigma_px) {
    Json out = Json::array();
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        out.push_back({{"pixel", {pixels[i].x(), pixels[i].y()}}, {"sigma_px", finite_or_null(sigma_px[i])}});
    }
    return out;
}

std::string at_lines(const std::vector<Vec2>& pixels, const std::vector<double>& sigma_px) {
    std::ostringstream out;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        out << "  at (" << format_short(pixels[i].x(), 7) << ", " << format_short(pixels[i].y(), 7) << "): ";
        if (std::isfinite(sigma_px[i])) out << "sigma " << format_short(sigma_px[i], 4) << " px\n";
        else out << "no ray through this pixel\n";
    }
    return out.str();
}

std::string distance_words(double distance) {
    return std::isinf(distance) ? "points at infinity" : "points " + format_short(distance) + " away (the board's unit)";
}

std::string summary_lines(const UncertaintySummary& summary) {
    std::ostringstream out;
    out << "  worst inside the region the corners covered: ";
    if (summary.observed_tiles == 0) out << "no grid point inside it\n";
    else if (std::isnan(summary.worst_observed_px)) out << "a pixel there has no ray\n";
    else out << format_short(summary.worst_observed_px, 4) << " px\n";
    out << "  the image under 0.1 px: " << format_short(100.0 * summary.share_below_0_1, 3) << "%, under 1 px: "
        << format_short(100.0 * summary.share_below_1, 3) << "%\n";
    return out.str();
}

std::string parameter_lines(const std::vector<ParameterSpread>& parameters) {
    std::ostringstream out;
    for (const ParameterSpread& p : parameters) {
        out << "  " << p.name << " " << format_short(p.value, 6) << " +- " << format_short(p.stdev, 3);
        if (p.stdev > std::abs(p.value)) out << "  (larger than its value: the data do not pin it down)";
        out << "\n";
    }
    return out.str();
}

Json parameters_json(const std::vector<ParameterSpread>& parameters) {
    Json out = Json::array();
    for (const ParameterSpread& p : parameters) {
        out.push_back({{"name", p.name}, {"value", p.value}, {"stdev", finite_or_null(p.stdev)}});
    }
    return out;
}

void write_uncertainty_heatmap(const std::string& path, const UncertaintyMap& map, const SolvedCalibration& solved,
                               const std::string& caption) {
    std::vector<Vec2> observed;
    for (const FitView& view : solved.views) {
        for (const FitSample& o : view.observations) observed.push_back(o.pixel);
    }
    write_png(path, uncertainty_heatmap(map, observed, observed_region(solved), caption));
}

}  // namespace libcam::cli
