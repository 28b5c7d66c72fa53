#include "libcam/remap/remap_map.hpp"

#include <algorithm>
#include <atomic>
#include <limits>

#include "libcam/camera/parallel.hpp"
#include "libcam/camera/projector.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/error.hpp"
#include "libcam/remap/detail/batches.hpp"

namespace libcam {

namespace {

// Pixels per step of a worker: the batch calls' buffers stay in cache.
constexpr std::size_t kStep = 1024;

// One worker's buffers, reused step after step.
struct Scratch {
    Points2<double> pixels;
    Points3<double> rays;
    ValidFlags has_ray;
    Points2<double> source_pixels;
    ValidFlags projected;
};

// What every worker reads: how a step's rays are found and projected.
struct MapPlan {
    const PreparedCamera& target;
    const Unprojector<double>* unprojector;  // none for a PINHOLE target: its rays by pinhole_rays
    const Projector<double>& projector;
    const RemapOptions& options;
    Mat3 to_source;
    bool turned;
    std::size_t width;
};

// The rays of target pixels [first, first + count) in the source's frame, and which have one.
void source_rays(const MapPlan& plan, std::size_t first, std::size_t count, Scratch& s) {
    if (plan.unprojector == nullptr) {
        detail::pinhole_rays(s.rays, first, count, plan.width, plan.target.camera().intrinsics, plan.to_source, plan.turned);
        s.has_ray.assign(count, 1);
        return;
    }
    detail::image_pixels(s.pixels, first, count, plan.width);
    plan.unprojector->unproject(s.pixels, plan.options.method, s.rays, s.has_ray);
    if (plan.turned) detail::turn(s.rays, plan.to_source);
}

// Every entry written, NaN or not; the test is made in double, before any rounding to
// Scalar, so a float map leaves out exactly the pixels the double map does.
template <class Scalar>
std::size_t write_step(const Scratch& s, std::size_t count, const ImageSize& source_size, Scalar* out_x, Scalar* out_y) {
    constexpr Scalar kNaN = std::numeric_limits<Scalar>::quiet_NaN();
    std::size_t found = 0;
    for (std::size_t j = 0; j < count; ++j) {
        const double x = s.source_pixels.x[j], y = s.source_pixels.y[j];
        const bool has = (s.has_ray[j] != 0) & (s.projected[j] != 0) & on_image(x, y, source_size);
        out_x[j] = has ? static_cast<Scalar>(x) : kNaN;
        out_y[j] = has ? static_cast<Scalar>(y) : kNaN;
        found += has ? 1 : 0;
    }
    return found;
}

}  // namespace

Mat3 rotation_between(const Camera& target, const Camera& source) { return target.pose.R * source.pose.R.transpose(); }

template <class Scalar>
BasicRemapMap<Scalar> build_remap_map(const PreparedCamera& target, const PreparedCamera& source, const RemapOptions& options) {
    // Validated as a pose's rotation is.
    Pose{options.rotation, Vec3::Zero()}.validate("rotation");
    const bool pinhole_target = target.camera().lens.type == LensType::Pinhole;
    const Projector<double> projector(source);
    BasicRemapMap<Scalar> map;
    map.size = target.camera().size;
    map.source_size = source.camera().size;
    const MapPlan plan{target,
                       pinhole_target ? nullptr : &target.unprojector(),
                       projector,
                       options,
                       options.rotation.transpose(),
                       !options.rotation.isIdentity(0.0),
                       static_cast<std::size_t>(map.size.width)};
    const std::size_t n = plan.width * static_cast<std::size_t>(map.size.height);
    map.x.resize(n);  // left uninitialised (UninitialisedAllocator): every entry is written once below
    map.y.resize(n);

    std::atomic<std::size_t> with_source{0};
    parallel_chunks(n, options.threads, kStep, [&](std::size_t begin, std::size_t end) {
        Scratch s;
        std::size_t found = 0;
        for (std::size_t first = begin; first < end; first += kStep) {
            const std::size_t m = std::min(kStep, end - first);
            source_rays(plan, first, m, s);
            projector.project(s.rays, s.source_pixels, s.projected);
            found += write_step(s, m, map.source_size, map.x.data() + first, map.y.data() + first);
        }
        with_source += found;
    });
    map.with_source = with_source;
    return map;
}

template RemapMap build_remap_map<double>(const PreparedCamera&, const PreparedCamera&, const RemapOptions&);
template RemapMapFloat build_remap_map<float>(const PreparedCamera&, const PreparedCamera&, const RemapOptions&);

}  // namespace libcam
