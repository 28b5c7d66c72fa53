#pragma once
// The map that turns an image of one camera (the source) into an image of another (the
// target): for each target pixel, the source pixel that sees the same ray.
//
//   const RemapMap map = build_remap_map(PreparedCamera(pinhole), PreparedCamera(fisheye));
//   // map.x[y * width + x], map.y[...]: where to sample the fisheye image; NaN: nowhere
//
// Each target pixel is unprojected through the target camera (the batch engine's exact
// or fast method), turned by the rotation between the cameras, and projected through the
// source camera. A target pixel has no source, and gets NaN, when it has no ray, when its
// ray is outside the source lens's valid domain (behind it, past its fold-over radius),
// or when the ray lands off the source image (outside [-0.5, W - 0.5] x [-0.5, H - 0.5],
// the pixels' own area). With the exact method each source coordinate is the one the
// rays give to about 1e-9 px; fast is within about 0.01 px (unprojector.hpp).
//
// Undistorting an image is the map from a pinhole target to the lens; distorting a
// render to look as the real lens took it is the map from the lens (target) to the
// pinhole the render was made with (source). Both go through this one function.

#include <cstddef>
#include <limits>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "libcam/camera/batch.hpp"
#include "libcam/camera/camera.hpp"

namespace libcam {

struct RemapOptions {
    // The target camera's axes relative to the source's: a direction d in the source
    // camera's frame is rotation * d in the target's (OpenCV's R of
    // cv::initUndistortRectifyMap: rectification, or a virtual camera looking elsewhere).
    Mat3 rotation = Mat3::Identity();
    UnprojectMethod method = UnprojectMethod::Exact;
    int threads = 1;
};

namespace detail {
// Memory for a map's coordinates (remap_map.cpp). Above a few MiB it is asked for in
// 2 MiB pages where the system gives them on request (Linux's transparent huge pages):
// the first write of a map of hundreds of MB then takes one page fault per 2 MiB instead
// of one per 4 KiB, which was most of the time of a large map.
void* allocate_map_memory(std::size_t bytes);
void free_map_memory(void* memory, std::size_t bytes) noexcept;
}  // namespace detail

// A std::allocator whose new elements are left uninitialised: a map's millions of
// coordinates are each written once, by the thread that computes them, instead of
// first being zeroed by one thread (a pass over the whole map the threads wait for).
// Its memory is allocate_map_memory's.
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
    using value_type = T;
    template <class U>
    struct rebind {
        using other = UninitialisedAllocator<U>;
    };
    UninitialisedAllocator() = default;
    template <class U>
    UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) {
        if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T*>(detail::allocate_map_memory(n * sizeof(T)));
    }
    void deallocate(T* p, std::size_t n) noexcept { detail::free_map_memory(p, n * sizeof(T)); }
    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;  // default-initialised: no value for a double
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

// One coordinate of every target pixel, row by row.
template <class Scalar>
using MapCoordinatesOf = std::vector<Scalar, UninitialisedAllocator<Scalar>>;
using MapCoordinates = MapCoordinatesOf<double>;

// Scalar: double, or float for the 8 bytes per pixel cv::remap reads (CV_32FC2's or two
// CV_32F maps' worth). A float map is the double map rounded once: each coordinate is
// computed in double and rounded to float, and the pixels without a source are the same.
template <class Scalar>
struct BasicRemapMap {
    ImageSize size;                    // the target image
    ImageSize source_size;             // the source image
    MapCoordinatesOf<Scalar> x, y;     // source pixel of target pixel (i % width, i / width); NaN: no source
    std::size_t with_source = 0;

    bool has_source(std::size_t i) const { return x[i] == x[i]; }
};

using RemapMap = BasicRemapMap<double>;
using RemapMapFloat = BasicRemapMap<float>;

// Throws InvalidArgument for a rotation that is not one (naming "rotation").
// build_remap_map<float>(...) gives the float map. A PINHOLE target (undistorting, the
// common case) takes its rays from K^-1 [x y 1] directly, row by row, without the
// unprojector: the same rays, with no per-pixel check to make.
template <class Scalar = double>
BasicRemapMap<Scalar> build_remap_map(const PreparedCamera& target, const PreparedCamera& source,
                                      const RemapOptions& options = {});

extern template RemapMap build_remap_map<double>(const PreparedCamera&, const PreparedCamera&, const RemapOptions&);
extern template RemapMapFloat build_remap_map<float>(const PreparedCamera&, const PreparedCamera&, const RemapOptions&);

// The rotation between two cameras' poses: X_target = R X_source for a direction, so
// R = R_target R_source^T (their rotations from the same world).
Mat3 rotation_between(const Camera& target, const Camera& source);

}  // namespace libcam
