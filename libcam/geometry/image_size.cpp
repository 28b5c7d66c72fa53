#include "libcam/geometry/image_size.hpp"

#include <string>

#include "libcam/error.hpp"

namespace libcam {

void ImageSize::validate(const char* field) const {
    auto check = [&](const char* side, long value) {
        if (value < 1 || value > kMaxImageSide) {
            throw InvalidArgument(std::string(field) + ": " + side + " must be an integer in [1, " +
                                  std::to_string(kMaxImageSide) + "], got " + std::to_string(value));
        }
    };
    check("width", width);
    check("height", height);
}

}  // namespace libcam
