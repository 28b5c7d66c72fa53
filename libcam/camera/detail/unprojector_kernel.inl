// The unprojection kernel, compiled once per instruction set: included only by
// camera/detail/kernels_for_target.hpp, inside its target region, which has included every
// header this file uses (no #include here: see projector_kernel.inl).

constexpr int kFastNewtonSteps = 1;
// From the bilinear start two steps reach rounding level on the lenses measured (the real
// wide lens: 0.2 px, then 5e-5 px, then 4e-12 px); a pixel they do not bring below
// reducible_residual() takes up to kExtraNewtonSteps more, each kept only where it lowers
// the residual, and the residual check sends any pixel still above the solver's
// tolerance to the full solver.
constexpr int kExactNewtonSteps = 2;
constexpr int kExtraNewtonSteps = 3;

// ---------------------------------------------------------------------------------
// Per block of pixels (kernels.hpp's Block): each step is one loop over the block's
// arrays. The steps that vectorise read the camera's constants from local copies (see
// batch_kernels.hpp).

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
    const Scalar* u_pairs;
    const std::uint8_t* fast_ok;  // per cell
    const std::uint8_t* lut_ok;
    int stride;  // nodes per row
    Scalar origin_x, origin_y, inv_step;
    Scalar end_x, end_y;  // a pixel's grid coordinates must lie in [1, end) for its bicubic stencil to fit
    Scalar last_x, last_y;  // the largest coordinates below end_x, end_y

    explicit TableView(const UnprojectionTable<Scalar>& table)
        : u_pairs(table.u_pairs.data()),
          fast_ok(table.fast_ok.data()),
          lut_ok(table.lut_ok.data()),
          stride(table.nodes_x),
          origin_x(Scalar(table.origin_x)),
          origin_y(Scalar(table.origin_y)),
          inv_step(table.step > 0 ? Scalar(1 / table.step) : Scalar(0)),
          end_x(Scalar(table.nodes_x - 2)),
          end_y(Scalar(table.nodes_y - 2)),
          last_x(std::nextafter(end_x, Scalar(0))),
          last_y(std::nextafter(end_y, Scalar(0))) {}
};

// The table cell of each pixel: the index of its top-left node and the fractions within
// it; ok = 1 only where its stencil fits in the table and its m lies in the certified
// disc (without the full solver only such a pixel may be called valid). A pixel whose
// stencil would leave the table, or whose coordinates are not finite, is clamped to the
// nearest cell whose stencil fits, so that every read stays in bounds (its estimate is
// not used: ok = 0). Clamps rather than a choice between the pixel and a fixed cell: GCC
// turned that choice into branches in float, and left the loop scalar. The arrays never
// overlap (restrict): the block's pixels are the caller's or the block's own, and without
// that promise GCC leaves the loop scalar rather than check every pair.
template <class Scalar>
[[gnu::always_inline]] inline void locate_pixels(const TableView<Scalar>& table, Scalar certified_radius_squared,
                                                 const Scalar* __restrict pixel_x, const Scalar* __restrict pixel_y,
                                                 const Scalar* __restrict m_x, const Scalar* __restrict m_y,
                                                 std::size_t count, int* __restrict cell,
                                                 Scalar* __restrict fraction_x, Scalar* __restrict fraction_y,
                                                 Scalar* __restrict ok) {
    for (std::size_t i = 0; i < count; ++i) {
        const Scalar gx = (pixel_x[i] - table.origin_x) * table.inv_step;
        const Scalar gy = (pixel_y[i] - table.origin_y) * table.inv_step;
        const bool inside = (gx >= Scalar(1)) & (gx < table.end_x) & (gy >= Scalar(1)) & (gy < table.end_y);  // no branch
        // max(1, NaN) is 1: (1 < NaN) is false.
        const Scalar x = std::min(std::max(Scalar(1), gx), table.last_x);
        const Scalar y = std::min(std::max(Scalar(1), gy), table.last_y);
        const int column = static_cast<int>(x), row = static_cast<int>(y);
        cell[i] = row * table.stride + column;
        fraction_x[i] = x - Scalar(column);
        fraction_y[i] = y - Scalar(row);
        const bool certified = m_x[i] * m_x[i] + m_y[i] * m_y[i] < certified_radius_squared;
        ok[i] = batch::flag<Scalar>(inside & certified);
    }
}

