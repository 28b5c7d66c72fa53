#pragma once
// The field of view a camera sees through its lens, distortion included: on each axis,
// the angle between the rays through the image's two edges (the outer sides of the edge
// pixels, -0.5 and W - 0.5 on the row through the principal point; likewise down the
// column), measured through the optical axis, so that a fisheye's reaches past 180
// degrees. This is not the pinhole angle 2 atan(W / 2 fx) that K alone gives.

#include "libcam/camera/camera.hpp"

namespace libcam {

struct AxisFieldOfView {
    double degrees = 0.0;
    // False when the lens gives an edge no ray (a fisheye's image circle inside the image,
    // a lens that folds over): the angle is then to the outermost point on that line
    // that has one.
    bool edge_to_edge = true;
};

struct FieldOfView {
    AxisFieldOfView horizontal, vertical;
    // The largest angle from the optical axis the lens images (PreparedCamera::valid_angle).
    double valid_angle_deg = 0.0;
    // The share of the image's pixels (on a 64 x 64 lattice) that have no ray.
    double rayless_fraction = 0.0;
};

FieldOfView field_of_view(const PreparedCamera& camera);

}  // namespace libcam
