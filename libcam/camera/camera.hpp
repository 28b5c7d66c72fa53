#pragma once
// Project these points, unproject these pixels: a calibrated camera and the engine that
// computes with it.
//
//   Camera: what a camera is (image size, intrinsic matrix K, lens, extrinsics R|t, all
//           in OpenCV's conventions, see geometry/intrinsics.hpp and geometry/pose.hpp);
//           what camera files hold and conversions produce. Plain data.
//   PreparedCamera: a Camera validated once, with its lens's valid domain worked out
//           once (and, on first unprojection, the table of the batch engine): every
//           projection and unprojection goes through one.
//
//   world point X -> camera point p = R X + t -> lens: normalised m -> pixel K [m; 1]
//
//   const PreparedCamera camera(read_camera_file("cam.yaml").camera);
//   std::vector<Projection> pixels = camera.project(world_points);
//   std::vector<Unprojection> rays = camera.unproject(pixels_to_unproject);
//
// Pixels here are OpenCV pixels (row 0 at the top, centres at integers). A point or a
// pixel is never an error: one the lens cannot map is returned with valid = false.
// For float, structure-of-arrays or full-frame batches see projector.hpp and
// unprojector.hpp, which share the same prepared state.

#include <memory>
#include <span>
#include <vector>

#include "libcam/geometry/image_size.hpp"
#include "libcam/geometry/intrinsics.hpp"
#include "libcam/geometry/pose.hpp"
#include "libcam/lens/lens_model.hpp"

namespace libcam {

struct Camera {
    ImageSize size;
    Intrinsics intrinsics;
    Lens lens;
    Pose pose;

    // Throws InvalidArgument naming the field for a bad size, K, lens or pose, and for a
    // camera whose numbers contradict each other: K not invertible over the image, or a
    // lens that has no ray, or changes its scale by more than 2, within the pixel next to
    // the principal point (camera.cpp says the rule).
    void validate() const;

    // P = K [R | t] (pinhole part only: distortion is not linear).
    Mat34 P() const { return intrinsics.K() * pose.matrix(); }
};

struct Projection {
    Vec2 pixel = Vec2::Zero();
    bool valid = false;  // false: outside the lens model's domain (e.g. behind the camera)
};

struct Unprojection {
    Vec3 direction = Vec3::Zero();  // camera frame, not normalised (see PreparedCamera::unproject)
    bool valid = false;             // false: the pixel has no ray under this lens
};

struct Ray {
    Vec3 origin = Vec3::Zero();     // the camera centre, world frame
    Vec3 direction = Vec3::Zero();  // unit length, world frame
    bool valid = false;             // false: the pixel has no ray under this lens
};

template <class Scalar>
class Unprojector;

namespace detail {
struct PreparedState;
}

class PreparedCamera {
public:
    // Validates the camera (throws InvalidArgument naming the field) and works out its
    // lens's valid domain (the radius where the distortion folds over).
    explicit PreparedCamera(const Camera& camera);

    const Camera& camera() const;
    // The lens's valid radius (lens/model_support.hpp): infinity where it has none.
    double valid_radius() const;
    // The largest angle from the optical axis the lens images, radians (pi: every
    // direction but the backward axis; below pi/2 for a perspective lens).
    double valid_angle() const;
    // The angle about the optical axis that no pixel sees, radians: 0 but for a
    // FISHEYE_LENS_POLYNOMIAL lens with k0 != 0 (lens_models.hpp's blind_angle).
    double blind_angle() const;

    // The pixel of a camera-frame point; invalid outside the lens model's domain
    // (behind the camera, past the radius where the distortion folds over, ...). Points
    // at any scale (1e-300, 1e300) give the pixel of their direction.
    Projection project_camera_point(const Vec3& camera_point) const;
    std::vector<Projection> project_camera_points(std::span<const Vec3> camera_points) const;
    // The same for world points (through R|t).
    Projection project(const Vec3& world_point) const;
    std::vector<Projection> project(std::span<const Vec3> world_points) const;

    // The direction, in the camera frame, of the ray through an OpenCV pixel, not
    // normalised: for PINHOLE and OpenCV's models K^-1 [x, y, 1] undistorted (z = 1), unit
    // length for the others. Invalid where the pixel has no ray, or none that
    // reprojects to it to rounding accuracy (the certified solver, lens/undistort.hpp).
    // A pixel's answer is the same bits in a single call and in any batch, with any
    // number of threads: both are the batch engine's `exact` method (unprojector.hpp),
    // whose table is built on the first call.
    Unprojection unproject(const Vec2& pixel) const;
    std::vector<Unprojection> unproject(std::span<const Vec2> pixels, int threads = 1) const;
    // The same into `out` (pixels.size() entries; throws InvalidArgument otherwise): no
    // allocation, for a caller that reuses its buffer.
    void unproject(std::span<const Vec2> pixels, std::span<Unprojection> out, int threads = 1) const;

    // The world-frame ray through an OpenCV pixel: origin at the camera centre,
    // direction R^T (the camera-frame direction) normalised.
    Ray ray(const Vec2& pixel) const;
    std::vector<Ray> rays(std::span<const Vec2> pixels, int threads = 1) const;

    // The batch engine these calls use (built on first use, shared by copies).
    const Unprojector<double>& unprojector() const;

private:
    std::shared_ptr<detail::PreparedState> state_;
};

}  // namespace libcam
