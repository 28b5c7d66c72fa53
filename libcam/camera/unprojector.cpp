#include "libcam/camera/unprojector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "libcam/camera/batch_kernels.hpp"
#include "libcam/camera/fill_values.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/camera/streaming_store.hpp"
#include "libcam/camera/unprojector_domain.hpp"
#include "libcam/camera/unprojector_table.hpp"
#include "libcam/error.hpp"
#include "libcam/lens/undistort.hpp"

namespace libcam {

namespace {

using batch::kBlock;
using namespace detail;

constexpr int kFastNewtonSteps = 1;
// From the bilinear start two steps reach rounding level on the lenses measured (the real
// wide lens: 0.2 px, then 5e-5 px, then 4e-12 px); a pixel they do not bring below
// reducible_residual() takes up to kExtraNewtonSteps more, each kept only where it lowers
// the residual, and the residual check sends any pixel still above the solver's
// tolerance to the full solver.
constexpr int kExactNewtonSteps = 2;
constexpr int kExtraNewtonSteps = 3;

// ---------------------------------------------------------------------------------
// Per block of pixels: each step is one loop over the block's arrays. The steps that
// vectorise read the camera's constants from local copies (see batch_kernels.hpp).

template <class Scalar>
struct Block {
    std::size_t count = 0;
    const Scalar* pixel_x;  // the block's pixels: the caller's arrays, or made_x, made_y
    const Scalar* pixel_y;
    Scalar made_x[kBlock], made_y[kBlock];  // pixels made here (the whole image, one pixel)
    Scalar m_x[kBlock], m_y[kBlock];  // K^-1 [x, y, 1]
    Scalar u_x[kBlock], u_y[kBlock];  // undistorted point
    Scalar ok[kBlock];  // 1: u (then the ray) is the answer; -1: settled, no ray; 0: for the full solver
    Scalar reducible[kBlock];  // 1: u passes, but another Newton step would gain digits (certify)
    detail::RayOutput<Scalar> rays;           // where the block's rays and flags go
    int cell[kBlock];                             // table node at the top-left of the pixel's cell
    Scalar fraction_x[kBlock], fraction_y[kBlock];  // position within that cell
};

template <class Scalar>
struct TableView;

template <class Scalar>
struct Context {
    const Intrinsics& intrinsics;
    const TableView<Scalar>& table;
    Scalar certified_radius_squared;
    Scalar no_ray_radius_squared;
    const detail::DomainRim& rim;
    Scalar valid_radius_squared;
};

template <class Scalar>
using Vec2L = Eigen::Matrix<Lane<Scalar>, 2, 1>;
template <class Scalar>
using Vec3L = Eigen::Matrix<Lane<Scalar>, 3, 1>;

template <class Scalar>
void normalize(const Intrinsics& camera_intrinsics, Block<Scalar>& b) {
    const Intrinsics intrinsics = camera_intrinsics;
    for (std::size_t i = 0; i < b.count; ++i) {
        const Vec2L<Scalar> m = intrinsics.normalized_from_pixel(Vec2L<Scalar>(b.pixel_x[i], b.pixel_y[i]));
        b.m_x[i] = lane_value(m.x());
        b.m_y[i] = lane_value(m.y());
    }
}

enum class Interpolation { Bilinear, Bicubic };

// The table as the loops read it (copied before each loop, see above).
template <class Scalar>
struct TableView {
    const Scalar* u_x;
    const Scalar* u_y;
    const Scalar* fast_ok;  // per cell
    const Scalar* lut_ok;
    int stride;  // nodes per row
    Scalar origin_x, origin_y, inv_step;
    Scalar end_x, end_y;  // a pixel's grid coordinates must lie in [1, end) for its bicubic stencil to fit

