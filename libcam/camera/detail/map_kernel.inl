// The remap map kernel (remap/remap_map.hpp), compiled once per instruction set: included
// only by camera/detail/kernels_for_target.hpp, inside its target region, after
// projector_kernel.inl and unprojector_kernel.inl (no #include here: see
// projector_kernel.inl).
//
// A map's entries are computed a block of pixels at a time, every step in the kernel's
// instruction set and on arrays that stay in the first-level cache: the block's rays in
// the source camera's frame (from K^-1 for a PINHOLE target, else the target's
// unprojection turned), their pixels through the source lens (project_block, the
// Projector's own loop, so the same bits), and the entries written, NaN where the pixel
// has no source. The projection is the only step that depends on the lens model, and the
// only one compiled once per model; the others are one loop each for any model.

// The rays of a block of a PINHOLE target's pixels, (column, row) to (column + count - 1,
// row): K^-1 [x, y, 1] by normalized_from_pixel, as the target's unprojection gives them
// (z = 1), turned into the source's frame where the job says.
// The columns are ints: a loop converting 64-bit integers to double stays scalar below
// AVX-512 (an image side is at most kMaxImageSide).
[[gnu::always_inline]] inline void pinhole_block_rays(const MapJob& job, int column, int row, int count,
                                                      double* __restrict x, double* __restrict y,
                                                      double* __restrict z) {
    const Intrinsics intrinsics = *job.target_intrinsics;  // a local copy: see batch_kernels.hpp
    const Lane<double> pixel_y(static_cast<double>(row));
    if (!job.turned) {
        for (int i = 0; i < count; ++i) {
            const Vec2L<double> m = intrinsics.normalized_from_pixel(Vec2L<double>(static_cast<double>(column + i), pixel_y));
            x[i] = lane_value(m.x());
            y[i] = lane_value(m.y());
            z[i] = 1.0;
        }
        return;
    }
    // to_source (xn, yn, 1) = xn column 0 + (yn column 1 + column 2)
    const Mat3 r = job.to_source;
    for (int i = 0; i < count; ++i) {
        const Vec2L<double> m = intrinsics.normalized_from_pixel(Vec2L<double>(static_cast<double>(column + i), pixel_y));
        const double xn = lane_value(m.x()), yn = lane_value(m.y());
        x[i] = r(0, 0) * xn + (r(0, 1) * yn + r(0, 2));
        y[i] = r(1, 0) * xn + (r(1, 1) * yn + r(1, 2));
        z[i] = r(2, 0) * xn + (r(2, 1) * yn + r(2, 2));
    }
}

// A block's rays in the source's frame: made from K^-1, or the caller's (turned).
struct BlockRays {
    const double* x;
    const double* y;
    const double* z;
    const std::uint8_t* has_ray;  // nullptr: every ray
};

// The rays of entries [first, first + count) (count <= kBlock, within one row when they
// come from K^-1): made in x, y, z, or the caller's `rays` from entry `begin` on, turned
// into x, y, z where the job says (rotation * d, as Eigen evaluates it elsewhere).
inline BlockRays block_rays(const MapJob& job, const MapRays* rays, std::size_t begin, std::size_t first,
                            std::size_t count, double* __restrict x, double* __restrict y, double* __restrict z) {
    if (rays == nullptr) {
        pinhole_block_rays(job, static_cast<int>(first % job.width), static_cast<int>(first / job.width),
                           static_cast<int>(count), x, y, z);
        return {x, y, z, nullptr};
    }
    const std::size_t at = first - begin;
    if (!job.turned) return {rays->x + at, rays->y + at, rays->z + at, rays->valid + at};
    for (std::size_t i = 0; i < count; ++i) {
        const Vec3 d = job.to_source * Vec3(rays->x[at + i], rays->y[at + i], rays->z[at + i]);
        x[i] = d.x();
        y[i] = d.y();
        z[i] = d.z();
    }
    return {x, y, z, rays->valid + at};
}

// A block's pixels through the source lens, flags 1 where valid.
struct ProjectedBlock {
    const double* pixel_x;
    const double* pixel_y;
    const double* projected;
    const std::uint8_t* has_ray;  // nullptr: every ray
    std::size_t count;
};

