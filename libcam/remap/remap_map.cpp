#include "libcam/remap/remap_map.hpp"

#include <algorithm>
#include <atomic>

#include "libcam/camera/detail/kernels.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/error.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace libcam {

namespace detail {

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;
constexpr std::size_t kInHugePagesFrom = 2 * kHugePage;  // smaller maps would round up too far
}  // namespace

void* allocate_map_memory(std::size_t bytes) {
    if (bytes < kInHugePagesFrom) return ::operator new(bytes);
    const std::size_t whole_pages = (bytes + kHugePage - 1) / kHugePage * kHugePage;
    void* memory = ::operator new(whole_pages, std::align_val_t{kHugePage});
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // A request: where it is refused (no transparent huge pages), the pages are ordinary.
    madvise(memory, whole_pages, MADV_HUGEPAGE);
#endif
    return memory;
}

void free_map_memory(void* memory, std::size_t bytes) noexcept {
    if (bytes < kInHugePagesFrom) {
        ::operator delete(memory);
    } else {
        ::operator delete(memory, std::align_val_t{kHugePage});
    }
}

}  // namespace detail

namespace {

// Pixels per step of a worker: the batch calls' buffers stay in cache.
constexpr std::size_t kStep = 1024;

// Entries [begin, end) of a map from a target that is not a PINHOLE: each step's pixels
// unprojected by the target's batch engine, then turned, projected and written by the
// map kernel. Returns how many have a source.
template <class Scalar>
std::size_t map_from_unprojection(const Unprojector<double>& unprojector, UnprojectMethod method,
                                  const kernels::MapJob& job, const kernels::MapOutput<Scalar>& out, std::size_t begin,
                                  std::size_t end) {
    const auto map_kernel = kernels::kernels<Scalar>().map;
    Points3<double> step_rays;  // one worker's, reused step after step
    ValidFlags has_ray;
    std::size_t found = 0;
    for (std::size_t first = begin; first < end; first += kStep) {
        const std::size_t count = std::min(kStep, end - first);
        unprojector.unproject_image_part(method, first, count, step_rays, has_ray);
        const kernels::MapRays rays{step_rays.x.data(), step_rays.y.data(), step_rays.z.data(), has_ray.data()};
        found += map_kernel(job, &rays, out, first, first + count);
    }
    return found;
}

}  // namespace

Mat3 rotation_between(const Camera& target, const Camera& source) { return target.pose.R * source.pose.R.transpose(); }

template <class Scalar>
BasicRemapMap<Scalar> build_remap_map(const PreparedCamera& target, const PreparedCamera& source, const RemapOptions& options) {
    // Validated as a pose's rotation is.
    Pose{options.rotation, Vec3::Zero()}.validate("rotation");
    const Camera& target_camera = target.camera();
    const bool pinhole_target = target_camera.lens.type == LensType::Pinhole;
    BasicRemapMap<Scalar> map;
    map.size = target_camera.size;
    map.source_size = source.camera().size;
    const std::size_t width = static_cast<std::size_t>(map.size.width);
    const std::size_t n = width * static_cast<std::size_t>(map.size.height);
    map.x.resize(n);  // left uninitialised (UninitialisedAllocator): every entry is written once below
    map.y.resize(n);

    const kernels::MapJob job{source.camera(),
                              source.valid_radius(),
                              pinhole_target ? &target_camera.intrinsics : nullptr,
                              options.rotation.transpose(),
                              !options.rotation.isIdentity(0.0),
                              width};
    const kernels::MapOutput<Scalar> out{map.x.data(), map.y.data()};
    const Unprojector<double>* unprojector = pinhole_target ? nullptr : &target.unprojector();
    std::atomic<std::size_t> with_source{0};
    parallel_chunks(n, options.threads, kStep, [&](std::size_t begin, std::size_t end) {
        // A PINHOLE target's rays are K^-1 [x y 1], made by the kernel row by row.
        with_source += unprojector == nullptr
                           ? kernels::kernels<Scalar>().map(job, nullptr, out, begin, end)
                           : map_from_unprojection(*unprojector, options.method, job, out, begin, end);
    });
    map.with_source = with_source;
    return map;
}

template RemapMap build_remap_map<double>(const PreparedCamera&, const PreparedCamera&, const RemapOptions&);
template RemapMapFloat build_remap_map<float>(const PreparedCamera&, const PreparedCamera&, const RemapOptions&);

}  // namespace libcam
