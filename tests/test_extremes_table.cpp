// The table of issue 5 (README, "Numerical limits"): every row of extremes.hpp with
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

std::string number(double value) {
    if (std::isnan(value)) return "n/a";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer,
                  value == 0 || (std::abs(value) >= 0.01 && std::abs(value) < 1e4) ? "%.3g" : "%.2g", value);
    return buffer;
}

void print_table(const std::vector<Row>& rows) {
    std::cout << "| extreme | error | double | float | bound (double / float) | formulation |\n"
              << "|---|---|---|---|---|---|\n";
    std::string previous;
    for (const Row& row : rows) {
        std::cout << "| " << (row.extreme == previous ? "" : row.extreme) << " | " << row.quantity << " | "
                  << number(row.in_double) << " | " << number(row.in_float) << " | " << number(row.bound_double)
                  << " / " << number(row.bound_float) << " | " << row.formulation << " |\n";
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
}
