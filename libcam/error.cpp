#include "libcam/error.hpp"

#include "libcam/text/shown_value.hpp"

namespace libcam {

Error::Error(const std::string& message) : std::runtime_error(printable_text(message, 4 * kShownMessageLength)) {}

Error::Error(const char* message) : Error(std::string(message)) {}

void require_finite(const char* field, double value) {
    if (!std::isfinite(value)) {
        throw InvalidArgument(std::string(field) + ": must be finite, got " + format_number(value));
    }
}

}  // namespace libcam
