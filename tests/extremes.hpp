#pragma once
// The numerical extremes as rows of one table: each row is one error measured at one
// extreme, in double and in float, against the 113-bit reference (reference.hpp) or a
// hand formula, with the bound the tests assert. The test cases check the rows; the
// hidden test case "[table]" prints them all (docs/numerical-limits.md):
//
//     build/tests/test_extremes "[table]"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace libcam::test {

inline constexpr double kNotApplicable = std::numeric_limits<double>::quiet_NaN();

struct Row {
    std::string extreme;                // the inputs swept
    std::string quantity;               // what is compared with what, and the unit
    double in_double = kNotApplicable;  // worst measured
    double in_float = kNotApplicable;
    double bound_double = kNotApplicable;  // asserted: in_double <= bound_double
    double bound_float = kNotApplicable;
    std::string formulation;  // what keeps it stable
    std::string worst_at;     // where the double worst was seen (for the test log)
};

// Every measurement, in table order.
std::vector<Row> fov_rows();
std::vector<Row> lens_rows();
// The batch paths (Projector, Unprojector's exact, fast and lut) at the same extremes.
std::vector<Row> batch_rows();

// CHECKs each measured value against its bound (a NaN measurement fails).
void check_rows(const std::vector<Row>& rows);

}  // namespace libcam::test
