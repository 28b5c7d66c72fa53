#include "libcam/camera/projector.hpp"

#include <algorithm>

#include "libcam/camera/batch_kernels.hpp"
#include "libcam/camera/parallel.hpp"

namespace libcam {

namespace {

// Points [begin, end) through Model (in Lane<Scalar>), block by block.
template <class Model, class Scalar>
void project_range(const Intrinsics& camera_intrinsics, const typename Model::Parameters& lens_parameters,
                   const Points3<Scalar>& points, std::size_t begin, std::size_t end, Points2<Scalar>& pixels,
                   ValidFlags& valid) {
    using Vec2L = typename Model::Vec2T;
    using Vec3L = typename Model::Vec3T;
    // Local copies, which no store to the outputs can alias: see batch_kernels.hpp.
    const Intrinsics intrinsics = camera_intrinsics;
    const typename Model::Parameters lens = lens_parameters;
    Scalar flags[batch::kBlock];
    for (std::size_t first = begin; first < end; first += batch::kBlock) {
        const std::size_t count = std::min(batch::kBlock, end - first);
        const Scalar* x = points.x.data() + first;
        const Scalar* y = points.y.data() + first;
        const Scalar* z = points.z.data() + first;
        Scalar* pixel_x = pixels.x.data() + first;
        Scalar* pixel_y = pixels.y.data() + first;
        for (std::size_t i = 0; i < count; ++i) {
            Vec2L m;
            const bool ok = Model::project(lens, Vec3L(x[i], y[i], z[i]), m);
            const Vec2L pixel = intrinsics.pixel_from_normalized(m);
            pixel_x[i] = ok ? lane_value(pixel.x()) : Scalar(0);
            pixel_y[i] = ok ? lane_value(pixel.y()) : Scalar(0);
            flags[i] = batch::flag<Scalar>(ok);
        }
        batch::store_flags<Scalar>({flags, count}, valid.data() + first);
    }
}

}  // namespace

template <class Scalar>
Projector<Scalar>::Projector(const Camera& camera) : camera_(camera) {
    camera_.validate();
    valid_radius_ = batch::lens_valid_radius(camera_.lens);
}

template <class Scalar>
void Projector<Scalar>::project(const Points3<Scalar>& camera_points, Points2<Scalar>& pixels, ValidFlags& valid,
                                int threads) const {
    const std::size_t n = camera_points.size();
    batch::require_same_sizes("camera_points", n, {camera_points.y.size(), camera_points.z.size()});
    pixels.resize(n);
    valid.resize(n);
    visit_lens_model<Lane<Scalar>>(camera_.lens.type, [&]<class Model>() {
        const auto lens = batch::model_parameters<Model>(camera_.lens, valid_radius_);
        parallel_chunks(n, threads, batch::kBlock, [&](std::size_t begin, std::size_t end) {
            project_range<Model>(camera_.intrinsics, lens, camera_points, begin, end, pixels, valid);
        });
    });
}

template class Projector<float>;
template class Projector<double>;

}  // namespace libcam
