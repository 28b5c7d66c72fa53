#include "libcam/stats/error_stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace libcam {

double nearest_rank_quantile(std::span<const double> sorted, double q) {
    const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
    return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

ErrorStats error_stats(std::vector<double> errors_px) {
    ErrorStats stats;
    stats.count = errors_px.size();
    if (errors_px.empty()) return stats;
    double sum_squares = 0.0;
    for (double& error : errors_px) {
        if (std::isnan(error)) error = std::numeric_limits<double>::infinity();
        sum_squares += error * error;
    }
    std::sort(errors_px.begin(), errors_px.end());
    stats.median_px = nearest_rank_quantile(errors_px, 0.5);
    stats.p99_px = nearest_rank_quantile(errors_px, 0.99);
    stats.max_px = errors_px.back();
    stats.rms_px = std::sqrt(sum_squares / static_cast<double>(errors_px.size()));
    return stats;
}

}  // namespace libcam
