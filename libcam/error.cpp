#include "libcam/error.hpp"

#include <charconv>

namespace libcam {

std::string format_number(double value) {
    char buffer[64];
    // Shortest representation that round-trips exactly.
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

void require_finite(const char* field, double value) {
    if (!std::isfinite(value)) {
        throw InvalidArgument(std::string(field) + ": must be finite, got " + format_number(value));
    }
}

}  // namespace libcam
