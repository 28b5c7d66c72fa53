#pragma once
// Unprojection of many pixels at once, or of every pixel of the image, in float or
// double, by a method chosen per call (batch.hpp):
//
//   Unprojector<double> unprojector(camera);                // builds the table once
//   unprojector.unproject(pixels, UnprojectMethod::Fast, directions, valid);
//   unprojector.unproject_image(UnprojectMethod::Exact, directions, valid, /*threads=*/2);
//
// For the models solved iteratively (OpenCV's family, FISHEYE) the constructor tabulates
// the exact undistorted point u of a grid of pixels covering the image (and one node
// beyond each edge), solved by the certified solver of lens/undistort.hpp. Then
//   exact: u from the table (bilinear), two Newton steps (up to three more, each kept
//          only if it lowers the residual, for a pixel still above
//          reducible_residual()), and the residual checked against
//          unprojection_tolerance(); a pixel that fails goes to the full solver;
//   fast:  u from the table (bilinear) and one Newton step, no check;
//   lut:   u from the table (bicubic, Catmull-Rom), no model evaluation.
// Validity never depends on the approximation: a method settles a pixel only inside the
// certified disc (certified_radius()), whose every pixel has a ray in the lens's valid
// domain; any other pixel (past it, outside the table, next to a table node without a
// ray) goes to the full solver, in double for both scalar types. So every method, in
// float and in double, flags exactly the pixels Camera::unproject flags. Nor does the
// accuracy of fast and lut depend on the lens: they answer only in the cells where they
// were checked to reproject within UnprojectorOptions::approximation_budget_px.
//
// Directions are in the camera frame, as Camera::unproject gives them (z = 1 for PINHOLE
// and OpenCV's models, unit length for the others), and 0 where invalid. The result of
// each pixel is bit for bit the same for any number of threads.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "libcam/camera/batch.hpp"
#include "libcam/camera/camera.hpp"

namespace libcam {

struct UnprojectorOptions {
    // Table nodes along the image's longer side (the same spacing on the other). The
    // interpolation error falls with the square (bilinear) or the cube (bicubic) of the
    // spacing; 384 puts the lut method within 0.01 px on the real wide lens
    // (camera/example_cameras.hpp).
    int table_nodes = 384;
    // fast and lut answer only in the table cells where their estimate reprojects within
    // this many pixels at five checkpoints (the centre and the quarter points); the other
    // cells (next to a fold, where the inverse steepens) go to the full solver.
    double approximation_budget_px = 0.005;
    // Threads that build the table (one per core when 0). The table is the same bits for
    // any number.
    int threads = 0;
};

// The table of exact undistorted points (used by the models solved iteratively).
template <class Scalar>
struct UnprojectionTable {
    double origin_x = 0, origin_y = 0;  // pixel of node (0, 0)
    double step = 0;                    // pixels between nodes; 0: no table
    int nodes_x = 0, nodes_y = 0;
    // Each node's u, node by node and row by row (x, y of node 0, then of node 1, ...),
    // NaN where the pixel has no ray: a pixel's two top nodes are one contiguous read, as
    // are its two bottom ones.
    std::vector<Scalar> u_pairs;
    // Per cell, indexed by its top-left node: 1 where fast (lut) keeps within the budget.
    // Bytes, a pixel's read beside its nodes' (one eighth of the cache lines of doubles).
    std::vector<std::uint8_t> fast_ok, lut_ok;
};

namespace detail {
// Where the rays and flags of a run go (unprojector.cpp).
template <class Scalar>
struct RayOutput {
    Scalar* x;
    Scalar* y;
    Scalar* z;
    std::uint8_t* valid;

    RayOutput at(std::size_t first) const { return {x + first, y + first, z + first, valid + first}; }
};

// A block's rays and flags, for an output that is not structure-of-arrays.
template <class Scalar, std::size_t kCount>
struct RayScratch {
    Scalar x[kCount], y[kCount], z[kCount];
    std::uint8_t valid[kCount];
};

// The rim of the valid domain's image: its radius against its polar angle (unprojector.cpp).
struct DomainRim {
    std::vector<double> angle, radius;
};
}  // namespace detail

template <class Scalar>
class Unprojector {
public:
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;

    // Throws InvalidArgument for an invalid camera or options. From a PreparedCamera,
    // its validated camera and valid domain are used as they are.
    explicit Unprojector(const Camera& camera, UnprojectorOptions options = {});
    explicit Unprojector(const PreparedCamera& camera, UnprojectorOptions options = {});

    // The direction through each pixel; valid[i] = 0 where the pixel has no ray. Resizes
    // the outputs (no allocation when they already have the size).
    void unproject(const Points2<Scalar>& pixels, UnprojectMethod method, Points3<Scalar>& directions,
                   ValidFlags& valid, int threads = 1) const;

    // Every pixel of the image, row by row: entry y * width + x is pixel (x, y).
    void unproject_image(UnprojectMethod method, Points3<Scalar>& directions, ValidFlags& valid,
                         int threads = 1) const;

    // Entries [first, first + count) of that, on the calling thread: a part of the image
    // small enough for the cache, for a caller that goes on with its rays (the remap maps).
    // The same bits as unproject() on those pixels. Throws InvalidArgument for a range
    // past the image's last pixel.
    void unproject_image_part(UnprojectMethod method, std::size_t first, std::size_t count,
                              Points3<Scalar>& directions, ValidFlags& valid) const;

    // One pixel; false where it has no ray (direction then left as it was). The same
    // bits as the pixel gets in any batch.
    bool unproject(const Vec2T& pixel, UnprojectMethod method, Vec3T& direction) const;

    // Pixels and rays as lists of points (PreparedCamera::unproject's form): out must
    // have pixels.size() entries. Computed in Scalar.
    void unproject(std::span<const Vec2> pixels, UnprojectMethod method, std::span<Unprojection> out,
                   int threads = 1) const;

    // Interleaved arrays, as numpy's (N, 2) pixels and (N, 3) directions lie in memory:
    // pixel i is pixels[2 i .. 2 i + 1], its direction directions[3 i .. 3 i + 2] (0 where
    // it has no ray) and its flag valid[i]. The same bits as the other batch calls.
    // Throws InvalidArgument unless pixels has 2 n entries, directions 3 n and valid n,
    // and where the three arrays overlap.
    void unproject_interleaved(std::span<const Scalar> pixels, UnprojectMethod method, std::span<Scalar> directions,
                               std::span<std::uint8_t> valid, int threads = 1) const;

    const Camera& camera() const { return camera_; }
    // Every pixel whose normalised point m has |m| below this has a ray (0 without a table).
    double certified_radius() const { return certified_radius_; }
    // No pixel whose m has |m| above this has a ray (infinity if the domain is unbounded).
    double no_ray_radius() const { return no_ray_radius_; }
    const UnprojectionTable<Scalar>& table() const { return table_; }

private:
    template <class FillPixels, class Output>
    void run(std::size_t n, UnprojectMethod method, int threads, FillPixels&& fill, Output&& out) const;
    void prepare(const UnprojectorOptions& options);

    Camera camera_;
    double valid_radius_ = 0;
    double certified_radius_ = 0;
    double no_ray_radius_ = std::numeric_limits<double>::infinity();
    detail::DomainRim rim_;
    UnprojectionTable<Scalar> table_;
};

extern template class Unprojector<float>;
extern template class Unprojector<double>;

}  // namespace libcam
