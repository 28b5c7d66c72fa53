#include "libcam/text/number_format.hpp"

#include <charconv>
#include <cstdio>

namespace libcam {

std::string format_number(double value) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string format_short(double value, int significant_digits) {
    char buffer[64];
    // %g never writes more than 17 significant digits that mean anything; a larger
    // request would only add noise (and could not fit the buffer at any exponent).
    const int digits = significant_digits < 1 ? 1 : significant_digits > 17 ? 17 : significant_digits;
    const int length = std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    return std::string(buffer, static_cast<std::size_t>(length));
}

}  // namespace libcam
