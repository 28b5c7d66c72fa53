#pragma once
// Every lens model's implementation, the rules an implementation follows (the LensModel
// concept), and the one dispatch from a runtime LensType to its compile-time
// implementation, generated from LIBCAM_LENS_MODEL_LIST (lens_model.hpp). Each row of the
// table is checked here against its implementation.
//
// A model is a stateless struct template on the scalar type (float, double, long
// double, Lane<T> for the batch loops, ceres::Jet for fitting) with
//
//   type, num_coefficients            its row of the table
//   InScalar<Other>                    the same model in another scalar type
//   Vec2T, Vec3T, Parameters           Parameters = LensParameters<Scalar, num_coefficients>;
//                                      a model with more to work out per camera (a
//                                      variable coefficient count: num_coefficients =
//                                      Eigen::Dynamic; FOV's tangent of its angle) has
//                                      its own struct holding
//                                      `coefficients` and `valid_radius` too, and
//                                      parameters(coefficients, valid_radius)
//   Parameters parameters(std::span<const double> coefficients)
//                                      the coefficients and the valid domain, worked out
//                                      once per camera (a polynomial root search for
//                                      the models that fold over)
//   bool project(parameters, point, m, d_m_d_point = nullptr, d_m_d_coefficients = nullptr)
//                                      m of a camera point, false outside the domain; the
//                                      Jacobians only when asked for, at no cost otherwise
//   bool unproject(parameters, m, ray) the ray through m, false where m has none
//
// and, for a model whose table row says Inverse::Solved (no closed-form inverse), what
// the iterative solver of undistort.hpp needs:
//
//   bool distort(parameters, u, m, d_m_d_u = nullptr)   m of the undistorted point u
//   Scalar radial_distortion(parameters, r, slope)       the radial part alone, d(r), d'(r)
//   Vec3T ray_from_undistorted(parameters, u)            the ray through u
//
// Optional: `static constexpr bool projects_ratios = true` for a model that starts from
// x / z and y / z (a point at any scale then needs no rescaling, camera/detail/point_scale.hpp).

#include <algorithm>
#include <cmath>
#include <concepts>
#include <numbers>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/lens/brown_k4.hpp"
#include "libcam/lens/cahvor.hpp"
#include "libcam/lens/cahvore.hpp"
#include "libcam/lens/cylindrical.hpp"
#include "libcam/lens/ocamcalib.hpp"
#include "libcam/lens/division.hpp"
#include "libcam/lens/double_sphere.hpp"
#include "libcam/lens/equisolid.hpp"
#include "libcam/lens/eucm.hpp"
#include "libcam/lens/fisheye.hpp"
#include "libcam/lens/fisheye_radial.hpp"
#include "libcam/lens/fov.hpp"
#include "libcam/lens/lane.hpp"
#include "libcam/lens/latlon.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/lens_polynomial.hpp"
#include "libcam/lens/lonlat.hpp"
#include "libcam/lens/mei.hpp"
#include "libcam/lens/opencv.hpp"
#include "libcam/lens/pinhole.hpp"
#include "libcam/lens/ptlens.hpp"
#include "libcam/lens/rad_tan_thin_prism_fisheye.hpp"
#include "libcam/lens/splined_stereographic.hpp"
#include "libcam/lens/stereographic.hpp"
#include "libcam/lens/thin_prism_fisheye.hpp"
#include "libcam/lens/theta_polynomial.hpp"  // WoodScape's fisheye
#include "libcam/lens/ftheta.hpp"  // NVIDIA's F-theta
#include "libcam/lens/ftheta_forward.hpp"
#include "libcam/lens/ucm.hpp"

