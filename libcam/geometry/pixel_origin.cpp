#include "libcam/geometry/pixel_origin.hpp"

#include <string>

#include "libcam/error.hpp"

namespace libcam {

std::string_view to_string(PixelOrigin origin) {
    return origin == PixelOrigin::BottomLeft ? "bottom-left" : "top-left";
}

PixelOrigin pixel_origin_from_string(std::string_view text) {
    if (text == "bottom-left") return PixelOrigin::BottomLeft;
    if (text == "top-left") return PixelOrigin::TopLeft;
    throw InvalidArgument("pixel_origin: must be bottom-left or top-left, got '" + std::string(text) + "'");
}

Vec2 opencv_pixel(const Vec2& pixel, PixelOrigin origin, const ImageSize& size) {
    return origin == PixelOrigin::TopLeft ? pixel : Vec2(pixel.x(), flip_row(pixel.y(), size));
}

Vec2 user_pixel(const Vec2& opencv, PixelOrigin origin, const ImageSize& size) {
    return opencv_pixel(opencv, origin, size);  // the flip is its own inverse
}

}  // namespace libcam
