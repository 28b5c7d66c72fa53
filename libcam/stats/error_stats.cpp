#include "libcam/stats/error_stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace libcam {

namespace {
// The 0-based index of the nearest-rank q-quantile among n values.
std::size_t nearest_rank_index(std::size_t n, double q) {
    const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(n)));
    return std::clamp<std::size_t>(rank, 1, n) - 1;
}
}  // namespace

double nearest_rank_quantile(std::span<const double> sorted, double q) {
    return sorted[nearest_rank_index(sorted.size(), q)];
}

ErrorStats error_stats(std::vector<double> errors_px) { return error_stats_in_place(errors_px); }

ErrorStats error_stats_in_place(std::span<double> errors_px) {
    ErrorStats stats;
    stats.count = errors_px.size();
    if (errors_px.empty()) return stats;
    double sum_squares = 0.0;
    for (double& error : errors_px) {
        if (std::isnan(error)) error = std::numeric_limits<double>::infinity();
        sum_squares += error * error;
    }
    // The same values a full sort gives, by selection (linear time: a report sorts
    // millions of errors otherwise). The median's selection leaves every larger value
    // after it, where the p99's is then selected.
    const auto at = [&](std::size_t index) { return errors_px.begin() + static_cast<std::ptrdiff_t>(index); };
    const std::size_t median = nearest_rank_index(errors_px.size(), 0.5);
    const std::size_t p99 = nearest_rank_index(errors_px.size(), 0.99);
    std::nth_element(errors_px.begin(), at(median), errors_px.end());
    stats.median_px = *at(median);
    // The second selection reorders what follows the median, not the median itself.
    if (p99 > median) std::nth_element(at(median + 1), at(p99), errors_px.end());
    stats.p99_px = *at(p99);
    stats.max_px = *std::max_element(at(p99), errors_px.end());
    stats.rms_px = std::sqrt(sum_squares / static_cast<double>(errors_px.size()));
    return stats;
}

std::array<ErrorStatsField, 5> error_stats_fields(const ErrorStats& stats) {
    return {{{"count", static_cast<double>(stats.count)},
             {"median_px", stats.median_px},
             {"p99_px", stats.p99_px},
             {"max_px", stats.max_px},
             {"rms_px", stats.rms_px}}};
}

}  // namespace libcam