    explicit TableView(const UnprojectionTable<Scalar>& table)
        : u_x(table.u_x.data()),
          u_y(table.u_y.data()),
          fast_ok(table.fast_ok.data()),
          lut_ok(table.lut_ok.data()),
          stride(table.nodes_x),
          origin_x(Scalar(table.origin_x)),
          origin_y(Scalar(table.origin_y)),
          inv_step(table.step > 0 ? Scalar(1 / table.step) : Scalar(0)),
          end_x(Scalar(table.nodes_x - 2)),
          end_y(Scalar(table.nodes_y - 2)) {}
};

// The table cell of each pixel: the index of its top-left node and the fractions within
// it; ok = 0 for a pixel whose stencil would leave the table (it reads a harmless cell
// inside instead, so that every read stays in bounds).
template <class Scalar>
void locate_in_table(const TableView<Scalar>& table_view, Block<Scalar>& b) {
    const TableView<Scalar> table = table_view;
    for (std::size_t i = 0; i < b.count; ++i) {
        const Scalar gx = (b.pixel_x[i] - table.origin_x) * table.inv_step;
        const Scalar gy = (b.pixel_y[i] - table.origin_y) * table.inv_step;
        const bool inside = gx >= Scalar(1) && gx < table.end_x && gy >= Scalar(1) && gy < table.end_y;
        const Scalar x = inside ? gx : Scalar(1), y = inside ? gy : Scalar(1);
        const int column = static_cast<int>(x), row = static_cast<int>(y);
        b.cell[i] = row * table.stride + column;
        b.fraction_x[i] = x - Scalar(column);
        b.fraction_y[i] = y - Scalar(row);
        b.ok[i] = batch::flag<Scalar>(inside);
    }
}

// u interpolated from the table at each located pixel; ok stays 1 only where every
// node used has a ray (a node without one is NaN and makes the sum NaN).
template <Interpolation kind, class Scalar>
void interpolate(const TableView<Scalar>& table_view, Block<Scalar>& b) {
    const TableView<Scalar> table = table_view;
    for (std::size_t i = 0; i < b.count; ++i) {
        const int k = b.cell[i];
        Scalar x, y;
        if constexpr (kind == Interpolation::Bilinear) {
            x = bilinear(table.u_x, k, table.stride, b.fraction_x[i], b.fraction_y[i]);
            y = bilinear(table.u_y, k, table.stride, b.fraction_x[i], b.fraction_y[i]);
        } else {
            Scalar wx[4], wy[4];
            catmull_rom_weights(b.fraction_x[i], wx);
            catmull_rom_weights(b.fraction_y[i], wy);
            x = bicubic(table.u_x, k, table.stride, wx, wy);
            y = bicubic(table.u_y, k, table.stride, wx, wy);
        }
        b.u_x[i] = x;
        b.u_y[i] = y;
        const bool numbers = (x == x) & (y == y);  // not NaN; & not &&: no branch in the loop
        b.ok[i] = numbers ? b.ok[i] : Scalar(0);
    }
}

template <Interpolation kind, class Scalar>
void start_from_table(const TableView<Scalar>& table, Block<Scalar>& b) {
    locate_in_table(table, b);
    interpolate<kind>(table, b);
}

// Keeps ok only in the cells where the method's estimate was checked to be within the
// budget (check_cells).
template <class Scalar>
void require_accurate_cell(const Scalar* cell_ok, Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) b.ok[i] = cell_ok[b.cell[i]] != Scalar(0) ? b.ok[i] : Scalar(0);
}

// Without the full solver, only a pixel inside the certified disc may be called valid.
template <class Scalar>
void require_certified_disc(Scalar radius_squared, Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) {
        const bool inside = b.m_x[i] * b.m_x[i] + b.m_y[i] * b.m_y[i] < radius_squared;
        b.ok[i] = inside ? b.ok[i] : Scalar(0);
    }
}

// The answer must lie inside the valid domain itself.
template <class Scalar>
void require_valid_radius(Scalar radius_squared, Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) {
        const bool inside = b.u_x[i] * b.u_x[i] + b.u_y[i] * b.u_y[i] < radius_squared;
        b.ok[i] = inside ? b.ok[i] : Scalar(0);
    }
}

