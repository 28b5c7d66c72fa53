#pragma once
// The steps the remap code runs on a batch of pixels, written once (internal).

#include <cstddef>

#include "libcam/camera/batch.hpp"

namespace libcam::detail {

// Pixels first, first + 1, ... first + count - 1 of an image `width` wide, row by row.
inline void image_pixels(Points2<double>& pixels, std::size_t first, std::size_t count, std::size_t width) {
    pixels.resize(count);
    for (std::size_t j = 0; j < count; ++j) {
        pixels.x[j] = static_cast<double>((first + j) % width);
        pixels.y[j] = static_cast<double>((first + j) / width);
    }
}

// Each direction d replaced by rotation * d.
inline void turn(Points3<double>& rays, const Mat3& rotation) {
    for (std::size_t j = 0; j < rays.size(); ++j) {
        const Vec3 d = rotation * Vec3(rays.x[j], rays.y[j], rays.z[j]);
        rays.x[j] = d.x();
        rays.y[j] = d.y();
        rays.z[j] = d.z();
    }
}

}  // namespace libcam::detail
