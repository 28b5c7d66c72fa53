#pragma once
// The statistics of a set of errors, computed by one rule for every report libcam makes
// (`libcam verify`, `libcam fit`, `libcam bench`).
//
// Quantiles are by NEAREST RANK: of n errors sorted in increasing order, the q-quantile
// is the one at rank ceil(q n), counting from 1 and clamped to [1, n]. It is always one
// of the measured errors, never an interpolation between two (which would mean nothing
// next to an infinite error). So the median of {1, 2, 3, 4} is 2, of {1, 2, 3} it is 2,
// and the p99 of 100 errors is the 99th smallest (of 1000, the 990th).
//
// An error that is NaN (a library gave no finite answer) counts as +infinity: infinitely
// wrong, never silently dropped.

#include <array>
#include <cstddef>
#include <string_view>
#include <span>
#include <vector>

namespace libcam {

struct ErrorStats {
    std::size_t count = 0;  // errors measured (points or pixels)
    double median_px = 0.0;
    double p99_px = 0.0;
    double max_px = 0.0;  // +inf when some error had no finite value
    double rms_px = 0.0;  // sqrt(mean of the squares); +inf likewise
    // With count 0 every other field is 0: a reader shows "no value", not a number.
};

ErrorStats error_stats(std::vector<double> errors_px);
// The same, reordering the caller's errors instead of copying them (a report of a million
// errors in groups).
ErrorStats error_stats_in_place(std::span<double> errors_px);

// One field of the statistics, by the name every report gives it (JSON keys, Python dict
// keys): count, median_px, p99_px, max_px, rms_px, in that order.
struct ErrorStatsField {
    std::string_view name;
    double value;
};
std::array<ErrorStatsField, 5> error_stats_fields(const ErrorStats& stats);

// The nearest-rank q-quantile (q in [0, 1]) of values sorted in increasing order; the
// values must not be empty.
double nearest_rank_quantile(std::span<const double> sorted, double q);

}  // namespace libcam
