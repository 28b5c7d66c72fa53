#include "libcam/camera/unprojector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "libcam/camera/detail/batch_kernels.hpp"
#include "libcam/camera/detail/fill_values.hpp"
#include "libcam/camera/detail/kernels.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/camera/detail/streaming_store.hpp"
#include "libcam/camera/detail/unprojector_domain.hpp"
#include "libcam/camera/detail/unprojector_table.hpp"
#include "libcam/error.hpp"
#include "libcam/lens/undistort.hpp"

namespace libcam {

namespace {

using batch::kBlock;
using namespace detail;
using kernels::Block;

template <class Scalar>
using Vec2L = Eigen::Matrix<Lane<Scalar>, 2, 1>;

}  // namespace

template <class Scalar>
Unprojector<Scalar>::Unprojector(const Camera& camera, UnprojectorOptions options)
    : Unprojector(PreparedCamera(camera), options) {}

template <class Scalar>
Unprojector<Scalar>::Unprojector(const PreparedCamera& camera, UnprojectorOptions options)
    : camera_(camera.camera()), valid_radius_(camera.valid_radius()) {
    prepare(options);
}

template <class Scalar>
void Unprojector<Scalar>::prepare(const UnprojectorOptions& options) {
    if (options.table_nodes < 4 || options.table_nodes > 100'000) {
        throw InvalidArgument("table_nodes: must be in [4, 100000], got " + std::to_string(options.table_nodes));
    }
    if (options.threads < 0) throw InvalidArgument("threads: must be >= 0, got " + std::to_string(options.threads));
    if (!(options.approximation_budget_px > 0)) {
        throw InvalidArgument("approximation_budget_px: must be > 0, got " + format_number(options.approximation_budget_px));
    }
    visit_lens_model<double>(camera_.lens.type, [&]<class Model>() {
        if constexpr (SolvedLensModel<Model>) {
            const auto lens = batch::model_parameters<Model>(camera_.lens, valid_radius_);
            const DomainBounds bounds = domain_bounds<Model>(camera_, lens);
            certified_radius_ = bounds.certified;
            no_ray_radius_ = bounds.no_ray;
            rim_ = bounds.rim;
            table_ = build_table<Model, Scalar>(camera_, lens, options);
        }
    });
}

namespace {

// A run's pixel source and ray sink as the kernels take them (kernels.hpp).
template <class Scalar, class FillPixels, class Output>
class RunIo final : public kernels::BlockIo<Scalar> {
public:
    using Scratch = typename kernels::BlockIo<Scalar>::Scratch;
    RunIo(const FillPixels& fill, const Output& out) : fill_(fill), out_(out) {}
    void fill(std::size_t first, Block<Scalar>& b) const override { fill_(first, b); }
    RayOutput<Scalar> at(std::size_t first, Scratch& scratch) const override { return out_.at(first, scratch); }
    void done(std::size_t first, std::size_t count, const Scratch& scratch) const override {
        out_.done(first, count, scratch);
    }

private:
    const FillPixels& fill_;
    const Output& out_;
};

}  // namespace

// `fill(first, block)` points the block at its pixels; `out.at(first, scratch)` says
// where a block's rays and flags go (the caller's arrays, or the scratch), and
// `out.done(first, count, scratch)` finishes the block.
template <class Scalar>
template <class FillPixels, class Output>
void Unprojector<Scalar>::run(std::size_t n, UnprojectMethod method, int threads, FillPixels&& fill,
                              Output&& out) const {
    const RunIo<Scalar, std::decay_t<FillPixels>, std::decay_t<Output>> io(fill, out);
    const kernels::UnprojectJob<Scalar> job{camera_, valid_radius_, certified_radius_, no_ray_radius_,
                                            rim_,    table_,        method,            &io};
    const auto unproject = kernels::kernels<Scalar>().unproject;
    parallel_chunks(n, threads, kBlock, [&](std::size_t begin, std::size_t end) { unproject(job, begin, end); });
}

namespace {

// Rays written straight into structure-of-arrays outputs.
template <class Scalar>
struct ArraysOutput {
    detail::RayOutput<Scalar> arrays;
    detail::RayOutput<Scalar> at(std::size_t first, RayScratch<Scalar, kBlock>&) const { return arrays.at(first); }
    void done(std::size_t, std::size_t, const RayScratch<Scalar, kBlock>&) const {}
};

template <class Scalar>
ArraysOutput<Scalar> output_into(Points3<Scalar>& directions, ValidFlags& valid) {
    return {{directions.x.data(), directions.y.data(), directions.z.data(), valid.data()}};
}

// Rays written to a block's scratch, then copied into a list of Unprojection.
template <class Scalar>
struct ListOutput {
    std::span<Unprojection> list;
    detail::RayOutput<Scalar> at(std::size_t, RayScratch<Scalar, kBlock>& scratch) const {
        return {scratch.x, scratch.y, scratch.z, scratch.valid};
    }
    void done(std::size_t first, std::size_t count, const RayScratch<Scalar, kBlock>& scratch) const {
        for (std::size_t i = 0; i < count; ++i) {
            Unprojection& out = list[first + i];
            out.direction = Vec3(double(scratch.x[i]), double(scratch.y[i]), double(scratch.z[i]));
            out.valid = scratch.valid[i] != 0;
        }
    }
};

}  // namespace

template <class Scalar>
void Unprojector<Scalar>::unproject(const Points2<Scalar>& pixels, UnprojectMethod method, Points3<Scalar>& directions,
                                    ValidFlags& valid, int threads) const {
    const std::size_t n = pixels.size();
    batch::require_same_sizes("pixels", n, {pixels.y.size()});
    directions.resize(n);
    valid.resize(n);
    const auto copy_pixels = [&pixels](std::size_t first, Block<Scalar>& b) {
        b.pixel_x = pixels.x.data() + first;
        b.pixel_y = pixels.y.data() + first;
    };
    run(n, method, threads, copy_pixels, output_into(directions, valid));
}

namespace {

// Every pixel's ray through a pinhole without skew, row by row. The ray's x depends on
// the column alone and its y on the row alone, so a row is a copy and three fills, at
// the speed of writing the bytes. The numbers are those of the general path, which
// evaluates K^-1 [x, y, 1] per pixel: there the skew term adds an exact 0. A frame much
// larger than the cache is written with stores that bypass it (streaming_store.hpp).
template <class Scalar>
void pinhole_image(const Intrinsics& intrinsics, const ImageSize& size, const detail::RayOutput<Scalar>& out,
                   int threads) {
    // Above a few MiB a frame does not stay in a core's share of the cache: its cache
    // lines would be read from memory only to be overwritten.
    constexpr std::size_t kStreamAbove = std::size_t{4} << 20;  // bytes of rays and flags
    const std::size_t width = static_cast<std::size_t>(size.width), height = static_cast<std::size_t>(size.height);
    const bool stream = width * height * (3 * sizeof(Scalar) + 1) > kStreamAbove;
    std::vector<Scalar> column_x(width);
    for (std::size_t x = 0; x < width; ++x) {
        column_x[x] = lane_value(intrinsics.normalized_from_pixel(Vec2L<Scalar>(Scalar(static_cast<int>(x)), Scalar(0))).x());
    }
    // Each array of a chunk of rows in one pass: one long stream of stores at a time.
    parallel_chunks(height, threads, 1, [&](std::size_t begin, std::size_t end) {
        const detail::RayOutput<Scalar> rays = out.at(begin * width);
        const std::size_t count = (end - begin) * width;
        if (stream) {
            detail::stream_fill(rays.valid, count, std::uint8_t{1});
            detail::stream_fill(rays.z, count, Scalar(1));
        } else {
            std::fill_n(rays.valid, count, std::uint8_t{1});
            detail::fill_values(rays.z, count, Scalar(1));
        }
        for (std::size_t row = begin; row < end; ++row) {
            const Vec2L<Scalar> start(Scalar(0), Scalar(static_cast<int>(row)));
            const Scalar row_y = lane_value(intrinsics.normalized_from_pixel(start).y());
            Scalar* y = out.y + row * width;
            stream ? detail::stream_fill(y, width, row_y) : detail::fill_values(y, width, row_y);
        }
        for (std::size_t row = begin; row < end; ++row) {
            Scalar* x = out.x + row * width;
            stream ? detail::stream_copy(x, column_x.data(), width) : static_cast<void>(std::copy_n(column_x.data(), width, x));
        }
        if (stream) detail::stream_fence();
    });
}

}  // namespace

namespace {

// The block's pixels: those of pixel index first on, index k being pixel (k % width, k /
// width) of the image, filled row segment by row segment.
template <class Scalar>
void image_block_pixels(std::size_t width, std::size_t first, Block<Scalar>& b) {
    int x = static_cast<int>(first % width), y = static_cast<int>(first / width);
    for (std::size_t i = 0; i < b.count; x = 0, ++y) {
        const std::size_t run = std::min(b.count - i, width - static_cast<std::size_t>(x));
        for (std::size_t j = 0; j < run; ++j) {
            b.made_x[i + j] = Scalar(x + static_cast<int>(j));
            b.made_y[i + j] = Scalar(y);
        }
        i += run;
    }
    b.pixel_x = b.made_x;
    b.pixel_y = b.made_y;
}

}  // namespace

template <class Scalar>
void Unprojector<Scalar>::unproject_image(UnprojectMethod method, Points3<Scalar>& directions, ValidFlags& valid,
                                          int threads) const {
    const std::size_t width = static_cast<std::size_t>(camera_.size.width);
    const std::size_t n = width * static_cast<std::size_t>(camera_.size.height);
    directions.resize(n);
    valid.resize(n);
    if (camera_.lens.type == LensType::Pinhole && camera_.intrinsics.skew == 0) {
        pinhole_image(camera_.intrinsics, camera_.size, output_into(directions, valid).arrays, threads);
        return;
    }
    const auto image_pixels = [width](std::size_t first, Block<Scalar>& b) { image_block_pixels(width, first, b); };
    run(n, method, threads, image_pixels, output_into(directions, valid));
}

template <class Scalar>
void Unprojector<Scalar>::unproject_image_part(UnprojectMethod method, std::size_t first, std::size_t count,
                                               Points3<Scalar>& directions, ValidFlags& valid) const {
    const std::size_t width = static_cast<std::size_t>(camera_.size.width);
    const std::size_t n = width * static_cast<std::size_t>(camera_.size.height);
    if (first > n || count > n - first) {
        throw InvalidArgument("unproject_image_part: pixels " + std::to_string(first) + " to " +
                              std::to_string(first + count) + " of an image of " + std::to_string(n));
    }
    directions.resize(count);
    valid.resize(count);
    const auto image_pixels = [width, first](std::size_t offset, Block<Scalar>& b) {
        image_block_pixels(width, first + offset, b);
    };
    run(count, method, 1, image_pixels, output_into(directions, valid));
}

template <class Scalar>
bool Unprojector<Scalar>::unproject(const Vec2T& pixel, UnprojectMethod method, Vec3T& direction) const {
    const auto one_pixel = [&pixel](std::size_t, Block<Scalar>& b) {
        b.made_x[0] = pixel.x();
        b.made_y[0] = pixel.y();
        b.pixel_x = b.made_x;
        b.pixel_y = b.made_y;
    };
    Vec3T ray;
    std::uint8_t valid = 0;
    const ArraysOutput<Scalar> out{{&ray.x(), &ray.y(), &ray.z(), &valid}};
    run(1, method, 1, one_pixel, out);
    if (valid) direction = ray;
    return valid != 0;
}

namespace {

// The block's pixels from interleaved pairs (x, y of pixel 0, then of pixel 1, ...),
// converted to Scalar: a list of Vec2 or numpy's (N, 2) array.
template <class Scalar, class Stored>
void fill_from_pairs(const Stored* pairs, std::size_t first, Block<Scalar>& b) {
    const Stored* pixel = pairs + 2 * first;
    for (std::size_t i = 0; i < b.count; ++i) {
        b.made_x[i] = Scalar(pixel[2 * i]);
        b.made_y[i] = Scalar(pixel[2 * i + 1]);
    }
    b.pixel_x = b.made_x;
    b.pixel_y = b.made_y;
}

}  // namespace

template <class Scalar>
void Unprojector<Scalar>::unproject(std::span<const Vec2> pixels, UnprojectMethod method, std::span<Unprojection> out,
                                    int threads) const {
    batch::require_same_sizes("pixels", pixels.size(), {out.size()});
    // A Vec2 is two doubles, and a span of them one array of pairs.
    static_assert(sizeof(Vec2) == 2 * sizeof(double));
    const double* pairs = pixels.empty() ? nullptr : pixels.data()->data();
    if constexpr (std::is_same_v<Scalar, double>) {
        // The kernel reads the pairs and writes each entry's direction (four doubles apart:
        // an entry is its direction and the eight bytes of its flag) and flag itself.
        static_assert(sizeof(Unprojection) == 4 * sizeof(double));
        if (pixels.empty()) return;
        const kernels::EntryIo<double> entries{pairs, out.data()->direction.data(), &out.data()->valid,
                                               sizeof(Unprojection)};
        const kernels::UnprojectJob<double> job{camera_, valid_radius_, certified_radius_, no_ray_radius_, rim_, table_,
                                                method,  nullptr,       nullptr,           &entries};
        const auto unproject = kernels::kernels<double>().unproject;
        parallel_chunks(pixels.size(), threads, kBlock, [&](std::size_t begin, std::size_t end) { unproject(job, begin, end); });
    } else {
        const auto copy_pixels = [pairs](std::size_t first, Block<Scalar>& b) { fill_from_pairs(pairs, first, b); };
        run(pixels.size(), method, threads, copy_pixels, ListOutput<Scalar>{out});
    }
}

template <class Scalar>
void Unprojector<Scalar>::unproject_interleaved(std::span<const Scalar> pixels, UnprojectMethod method,
                                                std::span<Scalar> directions, std::span<std::uint8_t> valid,
                                                int threads) const {
    batch::require_interleaved_batch<Scalar>("unproject_interleaved", pixels, 2, "pixel", directions, 3, "direction",
                                             valid);
    const std::size_t n = valid.size();
    if (n == 0) return;
    const kernels::InterleavedIo<Scalar> arrays{pixels.data(), directions.data(), valid.data()};
    const kernels::UnprojectJob<Scalar> job{camera_, valid_radius_, certified_radius_, no_ray_radius_, rim_,
                                            table_,  method,        nullptr,           &arrays};
    const auto unproject = kernels::kernels<Scalar>().unproject;
    parallel_chunks(n, threads, kBlock, [&](std::size_t begin, std::size_t end) { unproject(job, begin, end); });
}

template class Unprojector<float>;
template class Unprojector<double>;

}  // namespace libcam
