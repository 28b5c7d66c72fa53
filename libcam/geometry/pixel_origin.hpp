#pragma once
// Which way pixel rows are counted. Every calibrated camera (K, the camera files) counts
// them from the top (OpenCV's convention); the graphics camera's look-at formula counts
// them from the bottom. This only says how pixel coordinates given to or returned by
// libcam are counted: the geometry underneath is the same.

#include <string_view>
#include <type_traits>

#include "libcam/geometry/image_size.hpp"
#include "libcam/geometry/vector_math.hpp"

namespace libcam {

// Where the user's pixel row 0 is.
enum class PixelOrigin { BottomLeft, TopLeft };

std::string_view to_string(PixelOrigin origin);               // "bottom-left", "top-left"
PixelOrigin pixel_origin_from_string(std::string_view text);  // throws InvalidArgument

// A pixel's row in the other origin convention: y' = (H - 1) - y (its own inverse).
// A template on the scalar type so that the FOV formulas (graphics/look_at_formulas.hpp) run it
// in the tests' 113-bit reference type too.
template <class Scalar>
Scalar flip_row(const std::type_identity_t<Scalar>& y, const ImageSize& size) {
    return Scalar(size.height - 1) - y;
}
inline double flip_row(double y, const ImageSize& size) { return flip_row<double>(y, size); }

// The OpenCV (top-left) pixel of a pixel given in `origin`'s convention, and back.
Vec2 opencv_pixel(const Vec2& pixel, PixelOrigin origin, const ImageSize& size);
Vec2 user_pixel(const Vec2& opencv, PixelOrigin origin, const ImageSize& size);

}  // namespace libcam
