#include "libcam/error.hpp"

namespace libcam {

void require_finite(const char* field, double value) {
    if (!std::isfinite(value)) {
        throw InvalidArgument(std::string(field) + ": must be finite, got " + format_number(value));
    }
}

}  // namespace libcam
