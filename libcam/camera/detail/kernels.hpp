#pragma once
// Internal to libcam: the batch kernels, compiled once per instruction set
// (camera/simd.hpp, camera/detail/kernels_for_target.hpp), and what passes between them and
// the code that calls them (camera/projector.cpp, camera/unprojector.cpp). Everything
// here is compiled for the portable baseline.

#include <cstddef>
#include <cstdint>

#include "libcam/camera/detail/batch_kernels.hpp"
#include "libcam/camera/camera.hpp"
#include "libcam/camera/simd.hpp"
#include "libcam/camera/unprojector.hpp"

namespace libcam::kernels {

using batch::kBlock;

// Points [begin, end) of a projection: camera points in, pixels and flags out. Point i's
// coordinates are x[i * s], y[i * s], z[i * s] and its pixel pixel_x[i * p], pixel_y[i * p],
// with s = p = 1 for structure-of-arrays and s = 3, p = 2 for interleaved arrays (numpy's
// (N, 3) and (N, 2)), where y = x + 1, z = x + 2 and pixel_y = pixel_x + 1.
template <class Scalar>
struct ProjectJob {
    const Camera& camera;
    double valid_radius;
    const Scalar *x, *y, *z;
    Scalar *pixel_x, *pixel_y;
    std::uint8_t* valid;
};

// One block of pixels on its way through the unprojection steps.
template <class Scalar>
struct Block {
    std::size_t count = 0;
    const Scalar* pixel_x;  // the block's pixels: the caller's arrays, or made_x, made_y
    const Scalar* pixel_y;
    Scalar made_x[kBlock], made_y[kBlock];  // pixels made by the caller (the whole image, one pixel)
    Scalar m_x[kBlock], m_y[kBlock];  // K^-1 [x, y, 1]
    Scalar u_x[kBlock], u_y[kBlock];  // undistorted point
    Scalar ok[kBlock];  // 1: u (then the ray) is the answer; -1: settled, no ray; 0: for the full solver
    Scalar reducible[kBlock];  // 1: u passes, but another Newton step would gain digits (certify)
    detail::RayOutput<Scalar> rays;                 // where the block's rays and flags go
    Scalar* ray_groups = nullptr;  // or its rays interleaved: x, y, z of ray i at s i (RayLayout's stride s)
    int cell[kBlock];                               // table node at the top-left of the pixel's cell
    Scalar fraction_x[kBlock], fraction_y[kBlock];  // position within that cell
};

// Where an unprojection's pixels come from and its rays go, block by block.
template <class Scalar>
class BlockIo {
public:
    using Scratch = detail::RayScratch<Scalar, kBlock>;
    // Points b.pixel_x and b.pixel_y at the pixels of [first, first + b.count).
    virtual void fill(std::size_t first, Block<Scalar>& b) const = 0;
    // Where the rays and flags of the block at `first` go (the caller's arrays, or scratch).
    virtual detail::RayOutput<Scalar> at(std::size_t first, Scratch& scratch) const = 0;
    // Called after each block.
    virtual void done(std::size_t first, std::size_t count, const Scratch& scratch) const = 0;

protected:
    ~BlockIo() = default;
};

// Pixels and rays as numpy's (N, 2) and (N, 3) arrays: the kernel copies each block's
// pixels in and writes its rays out itself, compiled for its instruction set.
template <class Scalar>
struct InterleavedIo {
    const Scalar* pixels;  // x, y of pixel i at 2 i, 2 i + 1
    Scalar* directions;    // x, y, z of its ray at 3 i .. 3 i + 2
    std::uint8_t* valid;
};

// Pixels as a list of Vec2 and rays into a list of Unprojection entries
// (PreparedCamera::unproject's form): the pixels are pairs as in InterleavedIo, the rays
// groups of four doubles (an entry's direction, then the eight bytes that hold its flag),
// the flags bools one entry apart. Given for Scalar = double only: the lists hold doubles.
template <class Scalar>
struct EntryIo {
    const Scalar* pixels;     // x, y of pixel i at 2 i, 2 i + 1
    Scalar* directions;       // x, y, z of its ray at 4 i .. 4 i + 2
    bool* valid;              // its flag at valid + entry_bytes i
    std::size_t entry_bytes;  // sizeof(Unprojection)
};

// Pixels [begin, end) of an unprojection: from and to `io`, or `interleaved` or
// `entries` where one is given.
template <class Scalar>
struct UnprojectJob {
    const Camera& camera;
    double valid_radius;
    double certified_radius;
    double no_ray_radius;
    const detail::DomainRim& rim;
    const UnprojectionTable<Scalar>& table;
    UnprojectMethod method;
    const BlockIo<Scalar>* io;
    const InterleavedIo<Scalar>* interleaved = nullptr;
    const EntryIo<Scalar>* entries = nullptr;
};

// A remap map (remap/remap_map.hpp): entry k, the target's pixel (k % width, k / width),
// holds the source pixel that sees its ray.
struct MapJob {
    const Camera& source;
    double source_valid_radius;
    const Intrinsics* target_intrinsics;  // a PINHOLE target, whose rays are K^-1 [x, y, 1]; else nullptr
    Mat3 to_source;                       // a direction in the target's frame into the source's
    bool turned;                          // whether to_source turns (is not the identity)
    std::size_t width;                    // the target image's
};

// The target's rays of a run of entries, from its unprojection (in the target's frame).
struct MapRays {
    const double* x;
    const double* y;
    const double* z;
    const std::uint8_t* valid;
};

// Where a map's entries go: entry k's source pixel at x[k], y[k] (NaN: none).
template <class Scalar>
struct MapOutput {
    Scalar* x;
    Scalar* y;
};

// The kernels of one instruction set.
template <class Scalar>
struct KernelSet {
    void (*project)(const ProjectJob<Scalar>& job, std::size_t begin, std::size_t end);
    void (*project_interleaved)(const ProjectJob<Scalar>& job, std::size_t begin, std::size_t end);
    void (*unproject)(const UnprojectJob<Scalar>& job, std::size_t begin, std::size_t end);
    // Entries [begin, end) of a map in Scalar, computed in double: their rays from K^-1 where
    // `rays` is nullptr (a PINHOLE target), else rays' first end - begin; then turned,
    // projected through the source lens and written, NaN where there is no source. Returns
    // how many have one.
    std::size_t (*map)(const MapJob& job, const MapRays* rays, const MapOutput<Scalar>& out, std::size_t begin,
                       std::size_t end);
};

// Each compiled set (kernels_sse2.cpp, kernels_avx2.cpp, kernels_avx512.cpp).
template <SimdTarget target, class Scalar>
const KernelSet<Scalar>& compiled_kernels();
template <>
const KernelSet<float>& compiled_kernels<SimdTarget::Sse2, float>();
template <>
const KernelSet<double>& compiled_kernels<SimdTarget::Sse2, double>();
template <>
const KernelSet<float>& compiled_kernels<SimdTarget::Avx2, float>();
template <>
const KernelSet<double>& compiled_kernels<SimdTarget::Avx2, double>();
template <>
const KernelSet<float>& compiled_kernels<SimdTarget::Avx512, float>();
template <>
const KernelSet<double>& compiled_kernels<SimdTarget::Avx512, double>();

// The set of the target in use (simd_target()).
template <class Scalar>
const KernelSet<Scalar>& kernels() {
#if defined(LIBCAM_SIMD_DISPATCH)
    switch (simd_target()) {
        case SimdTarget::Avx512: return compiled_kernels<SimdTarget::Avx512, Scalar>();
        case SimdTarget::Avx2: return compiled_kernels<SimdTarget::Avx2, Scalar>();
        case SimdTarget::Sse2: break;
    }
#else
    (void)simd_target();  // LIBCAM_SIMD is checked in every build
#endif
    return compiled_kernels<SimdTarget::Sse2, Scalar>();
}

}  // namespace libcam::kernels
