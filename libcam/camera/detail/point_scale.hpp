#pragma once
// Internal to libcam (camera.cpp, projector.cpp): when a camera point must be scaled
// before a model projects it.
//
// Every model projects a direction, so a camera point may be scaled by a power of two
// (exactly) without changing its pixel. PINHOLE and OpenCV's models divide by z first
// and need no scaling. The others form squares and norms of the coordinates, which is
// exact while the largest coordinate lies in [2^(min exponent / 4), 2^(max exponent /
// 4)] (2^-255 to 2^256 in double, 2^-31 to 2^32 in float), where no square or fourth
// power under- or overflows; a point outside is scaled into [1, 2) first
// (scaled_to_unit_range, geometry/vector_math.hpp).

#include <algorithm>
#include <cmath>
#include <limits>

#include "libcam/lens/lens_models.hpp"

namespace libcam::detail {

template <class Scalar>
constexpr Scalar power_of_two(int exponent) {
    Scalar value(1);
    for (; exponent > 0; --exponent) value *= Scalar(2);
    for (; exponent < 0; ++exponent) value /= Scalar(2);
    return value;
}

template <class Scalar>
bool in_comfortable_range(Scalar x, Scalar y, Scalar z) {
    using Limits = std::numeric_limits<Scalar>;
    constexpr Scalar low = power_of_two<Scalar>(Limits::min_exponent / 4);
    constexpr Scalar high = power_of_two<Scalar>(Limits::max_exponent / 4);
    const Scalar largest = std::max(std::abs(x), std::max(std::abs(y), std::abs(z)));
    return (largest >= low) & (largest <= high);  // &, not &&: no branch
}

// Whether Model needs the point scaled first.
template <class Model, class Scalar>
bool needs_scaling(Scalar x, Scalar y, Scalar z) {
    if constexpr (ProjectsRatios<Model>) {
        (void)x, (void)y, (void)z;
        return false;
    } else {
        return !in_comfortable_range(x, y, z);
    }
}

}  // namespace libcam::detail
