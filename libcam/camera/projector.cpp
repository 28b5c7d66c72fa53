#include "libcam/camera/projector.hpp"

#include <cstdint>
#include <string>

#include "libcam/camera/detail/kernels.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/error.hpp"

namespace libcam {

template <class Scalar>
Projector<Scalar>::Projector(const Camera& camera) : Projector(PreparedCamera(camera)) {}

template <class Scalar>
Projector<Scalar>::Projector(const PreparedCamera& camera)
    : camera_(camera.camera()), valid_radius_(camera.valid_radius()) {}

template <class Scalar>
void Projector<Scalar>::project(const Points3<Scalar>& camera_points, Points2<Scalar>& pixels, ValidFlags& valid,
                                int threads) const {
    const std::size_t n = camera_points.size();
    batch::require_same_sizes("camera_points", n, {camera_points.y.size(), camera_points.z.size()});
    pixels.resize(n);
    valid.resize(n);
    project(camera_points.x, camera_points.y, camera_points.z, pixels.x, pixels.y, valid, threads);
}

using batch::overlap;

template <class Scalar>
void Projector<Scalar>::project(std::span<const Scalar> x, std::span<const Scalar> y, std::span<const Scalar> z,
                                std::span<Scalar> pixel_x, std::span<Scalar> pixel_y, std::span<std::uint8_t> valid,
                                int threads) const {
    const std::size_t n = valid.size();
    batch::require_same_sizes("project: the points' and pixels' arrays and the flags", n,
                              {x.size(), y.size(), z.size(), pixel_x.size(), pixel_y.size()});
    if (n == 0) return;
    // The kernel reads and writes these as separate arrays (restrict): an output written
    // over an input or another output would give wrong pixels.
    bool overlaps = overlap(pixel_x, pixel_y);
    for (const std::span<Scalar> out : {pixel_x, pixel_y}) {
        overlaps = overlaps || overlap(out, x) || overlap(out, y) || overlap(out, z) || overlap(out, valid);
    }
    if (overlaps) {
        throw InvalidArgument("project: the pixels' arrays must not overlap the points', the flags or each other");
    }
    const kernels::ProjectJob<Scalar> job{camera_,        valid_radius_,  x.data(),     y.data(),
                                          z.data(),       pixel_x.data(), pixel_y.data(), valid.data()};
    const auto project = kernels::kernels<Scalar>().project;
    parallel_chunks(n, threads, batch::kBlock,
                    [&](std::size_t begin, std::size_t end) { project(job, begin, end); });
}

template <class Scalar>
void Projector<Scalar>::project_interleaved(std::span<const Scalar> camera_points, std::span<Scalar> pixels,
                                            std::span<std::uint8_t> valid, int threads) const {
    batch::require_interleaved_batch<Scalar>("project_interleaved", camera_points, 3, "point", pixels, 2, "pixel", valid);
    const std::size_t n = valid.size();
    if (n == 0) return;
    const Scalar* points = camera_points.data();
    const kernels::ProjectJob<Scalar> job{camera_, valid_radius_,      points,       points + 1, points + 2,
                                          pixels.data(), pixels.data() + 1, valid.data()};
    const auto project = kernels::kernels<Scalar>().project_interleaved;
    parallel_chunks(n, threads, batch::kBlock,
                    [&](std::size_t begin, std::size_t end) { project(job, begin, end); });
}

template class Projector<float>;
template class Projector<double>;

}  // namespace libcam