template <class Scalar>
void locate_in_table(const TableView<Scalar>& table_view, Scalar certified_radius_squared, Block<Scalar>& b) {
    const TableView<Scalar> table = table_view;
    locate_pixels(table, certified_radius_squared, b.pixel_x, b.pixel_y, b.m_x, b.m_y, b.count, b.cell, b.fraction_x,
                  b.fraction_y, b.ok);
}

// Both interpolations read the table's nodes as (x, y) pairs from its node-by-node copy,
// one pixel at a time and both coordinates at once in two-lane vectors, which every
// instruction set has: one read per node where the loop over pixels would gather two
// single values per node and pixel (gathers cost about a value per cycle here; four
// lanes went through the stack on SSE2). The sums are bilinear()'s and bicubic()'s, the
// table check's, so the bits are too. A node without a ray is NaN and makes u NaN; no
// test for it here (a branch in these loops): every method's last check rejects a NaN u
// (see estimate). With kCheckCell, ok is also kept only in the cells marked in `cell_ok`
// (check_cells), read in the same loop rather than gathered in one of its own. (NodePairs
// is in unprojector_table.hpp, outside this file's target region, so that the shared
// sums, compiled for the baseline, may inline it.)
template <bool kCheckCell, class Scalar>
[[gnu::always_inline]] inline void bilinear_pixels(const Scalar* __restrict pairs, int stride, std::size_t count,
                                                   const int* __restrict cell, const Scalar* __restrict fraction_x,
                                                   const Scalar* __restrict fraction_y, const std::uint8_t* __restrict cell_ok,
                                                   Scalar* __restrict u_x, Scalar* __restrict u_y,
                                                   Scalar* __restrict ok) {
    const NodePairs<Scalar> node{pairs};
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t k = static_cast<std::size_t>(cell[i]);
        const auto u = bilinear(node, k, static_cast<std::size_t>(stride), fraction_x[i], fraction_y[i]);
        u_x[i] = u[0];
        u_y[i] = u[1];
        if constexpr (kCheckCell) ok[i] = cell_ok[k] != 0 ? ok[i] : Scalar(0);
    }
}

// Bicubic: the weights first, in a loop over the block's pixels that vectorises, then the
// sums, a pixel at a time.
template <bool kCheckCell, class Scalar>
[[gnu::always_inline]] inline void bicubic_pixels(const Scalar* __restrict pairs, int stride, std::size_t count,
                                                  const int* __restrict cell, const Scalar* __restrict fraction_x,
                                                  const Scalar* __restrict fraction_y, const std::uint8_t* __restrict cell_ok,
                                                  Scalar* __restrict u_x, Scalar* __restrict u_y,
                                                  Scalar* __restrict ok) {
    Scalar wx[kBlock][4], wy[kBlock][4];
    for (std::size_t i = 0; i < count; ++i) {
        catmull_rom_weights(fraction_x[i], wx[i]);
        catmull_rom_weights(fraction_y[i], wy[i]);
    }
    const NodePairs<Scalar> node{pairs};
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t k = static_cast<std::size_t>(cell[i]);
        const auto u = bicubic(node, k, static_cast<std::size_t>(stride), wx[i], wy[i]);
        u_x[i] = u[0];
        u_y[i] = u[1];
        if constexpr (kCheckCell) ok[i] = cell_ok[k] != 0 ? ok[i] : Scalar(0);
    }
}

