#pragma once
// Every lens model, and the one dispatch from a runtime LensType to its compile-time
// implementation, generated from LIBCAM_LENS_MODEL_LIST (lens_model.hpp).
//
// Each model is a stateless struct template on the scalar type with
//   type, num_coefficients, Parameters (= LensParameters<Scalar, num_coefficients>),
//   Parameters parameters(std::span<const double> coefficients)  the domain, once per camera
//   bool project(parameters, point, m, d_m_d_point = nullptr, d_m_d_coefficients = nullptr)
//   bool unproject(parameters, m, ray)

#include <string>
#include <utility>

#include "libcam/error.hpp"
#include "libcam/lens/fisheye.hpp"
#include "libcam/lens/latlon.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/lonlat.hpp"
#include "libcam/lens/opencv.hpp"
#include "libcam/lens/pinhole.hpp"
#include "libcam/lens/stereographic.hpp"

namespace libcam {

#define LIBCAM_LENS_CHECK(id, name, n, behind, model)                                            \
    static_assert(model<double>::type == LensType::id && model<double>::num_coefficients == (n), \
                  "LIBCAM_LENS_MODEL_LIST: " name " disagrees with its implementation");
LIBCAM_LENS_MODEL_LIST(LIBCAM_LENS_CHECK)
#undef LIBCAM_LENS_CHECK

// The same model in another scalar type: LensInScalar<OpenCvLens<double, 8>, long double>
// is OpenCvLens<long double, 8>.
template <class Model, class Scalar>
struct RebindLens;
template <template <class> class ModelTemplate, class Old, class Scalar>
struct RebindLens<ModelTemplate<Old>, Scalar> {
    using type = ModelTemplate<Scalar>;
};
template <class Old, int N, class Scalar>
struct RebindLens<OpenCvLens<Old, N>, Scalar> {
    using type = OpenCvLens<Scalar, N>;
};
template <class Model, class Scalar>
using LensInScalar = typename RebindLens<Model, Scalar>::type;

// Calls visitor.template operator()<Model>() with the implementation of `type` in
// Scalar, e.g.  visit_lens_model<double>(lens.type, [&]<class Model>() { ... });
template <class Scalar, class Visitor>
decltype(auto) visit_lens_model(LensType type, Visitor&& visitor) {
    switch (type) {
#define LIBCAM_LENS_VISIT(id, name, n, behind, model) \
    case LensType::id: return std::forward<Visitor>(visitor).template operator()<model<Scalar>>();
        LIBCAM_LENS_MODEL_LIST(LIBCAM_LENS_VISIT)
#undef LIBCAM_LENS_VISIT
    }
    throw InvalidArgument("lens: unknown model type #" + std::to_string(static_cast<int>(type)));
}

}  // namespace libcam
