#pragma once
// A calibrated camera: image size, intrinsic matrix K, lens, and extrinsics R|t, all
// in OpenCV's conventions (see geometry/intrinsics.hpp and geometry/pose.hpp).
//
//   world point X -> camera point p = R X + t -> lens: normalised m -> pixel K [m; 1]
//
// Pixels here are OpenCV pixels (row 0 at the top, centres at integers).

#include "libcam/geometry/image_size.hpp"
#include "libcam/geometry/intrinsics.hpp"
#include "libcam/geometry/pose.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam {

struct Projection {
    Vec2 pixel = Vec2::Zero();
    bool valid = false;  // false: outside the lens model's domain (e.g. behind the camera)
};

struct Ray {
    Vec3 origin = Vec3::Zero();     // the camera centre, world frame
    Vec3 direction = Vec3::Zero();  // unit length, world frame
    bool valid = false;             // false: the pixel has no ray under this lens
};

struct Camera {
    ImageSize size;
    Intrinsics intrinsics;
    Lens lens;
    Pose pose;

    // Throws InvalidArgument naming the field for a bad size, K, lens or pose.
    void validate() const;

    // P = K [R | t] (pinhole part only: distortion is not linear).
    Mat34 P() const { return intrinsics.K() * pose.matrix(); }

    Projection project_camera_point(const Vec3& camera_point) const;
    Projection project(const Vec3& world_point) const {
        return project_camera_point(pose.camera_from_world(world_point));
    }

    // The direction, in the camera frame, of the ray through an OpenCV pixel; for a
    // pinhole lens K^-1 [x, y, 1] (z = 1, not normalised).
    bool unproject(const Vec2& pixel, Vec3& camera_direction) const;

    // The world-frame ray through an OpenCV pixel: origin at the camera centre,
    // direction R^T K^-1 [x, y, 1] normalised.
    Ray ray(const Vec2& pixel) const;
};

}  // namespace libcam