// Newton steps on every pixel of the block. A pixel's answer never depends on the other
// pixels of its block, so it is the same in any batch.
template <class Model, class Scalar>
void newton_steps(const typename Model::Parameters& lens_parameters, int steps, Block<Scalar>& b) {
    const typename Model::Parameters lens = lens_parameters;
    for (int step = 0; step < steps; ++step) {
        for (std::size_t i = 0; i < b.count; ++i) {
            const Vec2L<Scalar> u(b.u_x[i], b.u_y[i]);
            Vec2L<Scalar> m_u;
            Eigen::Matrix<Lane<Scalar>, 2, 2> d_m_d_u;
            const bool in_domain = Model::distort(lens, u, m_u, &d_m_d_u);
            const Vec2L<Scalar> next = u - newton_step(d_m_d_u, Vec2L<Scalar>(m_u - Vec2L<Scalar>(b.m_x[i], b.m_y[i])));
            b.u_x[i] = lane_value(next.x());
            b.u_y[i] = lane_value(next.y());
            b.ok[i] = in_domain ? b.ok[i] : Scalar(0);
        }
    }
}

// Keeps ok only where u is inside the domain and reprojects to m within the tolerance
// the full solver accepts. Returns how many of the pixels kept are still above
// reducible_residual(), where another Newton step would gain digits.
template <class Model, class Scalar>
int certify(const typename Model::Parameters& lens_parameters, Block<Scalar>& b) {
    const typename Model::Parameters lens = lens_parameters;
    int reducible = 0;
    for (std::size_t i = 0; i < b.count; ++i) {
        const Vec2L<Scalar> u(b.u_x[i], b.u_y[i]), m(b.m_x[i], b.m_y[i]);
        Vec2L<Scalar> m_u;
        const bool in_domain = Model::distort(lens, u, m_u);
        const Lane<Scalar> tolerance = unprojection_tolerance(m.norm()), floor = reducible_residual(m.norm());
        const Lane<Scalar> residual_squared = (m_u - m).squaredNorm();  // squares: one square root, not two
        const bool kept = in_domain & (residual_squared <= tolerance * tolerance) & (b.ok[i] > Scalar(0));
        b.ok[i] = kept ? b.ok[i] : Scalar(0);
        b.reducible[i] = batch::flag<Scalar>(kept & (residual_squared > floor * floor));
        reducible += b.reducible[i] > Scalar(0) ? 1 : 0;
    }
    return reducible;
}

// For the pixels certify() marked reducible: one more Newton step, kept only where it
// lowers the residual (as the full solver keeps a step). Returns how many are still
// reducible. At rounding level a step can as well raise the residual, hence the guard.
template <class Model, class Scalar>
int refine_reducible(const typename Model::Parameters& lens_parameters, Block<Scalar>& b) {
    const typename Model::Parameters lens = lens_parameters;
    int reducible = 0;
    for (std::size_t i = 0; i < b.count; ++i) {
        const Vec2L<Scalar> u(b.u_x[i], b.u_y[i]), m(b.m_x[i], b.m_y[i]);
        Vec2L<Scalar> m_u, m_next;
        Eigen::Matrix<Lane<Scalar>, 2, 2> d_m_d_u;
        Model::distort(lens, u, m_u, &d_m_d_u);
        const Vec2L<Scalar> next = u - newton_step(d_m_d_u, Vec2L<Scalar>(m_u - m));
        const bool in_domain = Model::distort(lens, next, m_next);
        const Lane<Scalar> before = (m_u - m).squaredNorm(), after = (m_next - m).squaredNorm();
        const bool take = (b.reducible[i] > Scalar(0)) & in_domain & (after < before);
        b.u_x[i] = take ? lane_value(next.x()) : b.u_x[i];
        b.u_y[i] = take ? lane_value(next.y()) : b.u_y[i];
        const Lane<Scalar> floor = reducible_residual(m.norm());
        b.reducible[i] = batch::flag<Scalar>(take & (after > floor * floor));
        reducible += b.reducible[i] > Scalar(0) ? 1 : 0;
    }
    return reducible;
}