// Each pixel's cell and u interpolated there by `kind`; with `cell_ok` (fast's or lut's
// marks), ok kept only in the cells marked.
template <Interpolation kind, class Scalar>
void start_from_table(const Context<Scalar>& context, const std::uint8_t* cell_ok, Block<Scalar>& b) {
    const TableView<Scalar> table = context.table;
    locate_in_table(table, context.certified_radius_squared, b);
    const auto interpolate = [&]<bool kCheckCell>() {
        if constexpr (kind == Interpolation::Bilinear) {
            bilinear_pixels<kCheckCell>(table.u_pairs, table.stride, b.count, b.cell, b.fraction_x, b.fraction_y,
                                        cell_ok, b.u_x, b.u_y, b.ok);
        } else {
            bicubic_pixels<kCheckCell>(table.u_pairs, table.stride, b.count, b.cell, b.fraction_x, b.fraction_y,
                                       cell_ok, b.u_x, b.u_y, b.ok);
        }
    };
    if (cell_ok) {
        interpolate.template operator()<true>();
    } else {
        interpolate.template operator()<false>();
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
    int unsettled = 0;  // counted first, in a loop that vectorises: most blocks have none
    for (std::size_t i = 0; i < b.count; ++i) unsettled += b.ok[i] == Scalar(0) ? 1 : 0;
    if (unsettled == 0) return;
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

// Where a block's rays go: the three arrays of b.rays, or interleaved at b.ray_groups,
// written in the loop that computes them (a copy after the block would write its lines
// in one burst, which waits on memory for a batch larger than the cache): numpy's (N, 3)
// triples, or the directions of Unprojection entries, four doubles apart.
enum class RayLayout { Arrays, Triples, Entries };

template <RayLayout layout, class Scalar>
[[gnu::always_inline]] inline void set_ray(Block<Scalar>& b, std::size_t i, bool ok, const Vec3L<Scalar>& ray) {
    const Scalar x = ok ? lane_value(ray.x()) : Scalar(0);
    const Scalar y = ok ? lane_value(ray.y()) : Scalar(0);
    const Scalar z = ok ? lane_value(ray.z()) : Scalar(0);
    if constexpr (layout == RayLayout::Arrays) {
        b.rays.x[i] = x;
        b.rays.y[i] = y;
        b.rays.z[i] = z;
    } else {
        constexpr std::size_t stride = layout == RayLayout::Triples ? 3 : 4;
        b.ray_groups[stride * i] = x;
        b.ray_groups[stride * i + 1] = y;
        b.ray_groups[stride * i + 2] = z;
    }
}

template <class Model, RayLayout layout, class Scalar>
void rays_from_undistorted(const typename Model::Parameters& lens, Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) {
        set_ray<layout>(b, i, b.ok[i] > Scalar(0), Model::ray_from_undistorted(lens, Vec2L<Scalar>(b.u_x[i], b.u_y[i])));
    }
}

template <class Model, RayLayout layout, class Scalar>
void unproject_closed_form(const typename Model::Parameters& lens_parameters, Block<Scalar>& b) {
    const typename Model::Parameters lens = lens_parameters;
    for (std::size_t i = 0; i < b.count; ++i) {
        Vec3L<Scalar> ray = Vec3L<Scalar>::Zero();
        const bool ok = Model::unproject(lens, Vec2L<Scalar>(b.m_x[i], b.m_y[i]), ray);
        set_ray<layout>(b, i, ok, ray);
        b.ok[i] = batch::flag<Scalar>(ok);
    }
}

// u by `method`, with ok = 1 where that settles it (see approximate). A u interpolated
// from a node without a ray is NaN, and each method's last check (require_valid_radius,
// certify) fails for NaN: such a pixel goes to the full solver.
template <class Model, class Scalar>
void estimate(const Context<Scalar>& context, const typename Model::Parameters& lens, UnprojectMethod method,
              Block<Scalar>& b) {
    switch (method) {
        case UnprojectMethod::Lut:
            start_from_table<Interpolation::Bicubic>(context, context.table.lut_ok, b);
            require_valid_radius(context.valid_radius_squared, b);
            return;
        case UnprojectMethod::Fast:
            start_from_table<Interpolation::Bilinear>(context, context.table.fast_ok, b);
            newton_steps<Model>(lens, kFastNewtonSteps, b);
            require_valid_radius(context.valid_radius_squared, b);
            return;
        case UnprojectMethod::Exact:
            start_from_table<Interpolation::Bilinear>(context, nullptr, b);
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

template <class Model, RayLayout layout, class Scalar>
void unproject_block(const Context<Scalar>& context, const LensPair<Model>& lens, UnprojectMethod method,
                     Block<Scalar>& b) {
    normalize(context.intrinsics, b);
    if constexpr (SolvedLensModel<Model>) {
        approximate<Model>(context, lens.lanes, method, b);
        solve_remaining<typename LensPair<Model>::Plain>(context, lens.plain, b);
        rays_from_undistorted<Model, layout>(lens.lanes, b);
    } else {
        unproject_closed_form<Model, layout>(lens.lanes, b);
    }
}


// numpy's (N, 2) pixels into one array per coordinate: a loop GCC vectorises with
// shuffles at the kernel's width, on arrays that do not overlap.
template <class Scalar>
void pixels_from_pairs(const Scalar* __restrict pairs, std::size_t count, Scalar* __restrict x, Scalar* __restrict y) {
    for (std::size_t i = 0; i < count; ++i) {
        x[i] = pairs[2 * i];
        y[i] = pairs[2 * i + 1];
    }
}

// The flags of a block's Unprojection entries, one entry apart.
template <class Scalar>
void store_entry_flags(const Scalar* ok, std::size_t count, bool* first, std::size_t entry_bytes) {
    for (std::size_t i = 0; i < count; ++i) {
        *reinterpret_cast<bool*>(reinterpret_cast<char*>(first) + entry_bytes * i) = ok[i] > Scalar(0);
    }
}

// Pixels [begin, end) of a job, block by block.
template <class Scalar>
void unproject(const UnprojectJob<Scalar>& job, std::size_t begin, std::size_t end) {
    const TableView<Scalar> table(job.table);
    const Context<Scalar> context{job.camera.intrinsics,
                                  table,
                                  Scalar(job.certified_radius * job.certified_radius),
                                  Scalar(job.no_ray_radius * job.no_ray_radius),
                                  job.rim,
                                  Scalar(job.valid_radius * job.valid_radius)};
    visit_lens_model<Lane<Scalar>>(job.camera.lens.type, [&]<class Model>() {
        const LensPair<Model> lens(job.camera.lens, job.valid_radius);
        Block<Scalar> block;
        typename BlockIo<Scalar>::Scratch scratch;
        // A block of pixels from interleaved pairs, its rays written to `rays` with `layout`.
        const auto from_pairs = [&]<RayLayout layout>(const Scalar* pairs, Scalar* rays, std::size_t first) {
            // The next block's pixels (its rays are written as they are computed).
            batch::prefetch_for_reading(pairs + 2 * (first + block.count), 2 * std::min(kBlock, end - first - block.count));
            block.ray_groups = rays;
            pixels_from_pairs(pairs + 2 * first, block.count, block.made_x, block.made_y);
            block.pixel_x = block.made_x;
            block.pixel_y = block.made_y;
            unproject_block<Model, layout>(context, lens, job.method, block);
        };
        for (std::size_t first = begin; first < end; first += kBlock) {
            block.count = std::min(kBlock, end - first);
            if (job.interleaved) {
                block.rays = {nullptr, nullptr, nullptr, job.interleaved->valid + first};
                from_pairs.template operator()<RayLayout::Triples>(job.interleaved->pixels,
                                                                  job.interleaved->directions + 3 * first, first);
                batch::store_flags<Scalar>({block.ok, block.count}, block.rays.valid);
            } else if (job.entries) {
                block.rays = {nullptr, nullptr, nullptr, nullptr};
                from_pairs.template operator()<RayLayout::Entries>(job.entries->pixels,
                                                                  job.entries->directions + 4 * first, first);
                bool* const first_flag =
                    reinterpret_cast<bool*>(reinterpret_cast<char*>(job.entries->valid) + job.entries->entry_bytes * first);
                store_entry_flags(block.ok, block.count, first_flag, job.entries->entry_bytes);
            } else {
                block.rays = job.io->at(first, scratch);
                job.io->fill(first, block);
                unproject_block<Model, RayLayout::Arrays>(context, lens, job.method, block);
                batch::store_flags<Scalar>({block.ok, block.count}, block.rays.valid);
                job.io->done(first, block.count, scratch);
            }
        }
    });
}
