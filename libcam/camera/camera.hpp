#pragma once
// A calibrated camera: image size, intrinsic matrix K, lens, and extrinsics R|t, all
// in OpenCV's conventions (see geometry/intrinsics.hpp and geometry/pose.hpp).
//
//   world point X -> camera point p = R X + t -> lens: normalised m -> pixel K [m; 1]
//
// Pixels here are OpenCV pixels (row 0 at the top, centres at integers).

#include <span>
#include <vector>

#include "libcam/geometry/image_size.hpp"
#include "libcam/geometry/intrinsics.hpp"
#include "libcam/geometry/pose.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam {

struct Projection {
    Vec2 pixel = Vec2::Zero();
    bool valid = false;  // false: outside the lens model's domain (e.g. behind the camera)
};

struct Unprojection {
    Vec3 direction = Vec3::Zero();  // camera frame, not normalised (see Camera::unproject)
    bool valid = false;             // false: the pixel has no ray under this lens
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

    // Throws InvalidArgument naming the field for a bad size, K, lens or pose. Every
    // function below checks what it uses (K and the lens; the pose too for world
    // points and rays) on each call, and throws the same.
    void validate() const;

    // P = K [R | t] (pinhole part only: distortion is not linear).
    Mat34 P() const { return intrinsics.K() * pose.matrix(); }

    // The pixel of a camera-frame point; invalid outside the lens model's domain
    // (behind the camera, past the radius where the distortion folds over, ...).
    Projection project_camera_point(const Vec3& camera_point) const;
    Projection project(const Vec3& world_point) const;
    // Many points at once: the lens's valid domain is worked out once, not per point.
    std::vector<Projection> project_camera_points(std::span<const Vec3> camera_points) const;

    // The direction, in the camera frame, of the ray through an OpenCV pixel, not
    // normalised: for PINHOLE and OpenCV's models K^-1 [x, y, 1] undistorted (z = 1).
    // False where the pixel has no ray, or none that reprojects to it to rounding
    // accuracy (see lens/undistort.hpp).
    bool unproject(const Vec2& pixel, Vec3& camera_direction) const;
    // Many pixels at once, the lens's domain worked out once.
    std::vector<Unprojection> unproject_pixels(std::span<const Vec2> pixels) const;

    // The world-frame ray through an OpenCV pixel: origin at the camera centre,
    // direction R^T K^-1 [x, y, 1] normalised.
    Ray ray(const Vec2& pixel) const;

private:
    void validate_lens_and_k() const;
};

}  // namespace libcam
