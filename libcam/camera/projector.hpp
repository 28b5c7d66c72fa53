#pragma once
// Projection of many points at once, in float or double: the lens's constants are
// worked out once per camera, the points come and go as structure-of-arrays
// (batch.hpp), the loop over points is vectorised, and it can be split over threads.
//
//   Projector<double> projector(camera);
//   projector.project(camera_points, pixels, valid, /*threads=*/2);
//
// The result of each point is bit for bit the same for any number of threads, and
// (in double) the same as PreparedCamera::project_camera_point's.

#include <cstdint>
#include <span>

#include "libcam/camera/batch.hpp"
#include "libcam/camera/camera.hpp"

namespace libcam {

template <class Scalar>
class Projector {
public:
    // Throws InvalidArgument for an invalid camera. From a PreparedCamera, its
    // validated camera and valid domain are used as they are.
    explicit Projector(const Camera& camera);
    explicit Projector(const PreparedCamera& camera);

    // The pixel of each camera-frame point; valid[i] = 0, and pixel (0, 0), outside the
    // lens's domain (behind the camera, past the fold-over radius, ...) or where the
    // pixel passes the largest Scalar. Points at any scale (1e-300, 1e300) give the
    // pixel of their direction, as in Camera. Resizes the outputs (no allocation when
    // they already have the size).
    void project(const Points3<Scalar>& camera_points, Points2<Scalar>& pixels, ValidFlags& valid,
                 int threads = 1) const;

    // The same on the caller's memory, without copies: point i is (x[i], y[i], z[i]), its
    // pixel (pixel_x[i], pixel_y[i]) and its flag valid[i], as in a (3, N) array's rows or
    // the columns of a Fortran-ordered (N, 3) one. Throws InvalidArgument unless every
    // span has valid's length n, and where a pixel array overlaps a point array, the flags
    // or the other pixel array.
    void project(std::span<const Scalar> x, std::span<const Scalar> y, std::span<const Scalar> z,
                 std::span<Scalar> pixel_x, std::span<Scalar> pixel_y, std::span<std::uint8_t> valid,
                 int threads = 1) const;

    // The same for interleaved arrays, as numpy's (N, 3) and (N, 2) arrays and a list of
    // Eigen vectors lie in memory: point i is camera_points[3 i .. 3 i + 2], its pixel
    // pixels[2 i .. 2 i + 1] and its flag valid[i]. The same bits as project(). Throws
    // InvalidArgument unless camera_points has 3 n entries, pixels 2 n and valid n, and
    // where the three arrays overlap.
    void project_interleaved(std::span<const Scalar> camera_points, std::span<Scalar> pixels,
                             std::span<std::uint8_t> valid, int threads = 1) const;

    const Camera& camera() const { return camera_; }

private:
    Camera camera_;
    double valid_radius_;
};

extern template class Projector<float>;
extern template class Projector<double>;

}  // namespace libcam
