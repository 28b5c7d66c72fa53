// The table of numerical limits (docs/numerical-limits.md): every row of extremes.hpp with
// its measured worst error in double and in float and the asserted bound.
//
//     build/tests/test_extremes "[table]"        (hidden: not run by ctest)

#include <catch2/catch.hpp>
#include <cstdio>
#include <iostream>
#include <string>

#include "extremes.hpp"

namespace libcam::test {

namespace {

// A measured value; NaN is "n/a" where nothing is asserted, else a measured NaN.
std::string number(double value, double bound) {
    if (std::isnan(value)) return std::isnan(bound) ? "n/a" : "NaN";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer,
                  value == 0 || (std::abs(value) >= 0.01 && std::abs(value) < 1e4) ? "%.3g" : "%.2g", value);
    return buffer;
}

// Markdown: a '|' inside a cell (|m|, R|t) must be escaped.
std::string cell(const std::string& text) {
    std::string out;
    for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

void print_table(const std::vector<Row>& rows) {
    std::cout << "| extreme | error | double | float | bound (double / float) | formulation |\n"
              << "|---|---|---|---|---|---|\n";
    std::string previous;
    for (const Row& row : rows) {
        std::cout << "| " << (row.extreme == previous ? "" : cell(row.extreme)) << " | " << cell(row.quantity) << " | "
                  << number(row.in_double, row.bound_double) << " | " << number(row.in_float, row.bound_float) << " | "
                  << number(row.bound_double, row.bound_double) << " / " << number(row.bound_float, row.bound_float)
                  << " | " << cell(row.formulation) << " |\n";
        previous = row.extreme;
    }
}

}  // namespace

void check_rows(const std::vector<Row>& rows) {
    for (const Row& row : rows) {
        INFO(row.extreme << ": " << row.quantity << "; double " << row.in_double << " (worst at " << row.worst_at
                         << "), float " << row.in_float);
        if (!std::isnan(row.bound_double)) CHECK(row.in_double <= row.bound_double);
        if (!std::isnan(row.bound_float)) CHECK(row.in_float <= row.bound_float);
    }
}

}  // namespace libcam::test

TEST_CASE("the table of numerical limits", "[.][table]") {
    using namespace libcam::test;
    std::vector<Row> rows = fov_rows();
    const std::vector<Row> lens = lens_rows();
    rows.insert(rows.end(), lens.begin(), lens.end());
    print_table(rows);
    std::cout << "\n";
    print_table(batch_rows());
}
