// The projection kernel, compiled once per instruction set: included only by
// camera/kernels_for_target.hpp, inside its target region, which has included every
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

// How a job's points and pixels lie in memory (kernels.hpp's ProjectJob): the distance
// between consecutive points' coordinates and pixels' coordinates, known at compile time
// so that the interleaved loads and stores become vector shuffles.
enum class Layout { Arrays, Interleaved };

template <Layout layout>
inline constexpr std::size_t kPointStep = layout == Layout::Interleaved ? 3 : 1;
template <Layout layout>
inline constexpr std::size_t kPixelStep = layout == Layout::Interleaved ? 2 : 1;

// Those points again, one by one, in Scalar (the same bits Lane gives where both
// apply), scaled into [1, 2) first (point_scale.hpp). Rare: out of line, where it does not
// take the inlining budget of the vectorised loop.
template <class Model, Layout layout, class Scalar>
[[gnu::noinline]] void project_second_pass(const Intrinsics& intrinsics, const ProjectorLens<Model, Scalar>& lens,
                                           const std::array<const Scalar*, 3>& points, std::size_t count,
                                           Scalar* pixel_x, Scalar* pixel_y, Scalar* flags) {
    using Plain = typename ProjectorLens<Model, Scalar>::Plain;
    constexpr std::size_t s = kPointStep<layout>, p = kPixelStep<layout>;
    const auto [x, y, z] = points;
    for (std::size_t i = 0; i < count; ++i) {
        if (!needs_second_pass<Model>(x[i * s], y[i * s], z[i * s], flags[i])) continue;
        const Vec3T<Scalar> scaled = scaled_to_unit_range<Scalar>(Vec3T<Scalar>(x[i * s], y[i * s], z[i * s]));
        flags[i] = batch::flag<Scalar>(
            project_point<Plain>(intrinsics, lens.plain, scaled, pixel_x[i * p], pixel_y[i * p]));
    }
}

// Points [begin, end) through Model (in Lane<Scalar>), block by block.
template <class Model, Layout layout, class Scalar>
void project_range(const Intrinsics& camera_intrinsics, const ProjectorLens<Model, Scalar>& camera_lens,
                   const ProjectJob<Scalar>& job, std::size_t begin, std::size_t end) {
    using Vec3L = typename Model::Vec3T;
    constexpr std::size_t s = kPointStep<layout>, p = kPixelStep<layout>;
    // Local copies, which no store to the outputs can alias: see batch_kernels.hpp.
    const Intrinsics intrinsics = camera_intrinsics;
    const typename Model::Parameters lens = camera_lens.lanes;
    Scalar flags[kBlock];
    for (std::size_t first = begin; first < end; first += kBlock) {
        const std::size_t count = std::min(kBlock, end - first);
        const Scalar* x = job.x + first * s;
        const Scalar* y = job.y + first * s;
        const Scalar* z = job.z + first * s;
        Scalar* pixel_x = job.pixel_x + first * p;
        Scalar* pixel_y = job.pixel_y + first * p;
        for (std::size_t i = 0; i < count; ++i) {
            const bool ok = project_point<Model>(intrinsics, lens, Vec3L(x[i * s], y[i * s], z[i * s]), pixel_x[i * p],
                                                 pixel_y[i * p]);
            flags[i] = batch::flag<Scalar>(ok);
        }
        int again = 0;  // its own loop: an int sum, which vectorises
        for (std::size_t i = 0; i < count; ++i) {
            again += needs_second_pass<Model>(x[i * s], y[i * s], z[i * s], flags[i]) ? 1 : 0;
        }
        if (again > 0) {
            project_second_pass<Model, layout>(intrinsics, camera_lens, {x, y, z}, count, pixel_x, pixel_y, flags);
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
