#pragma once
// What every subcommand's --json shares: numbers that JSON can hold, and the error
// statistics under the names every report uses.

#include <cmath>
#include <initializer_list>
#include <string_view>
#include <nlohmann/json.hpp>

#include "libcam/stats/error_stats.hpp"

namespace libcam::cli {

using Json = nlohmann::ordered_json;

// JSON has no infinity or NaN: a value without a finite number is null.
template <class J = Json>
J finite_or_null(double value) {
    return std::isfinite(value) ? J(value) : J(nullptr);
}

// The statistics' fields (error_stats_fields) named in `keys` into `out`, in `keys`' order;
// each null when nothing was measured.
template <class J>
void put_error_stats(J& out, const ErrorStats& stats, bool measured, std::initializer_list<std::string_view> keys) {
    for (const std::string_view key : keys) {
        for (const ErrorStatsField& field : error_stats_fields(stats)) {
            if (field.name == key) out[std::string(key)] = measured ? finite_or_null<J>(field.value) : J(nullptr);
        }
    }
}

}  // namespace libcam::cli
