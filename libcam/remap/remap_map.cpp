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

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

}  // namespace

Mat3 rotation_between(const Camera& target, const Camera& source) { return target.pose.R * source.pose.R.transpose(); }

RemapMap build_remap_map(const PreparedCamera& target, const PreparedCamera& source, const RemapOptions& options) {
    // Validated as a pose's rotation is.
    Pose{options.rotation, Vec3::Zero()}.validate("rotation");
    const Unprojector<double>& unprojector = target.unprojector();
    const Projector<double> projector(source);
    const Mat3 to_source = options.rotation.transpose();
    const bool turned = !options.rotation.isIdentity(0.0);

    RemapMap map;
    map.size = target.camera().size;
    map.source_size = source.camera().size;
    const std::size_t width = static_cast<std::size_t>(map.size.width);
    const std::size_t n = width * static_cast<std::size_t>(map.size.height);
    map.x.resize(n);  // zero-filled (std::vector), then every entry written once below
    map.y.resize(n);

    std::atomic<std::size_t> with_source{0};
    parallel_chunks(n, options.threads, kStep, [&](std::size_t begin, std::size_t end) {
        Scratch s;
        std::size_t found = 0;
        for (std::size_t first = begin; first < end; first += kStep) {
            const std::size_t m = std::min(kStep, end - first);
            detail::image_pixels(s.pixels, first, m, width);
            unprojector.unproject(s.pixels, options.method, s.rays, s.has_ray);
            if (turned) detail::turn(s.rays, to_source);
            projector.project(s.rays, s.source_pixels, s.projected);
            double* out_x = map.x.data() + first;
            double* out_y = map.y.data() + first;
            for (std::size_t j = 0; j < m; ++j) {  // every entry written, NaN or not
                const double x = s.source_pixels.x[j], y = s.source_pixels.y[j];
                const bool has = s.has_ray[j] != 0 && s.projected[j] != 0 && on_image(x, y, map.source_size);
                out_x[j] = has ? x : kNaN;
                out_y[j] = has ? y : kNaN;
                found += has ? 1 : 0;
            }
        }
        with_source += found;
    });
    map.with_source = with_source;
    return map;
}

}  // namespace libcam