namespace libcam {

static_assert(kVariableCoefficientCount == Eigen::Dynamic,
              "a model with a variable coefficient count has num_coefficients = Eigen::Dynamic");

template <class Model>
concept LensModel = requires(const typename Model::Parameters& lens, const typename Model::Vec3T& point,
                             typename Model::Vec2T& m, typename Model::Vec3T& ray, std::span<const double> coefficients) {
    { Model::type } -> std::convertible_to<LensType>;
    { Model::num_coefficients } -> std::convertible_to<int>;
    typename Model::template InScalar<double>;
    { Model::parameters(coefficients) } -> std::same_as<typename Model::Parameters>;
    { Model::project(lens, point, m) } -> std::same_as<bool>;
    { Model::unproject(lens, m, ray) } -> std::same_as<bool>;
};

// A model unprojected by the certified iterative solver (lens/undistort.hpp).
template <class Model>
concept SolvedLensModel = LensModel<Model> && requires(const typename Model::Parameters& lens,
                                                       const typename Model::Vec2T& u, typename Model::Vec2T& m,
                                                       typename Model::Vec2T::Scalar r, typename Model::Vec2T::Scalar& slope) {
    { Model::distort(lens, u, m) } -> std::same_as<bool>;
    { Model::radial_distortion(lens, r, slope) } -> std::convertible_to<typename Model::Vec2T::Scalar>;
    { Model::ray_from_undistorted(lens, u) } -> std::convertible_to<typename Model::Vec3T>;
};

// A model that projects through x / z and y / z (optional; see above).
template <class Model>
concept ProjectsRatios = requires { requires Model::projects_ratios; };

// The same model in another scalar type: LensInScalar<OpenCvLens<double, 8>, long double>
// is OpenCvLens<long double, 8>.
template <class Model, class Scalar>
using LensInScalar = typename Model::template InScalar<Scalar>;

namespace detail {
// One row of the table against its implementation, in every scalar type libcam uses.
template <template <class> class Model>
constexpr bool implements_row(LensType type) {
    const LensInfo& info = lens_info(type);
    return Model<double>::type == type && Model<double>::num_coefficients == info.num_coefficients &&
           LensModel<Model<double>> && LensModel<Model<float>> && LensModel<Model<Lane<double>>> &&
           LensModel<Model<Lane<float>>> && (SolvedLensModel<Model<double>> == (info.inverse == Inverse::Solved)) &&
           std::same_as<LensInScalar<Model<double>, float>, Model<float>>;
}
}  // namespace detail

#define LIBCAM_LENS_CHECK(id, model)                                   \
    static_assert(detail::implements_row<model>(LensType::id),        \
                  "kLensTable's row " #id " disagrees with " #model \
                  " (type, coefficient count, LensModel, or Inverse::Solved without distort())");
LIBCAM_LENS_MODEL_LIST(LIBCAM_LENS_CHECK)
#undef LIBCAM_LENS_CHECK

// The largest angle from the optical axis a lens of Model images (radians; pi: every
// direction but the backward axis), from its valid radius: the radius itself for a model
// that sees behind the camera (it measures the radius as that angle), atan of it for a
// perspective model (the radius of (x/z, y/z)), and what the model says
// (Model::valid_angle) for one whose radius is neither (MEI's lies in UCM's plane).
template <class Model>
double valid_angle(std::span<const double> coefficients, double valid_radius) {
    if constexpr (requires { Model::valid_angle(coefficients, valid_radius); }) {
        return Model::valid_angle(coefficients, valid_radius);
    } else if (lens_info(Model::type).sees_behind_camera) {
        return std::min(valid_radius, std::numbers::pi);
    } else {
        return std::atan(valid_radius);
    }
}

// The angle from the optical axis at which the lens's domain ends towards azimuth phi
// (radians; phi = atan2(Y, X) of the camera point): valid_angle for a model whose domain
// is round about the axis, what the model says (Model::edge_angle) for one whose is not
// (SPLINED_STEREOGRAPHIC's rectangle).
template <class Model>
double edge_angle(std::span<const double> coefficients, double valid_radius, double azimuth) {
    if constexpr (requires { Model::edge_angle(coefficients, azimuth); }) {
        return Model::edge_angle(coefficients, azimuth);
    } else {
        return valid_angle<Model>(coefficients, valid_radius);
    }
}

// The angle about the optical axis that no pixel sees (radians): 0 for every model but
// one that says otherwise (Model::blind_angle: FISHEYE_LENS_POLYNOMIAL with k0 != 0,
// whose centre pixel looks |k0| off the axis). Points there are flagged.
template <class Model>
double blind_angle(std::span<const double> coefficients) {
    if constexpr (requires { Model::blind_angle(coefficients); }) {
        return Model::blind_angle(coefficients);
    } else {
        return 0.0;
    }
}

// The coefficients `libcam fit` starts a model from when it has no camera of that model
// to start from: what the model says (Model::fit_start: a start that reaches as wide as
// the model can), else all 0 (the pinhole camera or the equidistant lens most models
// reduce to). `radians_per_unit` is the source's angle from the axis per unit of m near
// the axis, for a model whose m is not in units of the focal length
// (FISHEYE_LENS_POLYNOMIAL's millimetres); 1 for the others.
template <class Model>
std::vector<double> fit_start(double radians_per_unit) {
    if constexpr (requires { Model::fit_start(radians_per_unit); }) {
        const auto start = Model::fit_start(radians_per_unit);
        return {start.begin(), start.end()};
    } else if constexpr (requires { Model::fit_start(); }) {
        const auto start = Model::fit_start();
        return {start.begin(), start.end()};
    } else {
        return std::vector<double>(static_cast<std::size_t>(std::max(0, Model::num_coefficients)), 0.0);
    }
}

// Calls visitor.template operator()<Model>() with the implementation of `type` in
// Scalar, e.g.  visit_lens_model<double>(lens.type, [&]<class Model>() { ... });
template <class Scalar, class Visitor>
decltype(auto) visit_lens_model(LensType type, Visitor&& visitor) {
    switch (type) {
#define LIBCAM_LENS_VISIT(id, model) \
    case LensType::id: return std::forward<Visitor>(visitor).template operator()<model<Scalar>>();
        LIBCAM_LENS_MODEL_LIST(LIBCAM_LENS_VISIT)
#undef LIBCAM_LENS_VISIT
    }
    throw InvalidArgument("lens: unknown model type #" + std::to_string(static_cast<int>(type)));
}

}  // namespace libcam