// Settles as having no ray every pixel beyond the image of the whole domain.
template <class Scalar>
void reject_beyond_domain(Scalar no_ray_radius_squared, Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) {
        const bool beyond = b.m_x[i] * b.m_x[i] + b.m_y[i] * b.m_y[i] > no_ray_radius_squared;
        b.ok[i] = beyond ? Scalar(-1) : b.ok[i];
    }
}

// The full solver, in double whatever the scalar type, for every pixel not settled yet:
// its answer, or no ray. In double, so that the float methods flag exactly the pixels
// the double solver flags (a float residual test would accept pixels just past a fold).
// A pixel past the rim has no ray; it is not sent to the solver, whose failures are slow.
template <class ModelDouble, class Scalar>
void solve_remaining(const Context<Scalar>& context, const typename ModelDouble::Parameters& lens, Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) {
        if (b.ok[i] != Scalar(0)) continue;
        const Vec2 m = context.intrinsics.normalized_from_pixel(Vec2(double(b.pixel_x[i]), double(b.pixel_y[i])));
        Vec2 u;
        const bool solved = !beyond_rim(context.rim, m) && solve_undistorted<ModelDouble>(lens, m, u);
        b.u_x[i] = solved ? Scalar(u.x()) : Scalar(0);
        b.u_y[i] = solved ? Scalar(u.y()) : Scalar(0);
        b.ok[i] = batch::flag<Scalar>(solved);
    }
}

template <class Scalar>
void set_ray(Block<Scalar>& b, std::size_t i, bool ok, const Vec3L<Scalar>& ray) {
    b.rays.x[i] = ok ? lane_value(ray.x()) : Scalar(0);
    b.rays.y[i] = ok ? lane_value(ray.y()) : Scalar(0);
    b.rays.z[i] = ok ? lane_value(ray.z()) : Scalar(0);
}

template <class Model, class Scalar>
void rays_from_undistorted(const typename Model::Parameters& lens, Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) {
        set_ray(b, i, b.ok[i] > Scalar(0), Model::ray_from_undistorted(lens, Vec2L<Scalar>(b.u_x[i], b.u_y[i])));
    }
}

template <class Model, class Scalar>
void unproject_closed_form(const typename Model::Parameters& lens_parameters, Block<Scalar>& b) {
    const typename Model::Parameters lens = lens_parameters;
    for (std::size_t i = 0; i < b.count; ++i) {
        Vec3L<Scalar> ray = Vec3L<Scalar>::Zero();
        const bool ok = Model::unproject(lens, Vec2L<Scalar>(b.m_x[i], b.m_y[i]), ray);
        set_ray(b, i, ok, ray);
        b.ok[i] = batch::flag<Scalar>(ok);
    }
}

// u by `method`, with ok = 1 where that settles it (see approximate).
template <class Model, class Scalar>
void estimate(const Context<Scalar>& context, const typename Model::Parameters& lens, UnprojectMethod method,
              Block<Scalar>& b) {
    switch (method) {
        case UnprojectMethod::Lut:
            start_from_table<Interpolation::Bicubic>(context.table, b);
            require_certified_disc(context.certified_radius_squared, b);
            require_accurate_cell(context.table.lut_ok, b);
            require_valid_radius(context.valid_radius_squared, b);
            return;
        case UnprojectMethod::Fast:
            start_from_table<Interpolation::Bilinear>(context.table, b);
            require_certified_disc(context.certified_radius_squared, b);
            require_accurate_cell(context.table.fast_ok, b);
            newton_steps<Model>(lens, kFastNewtonSteps, b);
            require_valid_radius(context.valid_radius_squared, b);
            return;
        case UnprojectMethod::Exact:
            start_from_table<Interpolation::Bilinear>(context.table, b);
            require_certified_disc(context.certified_radius_squared, b);
            newton_steps<Model>(lens, kExactNewtonSteps, b);
            if (certify<Model>(lens, b) > 0) {
                // A pixel not yet at rounding level (a coarse table on a huge image, a
                // strong lens): more steps for it, each kept only if it helps, as the full
                // solver does. Rejected pixels stay rejected.
                for (int step = 0; step < kExtraNewtonSteps && refine_reducible<Model>(lens, b) > 0; ++step) {
                }
                certify<Model>(lens, b);
            }
            return;
    }
}

