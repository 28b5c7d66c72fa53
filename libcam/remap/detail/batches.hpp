#pragma once
// The steps the remap code runs on a batch of pixels, written once (internal).

#include <algorithm>
#include <cstddef>

#include "libcam/camera/batch.hpp"

namespace libcam::detail {

// Pixels first, first + 1, ... first + count - 1 of an image `width` wide, row by row.
// (One division for the batch, not two per pixel: a 64-bit division costs more than
// the rest of a pinhole's unprojection.)
inline void image_pixels(Points2<double>& pixels, std::size_t first, std::size_t count, std::size_t width) {
    pixels.resize(count);
    std::size_t column = first % width, row = first / width;
    for (std::size_t j = 0; j < count; column = 0, ++row) {  // row segment by row segment
        const std::size_t run = std::min(count - j, width - column);
        for (std::size_t i = 0; i < run; ++i) {
            pixels.x[j + i] = static_cast<double>(column + i);
            pixels.y[j + i] = static_cast<double>(row);
        }
        j += run;
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
