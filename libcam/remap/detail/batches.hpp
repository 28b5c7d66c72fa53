#pragma once
// The steps the remap code runs on a batch of pixels, written once (internal).

#include <algorithm>
#include <cstddef>

#include "libcam/camera/batch.hpp"
#include "libcam/geometry/intrinsics.hpp"

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

// The rays of pixels first, ... first + count - 1 of a PINHOLE camera `width` wide, as its
// unprojection gives them (K^-1 [x y 1], z = 1, normalized_from_pixel's arithmetic), each
// turned by `rotation` where `turned`. Row segment by row segment: the row's yn once,
// then a loop over the columns that vectorises.
inline void pinhole_rays(Points3<double>& rays, std::size_t first, std::size_t count, std::size_t width,
                         const Intrinsics& intrinsics, const Mat3& rotation, bool turned) {
    rays.resize(count);
    const double inverse_fx = 1.0 / intrinsics.fx, inverse_fy = 1.0 / intrinsics.fy;
    double* __restrict x = rays.x.data();
    double* __restrict y = rays.y.data();
    double* __restrict z = rays.z.data();
    std::size_t column = first % width, row = first / width;
    for (std::size_t j = 0; j < count; column = 0, ++row) {
        const std::size_t run = std::min(count - j, width - column);
        const double yn = (static_cast<double>(row) - intrinsics.cy) * inverse_fy;
        const double cx = intrinsics.cx, skew_yn = intrinsics.skew * yn;
        if (!turned) {
            for (std::size_t i = 0; i < run; ++i) {
                x[j + i] = (static_cast<double>(column + i) - cx - skew_yn) * inverse_fx;
                y[j + i] = yn;
                z[j + i] = 1.0;
            }
        } else {
            // rotation * (xn, yn, 1) = xn column 0 + (yn column 1 + column 2)
            const Vec3 row_part = rotation.col(1) * yn + rotation.col(2);
            const Vec3 per_xn = rotation.col(0);
            for (std::size_t i = 0; i < run; ++i) {
                const double xn = (static_cast<double>(column + i) - cx - skew_yn) * inverse_fx;
                x[j + i] = per_xn.x() * xn + row_part.x();
                y[j + i] = per_xn.y() * xn + row_part.y();
                z[j + i] = per_xn.z() * xn + row_part.z();
            }
        }
        j += run;
    }
}

}  // namespace libcam::detail