// u for every pixel by `method`, with ok = 1 where that settles it: only inside the
// certified disc, whose pixels all have a ray, so that the validity never depends on
// the approximation. Pixels beyond the domain's image are settled as having none; the
// full solver decides the others.
template <class Model, class Scalar>
void approximate(const Context<Scalar>& context, const typename Model::Parameters& lens, UnprojectMethod method,
                 Block<Scalar>& b) {
    estimate<Model>(context, lens, method, b);
    reject_beyond_domain(context.no_ray_radius_squared, b);
}

// The model in Lane<Scalar> for the vectorised steps, and in double for the full solver.
template <class Model>
using LensPair = batch::BatchLens<Model, double>;

template <class Model, class Scalar>
void unproject_block(const Context<Scalar>& context, const LensPair<Model>& lens, UnprojectMethod method,
                     Block<Scalar>& b) {
    normalize(context.intrinsics, b);
    if constexpr (SolvedLensModel<Model>) {
        approximate<Model>(context, lens.lanes, method, b);
        solve_remaining<typename LensPair<Model>::Plain>(context, lens.plain, b);
        rays_from_undistorted<Model>(lens.lanes, b);
    } else {
        unproject_closed_form<Model>(lens.lanes, b);
    }
}

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

// `out.at(first, scratch)` says where a block's rays and flags go (the caller's arrays,
// or the scratch), and `out.done(first, count, scratch)` finishes the block.
template <class Scalar>
template <class FillPixels, class Output>
void Unprojector<Scalar>::run(std::size_t n, UnprojectMethod method, int threads, FillPixels&& fill,
                              Output&& out) const {
    const TableView<Scalar> table(table_);
    const Context<Scalar> context{camera_.intrinsics, table, Scalar(certified_radius_ * certified_radius_),
                                  Scalar(no_ray_radius_ * no_ray_radius_), rim_, Scalar(valid_radius_ * valid_radius_)};
    visit_lens_model<Lane<Scalar>>(camera_.lens.type, [&]<class Model>() {
        const LensPair<Model> lens(camera_.lens, valid_radius_);
        parallel_chunks(n, threads, kBlock, [&](std::size_t begin, std::size_t end) {
            Block<Scalar> block;
            RayScratch<Scalar, kBlock> scratch;
            for (std::size_t first = begin; first < end; first += kBlock) {
                block.count = std::min(kBlock, end - first);
                block.rays = out.at(first, scratch);
                fill(first, block);
                unproject_block<Model>(context, lens, method, block);
                batch::store_flags<Scalar>({block.ok, block.count}, block.rays.valid);
                out.done(first, block.count, scratch);
            }
        });
    });
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
    // Pixel index k is (k % width, k / width); each block is filled row segment by row segment.
    const auto image_pixels = [width](std::size_t first, Block<Scalar>& b) {
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
    };
    run(n, method, threads, image_pixels, output_into(directions, valid));
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

template <class Scalar>
void Unprojector<Scalar>::unproject(std::span<const Vec2> pixels, UnprojectMethod method, std::span<Unprojection> out,
                                    int threads) const {
    batch::require_same_sizes("pixels", pixels.size(), {out.size()});
    const auto copy_pixels = [&pixels](std::size_t first, Block<Scalar>& b) {
        for (std::size_t i = 0; i < b.count; ++i) {
            b.made_x[i] = Scalar(pixels[first + i].x());
            b.made_y[i] = Scalar(pixels[first + i].y());
        }
        b.pixel_x = b.made_x;
        b.pixel_y = b.made_y;
    };
    run(pixels.size(), method, threads, copy_pixels, ListOutput<Scalar>{out});
}

template class Unprojector<float>;
template class Unprojector<double>;

}  // namespace libcam
