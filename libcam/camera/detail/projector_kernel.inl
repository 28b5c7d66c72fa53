// The projection kernel, compiled once per instruction set: included only by
// camera/detail/kernels_for_target.hpp, inside its target region, which has included every
// header this file uses (no #include here: a header first included inside the region
// would compile its inline functions for the region's instruction set).

// The pixel of one camera point through Model; invalid outside the domain, or where the
// pixel is not finite (K m can overflow). Always inlined: called from two places, it
// would otherwise stay a call in the hot loop.
template <class Model, class Scalar>
[[gnu::always_inline]] inline bool project_point(const Intrinsics& intrinsics, const typename Model::Parameters& lens,
                                                 const typename Model::Vec3T& point, Scalar& pixel_x,
                                                 Scalar& pixel_y) {
    using Vec2L = typename Model::Vec2T;
    Vec2L m = Vec2L::Zero();  // not every model writes m for a point outside its domain
    const bool in_domain = Model::project(lens, point, m);
    const Vec2L pixel = intrinsics.pixel_from_normalized(m);
    const Scalar x = lane_value(pixel.x()), y = lane_value(pixel.y());
    // Not isfinite but a comparison, which vectorises; NaN fails it too.
    constexpr Scalar largest = std::numeric_limits<Scalar>::max();
    const bool x_finite = std::abs(x) <= largest, y_finite = std::abs(y) <= largest;
    const bool ok = in_domain & x_finite & y_finite;  // &, not &&: no branch
    pixel_x = ok ? x : Scalar(0);
    pixel_y = ok ? y : Scalar(0);
    return ok;
}

// The model in Lane<Scalar> for the vectorised pass, and in Scalar for the points that
// pass leaves to a second one.
template <class Model, class Scalar>
using ProjectorLens = batch::BatchLens<Model, Scalar>;

// Whether the vectorised pass may have got a point wrong: for PINHOLE and OpenCV's
// models a point in front of the camera that it flagged (in Lane the rational factor
// skips its overflow-safe form, see opencv.hpp); for the others a point outside the
// comfortable range.
template <class Model, class Scalar>
bool needs_second_pass(Scalar x, Scalar y, Scalar z, Scalar flag) {
    if constexpr (ProjectsRatios<Model>) {
        (void)x, (void)y;
        return (flag == Scalar(0)) & (z > Scalar(0));  // &, not &&: no branch
    } else {
        (void)flag;
        return detail::needs_scaling<Model>(x, y, z);
    }
}

// How a job's points and pixels lie in memory (kernels.hpp's ProjectJob): separate arrays,
// or numpy's (N, 3) points and (N, 2) pixels.
enum class Layout { Arrays, Interleaved };

// Those points again, one by one, in Scalar (the same bits Lane gives where both
// apply), scaled into [1, 2) first (point_scale.hpp). Rare: out of line, where it does not
// take the inlining budget of the vectorised loop.
template <class Model, class Scalar>
[[gnu::noinline]] void project_second_pass(const Intrinsics& intrinsics, const ProjectorLens<Model, Scalar>& lens,
                                           const std::array<const Scalar*, 3>& points, std::size_t count,
                                           Scalar* pixel_x, Scalar* pixel_y, std::size_t pixel_stride, Scalar* flags) {
    using Plain = typename ProjectorLens<Model, Scalar>::Plain;
    const auto [x, y, z] = points;
    for (std::size_t i = 0; i < count; ++i) {
        if (!needs_second_pass<Model>(x[i], y[i], z[i], flags[i])) continue;
        const Vec3T<Scalar> scaled = scaled_to_unit_range<Scalar>(Vec3T<Scalar>(x[i], y[i], z[i]));
        flags[i] = batch::flag<Scalar>(
            project_point<Plain>(intrinsics, lens.plain, scaled, pixel_x[pixel_stride * i], pixel_y[pixel_stride * i]));
    }
}