// The entries of a block: its pixel where the ray has one, its projection is valid and
// the pixel lies on the source image, NaN elsewhere. The test is made in double, before
// any rounding to Out, so a float map leaves out exactly the pixels the double map does.
// Returns how many have a source.
template <class Out, bool kEveryRay>
[[gnu::always_inline]] inline std::size_t write_entries(const double* __restrict pixel_x, const double* __restrict pixel_y,
                                                        const double* __restrict projected,
                                                        const std::uint8_t* __restrict has_ray, std::size_t count,
                                                        const ImageSize& source_size, Out* __restrict out_x,
                                                        Out* __restrict out_y) {
    constexpr Out kNaN = std::numeric_limits<Out>::quiet_NaN();
    std::size_t found = 0;
    for (std::size_t i = 0; i < count; ++i) {
        const double x = pixel_x[i], y = pixel_y[i];
        const bool ray = kEveryRay || has_ray[i] != 0;
        const bool on = on_image(x, y, source_size);
        const bool has = ray & (projected[i] > 0.0) & on;  // &: no branch
        out_x[i] = has ? static_cast<Out>(x) : kNaN;
        out_y[i] = has ? static_cast<Out>(y) : kNaN;
        found += has ? 1 : 0;
    }
    return found;
}

// Entries [first, first + block.count) of `output` (a MapOutput<Out>).
template <class Out>
std::size_t write_block(const void* output, std::size_t first, const ProjectedBlock& block, const ImageSize& source_size) {
    const MapOutput<Out>& out = *static_cast<const MapOutput<Out>*>(output);
    const ImageSize size = source_size;
    if (block.has_ray == nullptr) {
        return write_entries<Out, true>(block.pixel_x, block.pixel_y, block.projected, nullptr, block.count, size,
                                        out.x + first, out.y + first);
    }
    return write_entries<Out, false>(block.pixel_x, block.pixel_y, block.projected, block.has_ray, block.count, size,
                                     out.x + first, out.y + first);
}

// How a map's entries are written: write(output, ...) for the map's scalar. Passed to the
// lens's loop rather than making it a template of the scalar: the loop is compiled once
// per model, for float and double maps alike.
struct EntryWriter {
    const void* output;
    std::size_t (*write)(const void* output, std::size_t first, const ProjectedBlock& block, const ImageSize& source_size);
};

// Entries [begin, end) through Model, block by block (a block never crosses a row, so
// that rays from K^-1 share the row's yn). The projection is the Projector's own loop
// (project_block) on the block's arrays: the same bits as Projector::project.
template <class Model>
[[gnu::noinline]] std::size_t map_range(const MapJob& job, const ProjectorLens<Model, double>& camera_lens,
                                        const MapRays* rays, const EntryWriter& writer, std::size_t begin,
                                        std::size_t end) {
    const Intrinsics intrinsics = job.source.intrinsics;  // local copies: see batch_kernels.hpp
    const typename Model::Parameters lens = camera_lens.lanes;
    alignas(64) double x[kBlock], y[kBlock], z[kBlock];
    alignas(64) double pixel_x[kBlock], pixel_y[kBlock], projected[kBlock];
    std::size_t found = 0;
    for (std::size_t first = begin; first < end;) {
        const std::size_t row_left = rays == nullptr ? job.width - first % job.width : kBlock;
        const std::size_t count = std::min({kBlock, end - first, row_left});
        const BlockRays in = block_rays(job, rays, begin, first, count, x, y, z);
        project_block<Model, Layout::Arrays>(intrinsics, lens, camera_lens, in.x, in.y, in.z, count, pixel_x, pixel_y,
                                             projected);
        found += writer.write(writer.output, first, {pixel_x, pixel_y, projected, in.has_ray, count}, job.source.size);
        first += count;
    }
    return found;
}

// Entries [begin, end) of a map in Out: see KernelSet::map.
template <class Out>
std::size_t map(const MapJob& job, const MapRays* rays, const MapOutput<Out>& output, std::size_t begin, std::size_t end) {
    const EntryWriter writer{&output, &write_block<Out>};
    return visit_lens_model<Lane<double>>(job.source.lens.type, [&]<class Model>() {
        const ProjectorLens<Model, double> lens(job.source.lens, job.source_valid_radius);
        return map_range<Model>(job, lens, rays, writer, begin, end);
    });
}
