#pragma once
// The steps the remap code runs on a batch of pixels, written once (internal).

#include <cstddef>

#include "libcam/camera/batch.hpp"

namespace libcam::detail {

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