// One block of at most kBlock points, each coordinate its own array; the pixels go to
// two arrays, or as numpy's (N, 2) pairs to pixel_x (pixel_y unused), written by the loop
// that computes them. No output overlaps an input or another output (restrict): without
// that promise GCC must check every pair before it vectorises, and gives up past ten pairs.
template <class Model, Layout pixels, class Scalar>
[[gnu::always_inline]] inline void project_block(const Intrinsics& intrinsics, const typename Model::Parameters& lens,
                                                 const ProjectorLens<Model, Scalar>& camera_lens,
                                                 const Scalar* __restrict x, const Scalar* __restrict y,
                                                 const Scalar* __restrict z, std::size_t count,
                                                 Scalar* __restrict pixel_x, Scalar* __restrict pixel_y,
                                                 Scalar* __restrict flags) {
    using Vec3L = typename Model::Vec3T;
    for (std::size_t i = 0; i < count; ++i) {
        Scalar u, v;
        const bool ok = project_point<Model>(intrinsics, lens, Vec3L(x[i], y[i], z[i]), u, v);
        if constexpr (pixels == Layout::Interleaved) {
            pixel_x[2 * i] = u;
            pixel_x[2 * i + 1] = v;
        } else {
            pixel_x[i] = u;
            pixel_y[i] = v;
        }
        flags[i] = batch::flag<Scalar>(ok);
    }
    int again = 0;  // its own loop: an int sum, which vectorises
    for (std::size_t i = 0; i < count; ++i) again += needs_second_pass<Model>(x[i], y[i], z[i], flags[i]) ? 1 : 0;
    if (again == 0) return;
    if constexpr (pixels == Layout::Interleaved) {
        project_second_pass<Model>(intrinsics, camera_lens, {x, y, z}, count, pixel_x, pixel_x + 1, 2, flags);
    } else {
        project_second_pass<Model>(intrinsics, camera_lens, {x, y, z}, count, pixel_x, pixel_y, 1, flags);
    }
}

// Points [begin, end) through Model (in Lane<Scalar>), block by block. Interleaved points
// are copied into arrays first, a loop that does nothing but shuffle, where the model's
// loop reading stride-3 data vectorised poorly (1.5x the arrays' time); the pixels are
// written as pairs by the model's loop (a copy after the block wrote its lines in one
// burst, which waited on memory).
template <class Model, Layout layout, class Scalar>
void project_range(const Intrinsics& camera_intrinsics, const ProjectorLens<Model, Scalar>& camera_lens,
                   const ProjectJob<Scalar>& job, std::size_t begin, std::size_t end) {
    // Local copies, which no store to the outputs can alias: see batch_kernels.hpp.
    const Intrinsics intrinsics = camera_intrinsics;
    const typename Model::Parameters lens = camera_lens.lanes;
    Scalar flags[kBlock];
    for (std::size_t first = begin; first < end; first += kBlock) {
        const std::size_t count = std::min(kBlock, end - first);
        if constexpr (layout == Layout::Arrays) {
            project_block<Model, Layout::Arrays>(intrinsics, lens, camera_lens, job.x + first, job.y + first,
                                                 job.z + first, count, job.pixel_x + first, job.pixel_y + first, flags);
        } else {
            alignas(64) Scalar x[kBlock], y[kBlock], z[kBlock];
            const Scalar* points = job.x + 3 * first;  // job.x, y, z: the first point's x, y, z
            for (std::size_t i = 0; i < count; ++i) {
                x[i] = points[3 * i];
                y[i] = points[3 * i + 1];
                z[i] = points[3 * i + 2];
            }
            project_block<Model, Layout::Interleaved>(intrinsics, lens, camera_lens, x, y, z, count,
                                                      job.pixel_x + 2 * first, static_cast<Scalar*>(nullptr), flags);
        }
        batch::store_flags<Scalar>({flags, count}, job.valid + first);
    }
}

template <class Scalar, Layout layout>
void project(const ProjectJob<Scalar>& job, std::size_t begin, std::size_t end) {
    visit_lens_model<Lane<Scalar>>(job.camera.lens.type, [&]<class Model>() {
        const ProjectorLens<Model, Scalar> lens(job.camera.lens, job.valid_radius);
        project_range<Model, layout>(job.camera.intrinsics, lens, job, begin, end);
    });
}
