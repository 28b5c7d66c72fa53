// One generic harness for every lens model: the same checks run on every row of the model
// table (lens_models(), each row's implementation reached by visit_lens_model) with the
// example cameras of lens_harness_cases.hpp, so that a model added to the table is
// tested here with no new test code. For each model and example camera:
//   1. Jacobians (d m / d point, d m / d coefficients) against central differences in
//      long double;
//   2. round trips: point -> m -> ray (the model), pixel -> ray -> pixel (PreparedCamera);
//   3. the validity flag at the valid domain's edge (the fold-over radius, z <= 0,
//      behind the camera);
//   4. float against double (the model's projection, Unprojector's exact method);
//   5. the batch engine against the one-point calls, bit for bit, with 1 and 2 threads;
//   6. the table's row against its implementation.
// Expected values come from central differences in higher precision, formulas worked by
// hand and round trips, never from the code under test's own output for the same
// quantity.

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "lens_harness_cases.hpp"
#include "libcam/camera/projector.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/lens/lens_models.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

using Vec2L = Eigen::Matrix<long double, 2, 1>;
using Vec3L = Eigen::Matrix<long double, 3, 1>;

constexpr double kFloatEpsilon = std::numeric_limits<float>::epsilon();

// ---------------------------------------------------------------------------------
// Running a check on every model

// Calls check.template operator()<Model>(info, lens_case) for every example camera of
// every row of the table (Model: the row's implementation in double), each in a section
// naming the model and the camera.
template <class Check>
void for_each_model(Check&& check) {
    const std::vector<LensCase> cases = harness_cases();
    for (const LensInfo& info : lens_models()) {
        for (const LensCase& lens_case : cases) {
            if (lens_case.camera.lens.type != info.type) continue;
            DYNAMIC_SECTION(info.name << ": " << lens_case.name) {
                visit_lens_model<double>(info.type,
                                         [&]<class Model>() { check.template operator()<Model>(info, lens_case); });
            }
        }
    }
}

// One PreparedCamera per example camera, shared by the checks: the batch engine's table,
// built on its first unprojection, is most of this test's run time.
const PreparedCamera& prepared_camera(const LensCase& lens_case) {
    static std::map<std::string, PreparedCamera> cache;
    auto found = cache.find(lens_case.name);
    if (found == cache.end()) found = cache.emplace(lens_case.name, PreparedCamera(lens_case.camera)).first;
    if (!(found->second.camera().lens == lens_case.camera.lens)) FAIL("two example cameras named " << lens_case.name);
    return found->second;
}

// Random numbers from a generator of the caller's own, so that the points of one model
// are the same whichever sections run before.
double uniform_in(std::mt19937_64& generator, double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(generator);
}

template <class Vector>
std::string describe(const Vector& v) {
    std::ostringstream out;
    out.precision(17);
    out << "(";
    for (int i = 0; i < v.size(); ++i) out << (i > 0 ? ", " : "") << double(v(i));
    out << ")";
    return out.str();
}

// The largest value seen and where.
struct Worst {
    double value = 0;
    std::string where = "nowhere";

    void update(double candidate, const std::string& at) {
        if (!(candidate <= value)) {  // NaN counts as the worst
            value = candidate;
            where = at;
        }
    }
};

// Disagreements counted, the first described.
struct Mismatches {
    int count = 0;
    std::string first = "none";

    void add(const std::string& what) {
        if (count++ == 0) first = what;
    }
};

// ---------------------------------------------------------------------------------
// Points over a model's valid domain

Vec3 direction_at(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// Where the tests measure a domain's edge (domain_edge_of): in the angle theta from the
// optical axis for a model that sees behind the camera (FISHEYE), in the radius
// |(x/z, y/z)| of the pinhole-normalised point for one that does not (OpenCV's). The
// point at that radius and azimuth phi.
Vec3 point_at_radius(const LensInfo& info, double radius, double phi) {
    if (info.sees_behind_camera) return direction_at(radius, phi);
    return {radius * std::cos(phi), radius * std::sin(phi), 1.0};
}

// The largest angle from the optical axis sampled: 2 % inside the valid radius (where
// the fold-over nears, the inverse loses its conditioning), 10 degrees short of the
// backward axis (singular for FISHEYE and STEREOGRAPHIC), and for a perspective model
// at most |(x/z, y/z)| = 2.5 (68 degrees, about the widest example camera's corners).
double max_sample_angle(const LensInfo& info, double edge) {
    if (info.sees_behind_camera) return std::min(0.98 * edge, radians_from_degrees(170.0));
    return std::atan(std::min(0.98 * edge, 2.5));
}

// Within 2 degrees of the X or Y axis: LATLON's and LONLAT's singular axes.
bool near_x_or_y_axis(const Vec3& direction) {
    const double limit = std::cos(radians_from_degrees(2.0)) * direction.norm();
    return std::abs(direction.x()) > limit || std::abs(direction.y()) > limit;
}

// The optical axis, a direction 2e-5 rad off it (FISHEYE's series there), and `count`
// directions over the cap within max_angle of the axis (each axis_margin off it), uniform in solid angle (cos theta
// evenly spaced, azimuth by the golden angle); each at a random distance in [0.2, 50].
std::vector<Vec3> domain_points(double max_angle, int count, double axis_margin = 0.0) {
    std::vector<Vec3> directions{{0, 0, 1}, {1e-5, -2e-5, 1}};
    // Off the axis by axis_margin (lens_cases.hpp's axis_margin_of).
    const auto seen = [&](const Vec3& d) { return axis_margin == 0.0 || std::atan2(d.head<2>().norm(), d.z()) > axis_margin; };
    std::erase_if(directions, [&](const Vec3& d) { return !seen(d); });
    const double golden_angle = std::numbers::pi * (3 - std::sqrt(5.0));
    for (int i = 0; i < count; ++i) {
        const double cos_theta = 1 - (1 - std::cos(max_angle)) * (i + 0.5) / count;
        const Vec3 direction = direction_at(std::acos(cos_theta), golden_angle * i);
        if (!near_x_or_y_axis(direction) && seen(direction)) directions.push_back(direction);
    }
    std::mt19937_64 generator(20261121);
    std::vector<Vec3> points;
    for (const Vec3& direction : directions) points.push_back(direction.normalized() * uniform_in(generator, 0.2, 50.0));
    return points;
}

// Under the sanitizers a third: the same paths through each model (lens_cases.hpp).
const int kPointsPerCase = sweep_side(300);

std::vector<Vec3> sample_points(const LensInfo& info, const Camera& camera) {
    return domain_points(max_sample_angle(info, domain_edge_of(camera.lens)), kPointsPerCase, axis_margin_of(camera.lens));
}

// The angle between two directions, in long double (atan2 of the cross and dot
// products: accurate for tiny angles, where acos loses half the digits).
double angle_between_long(const Vec3& a, const Vec3& b) {
    const Vec3L al = a.cast<long double>(), bl = b.cast<long double>();
    return double(std::atan2(al.cross(bl).norm(), al.dot(bl)));
}

// A grid of nx by ny pixels reaching 10 % past every edge of the image (pixels without a
// ray under the strong lenses, and beyond the batch engine's table).
std::vector<Vec2> pixels_past_edges(const ImageSize& size, int nx, int ny) {
    std::vector<Vec2> pixels;
    for (const Vec2& p : pixel_grid(size, nx, ny)) {
        pixels.emplace_back(1.2 * p.x() - 0.1 * static_cast<double>(size.width),
                            1.2 * p.y() - 0.1 * static_cast<double>(size.height));
    }
    return pixels;
}

// ---------------------------------------------------------------------------------
// 1. Jacobians

// The step of the central differences in long double, times the coordinate's scale:
// eps^(1/5) balances the truncation error left by Richardson's extrapolation (h^4 |m^(5)|)
// against the rounding error (eps |m| / h), each then near eps^(4/5) = 6e-16 of the scale.
const long double kStep = std::pow(std::numeric_limits<long double>::epsilon(), 0.2L);

// The analytic Jacobians in double may differ from the central differences by this much,
// relative to the Jacobian's largest entry (for the coefficients: or |m|, the scale of
// the differences' rounding error, if larger). The differences err by ~6e-16 of the
// scale where m is smooth (above) and up to ~5e-13 close to a fold (OPENCV5 strong at
// 97 % of its fold radius, where the fifth derivative is large against the slope); the
// double Jacobians by a few roundings of their terms, ~1e-15. 1e-11 leaves a factor of
// 20 above the worst seen, and a missing or wrong term (a relative error of 1e-6 or more
// at some point) still fails by orders of magnitude.
constexpr double kJacobianTolerance = 1e-11;

template <class ModelLong>
Vec2L project_long(const typename ModelLong::Parameters& lens, const Vec3L& point) {
    Vec2L m = Vec2L::Zero();
    if (!ModelLong::project(lens, point, m)) FAIL("long double projection flagged " << describe(point));
    return m;
}

// The central difference of evaluate at x along coordinate j with the step h.
template <class Vector, class Evaluate>
Vec2L central_difference(const Vector& x, int j, long double h, Evaluate&& evaluate) {
    Vector plus = x, minus = x;
    plus(j) += h;
    minus(j) -= h;
    return (evaluate(plus) - evaluate(minus)) / (plus(j) - minus(j));  // the step actually taken
}

// Column j of the Jacobian of evaluate at x: central differences at the steps h and h / 2
// combined by Richardson's extrapolation, (4 D(h / 2) - D(h)) / 3, which cancels the h^2
// term of their truncation error. (Plain central differences leave ~1e-11 of the scale
// near a fold, where the third derivative is large against the slope.)
template <class Vector, class Evaluate>
Vec2L derivative(const Vector& x, int j, long double h, Evaluate&& evaluate) {
    return (4 * central_difference(x, j, h / 2, evaluate) - central_difference(x, j, h, evaluate)) / 3;
}

// max |analytic - numeric| / max(the analytic Jacobian's largest entry, floor).
template <class Analytic, class Numeric>
double relative_difference(const Analytic& analytic, const Numeric& numeric, double floor) {
    const long double difference = (numeric - analytic.template cast<long double>()).cwiseAbs().maxCoeff();
    const double scale = std::max({analytic.cwiseAbs().maxCoeff(), floor, std::numeric_limits<double>::min()});
    return double(difference) / scale;
}

// The scale of one coordinate (of the point or of the coefficients) for a central
// difference: its natural scale (|p| for the point; |k|, at least 1, for a coefficient),
// but no more than the change that moves m by max(1, |m|) at the analytic slope (used
// only to size the step). Where m varies fast (near LATLON's and LONLAT's singular
// axes, at 68 degrees through a perspective lens, a coefficient of a high power of r:
// k6 r^6 = 244 k6 at r = 2.5) it also curves fast, and the step must shrink as much for
// the truncation error to stay small.
template <class Column>
long double step_scale(long double natural, const Column& d_m_d_coordinate, const Vec2& m) {
    const long double speed = d_m_d_coordinate.cwiseAbs().maxCoeff() / std::max(1.0, m.cwiseAbs().maxCoeff());
    return speed * natural > 1 ? 1 / speed : natural;
}

struct JacobianErrors {
    Worst point, coefficients;
};

template <class Model>
JacobianErrors jacobian_errors(const Lens& lens, const std::vector<Vec3>& points) {
    using ModelLong = LensInScalar<Model, long double>;
    constexpr int N = Model::num_coefficients;  // Eigen::Dynamic for a variable count
    const auto parameters = Model::parameters(lens.coefficients);
    const auto parameters_long = ModelLong::parameters(lens.coefficients);
    const int n = static_cast<int>(parameters.coefficients.size());
    // The leading coefficients that configure the model (SPLINED_STEREOGRAPHIC's grid)
    // are not differentiated: their columns are zero.
    int configuration = 0;
    if constexpr (requires { Model::num_configuration_values; }) configuration = Model::num_configuration_values;
    JacobianErrors errors;
    for (const Vec3& point : points) {
        Vec2 m = Vec2::Zero();
        Eigen::Matrix<double, 2, 3> d_m_d_point;
        Eigen::Matrix<double, 2, N> d_m_d_coefficients;
        if (!Model::project(parameters, point, m, &d_m_d_point, &d_m_d_coefficients)) {
            FAIL("a point of the valid domain flagged: " << describe(point));
        }
        // PanoTools' c |u| u (PTLENS, the fisheye *_RADIAL models) is once, not twice,
        // differentiable on the axis, and its higher derivatives grow as 1 / |u| near it:
        // the differences' error there is c h, or c h^4 / |u|^3, not their usual size. Points
        // within 0.05 of the axis (in x/z) are left to the models' own tests of the
        // Jacobian's limit (tests/io/test_lensfun.cpp).
        if constexpr (panotools_polynomial(Model::type)) {
            if (std::hypot(point.x(), point.y()) < 0.05 * std::abs(point.z())) continue;
        }
        const Vec3L point_long = point.cast<long double>();
        const auto project_point = [&](const Vec3L& p) { return project_long<ModelLong>(parameters_long, p); };
        Eigen::Matrix<long double, 2, 3> numeric_point;
        for (int j = 0; j < 3; ++j) {
            const long double h = kStep * step_scale(point_long.norm(), d_m_d_point.col(j), m);
            numeric_point.col(j) = derivative(point_long, j, h, project_point);
        }
        errors.point.update(relative_difference(d_m_d_point, numeric_point, 0.0), describe(point));
        if constexpr (N != 0) {
            // The lens with perturbed coefficients, its domain worked out again as for a
            // camera with those coefficients (the valid radius bounds the models that solve
            // for their projection: FISHEYE_LENS_POLYNOMIAL's).
            const auto project_with = [&](const Eigen::Matrix<long double, N, 1>& coefficients) {
                std::vector<double> rounded(static_cast<std::size_t>(n));
                for (int i = 0; i < n; ++i) rounded[static_cast<std::size_t>(i)] = static_cast<double>(coefficients(i));
                auto perturbed = parameters_long;
                perturbed.coefficients = coefficients;
                perturbed.valid_radius = ModelLong::parameters(rounded).valid_radius;
                return project_long<ModelLong>(perturbed, point_long);
            };
            Eigen::Matrix<long double, 2, N> numeric_coefficients;
            numeric_coefficients.setZero(2, n);
            for (int j = configuration; j < n; ++j) {
                const long double natural = std::max(1.0L, std::abs(parameters_long.coefficients(j)));
                const long double h = kStep * step_scale(natural, d_m_d_coefficients.col(j), m);
                numeric_coefficients.col(j) = derivative(parameters_long.coefficients, j, h, project_with);
            }
            errors.coefficients.update(
                relative_difference(d_m_d_coefficients, numeric_coefficients, m.cwiseAbs().maxCoeff()), describe(point));
        }
    }
    return errors;
}

}  // namespace

TEST_CASE("harness: Jacobians match central differences in long double", "[sweep][harness]") {
    for_each_model([]<class Model>(const LensInfo& info, const LensCase& lens_case) {
        const JacobianErrors errors = jacobian_errors<Model>(lens_case.camera.lens, sample_points(info, lens_case.camera));
        INFO("worst d m / d point " << errors.point.value << " (bound " << kJacobianTolerance << ") at "
                                     << errors.point.where);
        CHECK(errors.point.value <= kJacobianTolerance);
        INFO("worst d m / d coefficients " << errors.coefficients.value << " at " << errors.coefficients.where);
        CHECK(errors.coefficients.value <= kJacobianTolerance);
    });
}

// ---------------------------------------------------------------------------------
// 2. Round trips

namespace {

// Point -> m -> ray: the ray's angle from the point, within 1e-12 rad. The solver
// accepts a residual of 64 eps (1 + |m|) in m (lens/undistort.hpp), 3e-14 for |m| ~ 1,
// and an error in m becomes an angle divided by the slope of the distortion, which 2 %
// inside a fold is still ~0.04 (OPENCV4 k1 = -0.5: d' = 1 - 1.5 (0.98 r_max)^2 = 0.04):
// below 1e-12 even at the tolerance. The closed-form inverses are a few roundings. (The
// worst seen is 3e-15 rad: the solver converges far below its tolerance.)
constexpr double kRoundTripAngle = 1e-12;
// Pixel -> ray -> pixel through PreparedCamera: the library's bound for `exact` (1e-9 px).
constexpr double kRoundTripPixels = 1e-9;

template <class Model>
void check_model_round_trip(const Lens& lens, const std::vector<Vec3>& points) {
    const auto parameters = Model::parameters(lens.coefficients);
    Worst worst;
    Mismatches no_ray;
    for (const Vec3& point : points) {
        Vec2 m = Vec2::Zero();
        Vec3 ray = Vec3::Zero();
        if (!Model::project(parameters, point, m)) FAIL("a point of the valid domain flagged: " << describe(point));
        if (!Model::unproject(parameters, m, ray)) {
            no_ray.add(describe(point) + " -> m " + describe(m));
            continue;
        }
        worst.update(angle_between_long(point, ray), describe(point));
    }
    INFO("no ray: " << no_ray.first);
    CHECK(no_ray.count == 0);
    INFO("worst angle " << worst.value << " rad (bound " << kRoundTripAngle << ") at " << worst.where);
    CHECK(worst.value <= kRoundTripAngle);
}

void check_pixel_round_trip(const PreparedCamera& camera) {
    const Intrinsics& k = camera.camera().intrinsics;
    // m = 0: every example lens is close to the identity there, so the pixel has a ray,
    // but for one whose centre pixel looks off the axis in no particular direction
    // (blind_angle > 0: FISHEYE_LENS_POLYNOMIAL with k0 != 0), which has none.
    REQUIRE(camera.unproject(Vec2(k.cx, k.cy)).valid == (camera.blind_angle() == 0.0));
    Worst worst;
    Mismatches not_reprojected;
    int with_ray = 0;
    for (const Vec2& pixel : pixel_grid(camera.camera().size, 41, 31)) {
        const Unprojection ray = camera.unproject(pixel);
        if (!ray.valid) continue;
        ++with_ray;
        const Projection back = camera.project_camera_point(ray.direction);
        if (!back.valid) {
            not_reprojected.add(describe(pixel) + " -> " + describe(ray.direction));
            continue;
        }
        worst.update((back.pixel - pixel).norm(), describe(pixel));
    }
    INFO(with_ray << " pixels of 41 x 31 with a ray; flagged on the way back: " << not_reprojected.first);
    CHECK(with_ray > 0);
    CHECK(not_reprojected.count == 0);
    INFO("worst " << worst.value << " px (bound " << kRoundTripPixels << ") at pixel " << worst.where);
    CHECK(worst.value <= kRoundTripPixels);
}

}  // namespace

TEST_CASE("harness: point -> m -> ray and pixel -> ray -> pixel come back", "[harness]") {
    for_each_model([]<class Model>(const LensInfo& info, const LensCase& lens_case) {
        check_model_round_trip<Model>(lens_case.camera.lens, sample_points(info, lens_case.camera));
        check_pixel_round_trip(prepared_camera(lens_case));
    });
}

// ---------------------------------------------------------------------------------
// 3. Validity at the domain's edge

namespace {

// Both paths that flag a point: the model itself and PreparedCamera.
template <class Model>
struct Flags {
    typename Model::Parameters parameters;
    const PreparedCamera& camera;

    bool model(const Vec3& point) const {
        Vec2 m = Vec2::Zero();
        return Model::project(parameters, point, m);
    }
    bool prepared(const Vec3& point) const { return camera.project_camera_point(point).valid; }
};

// Just inside the valid radius (1 - 1e-6 of it) valid, just outside (1 + 1e-6) not, at
// azimuths off the coordinate axes.
template <class Model, class EdgeAt>
void check_radius_edge(const LensInfo& info, const Flags<Model>& flags, const EdgeAt& edge_at) {
    for (int i = 0; i < 8; ++i) {
        const double phi = 0.3 + 2 * std::numbers::pi * i / 8;
        const double radius = edge_at(phi);
        const Vec3 inside = point_at_radius(info, radius * (1 - 1e-6), phi);
        const Vec3 outside = point_at_radius(info, radius * (1 + 1e-6), phi);
        INFO("azimuth " << phi << ", inside " << describe(inside) << ", outside " << describe(outside));
        CHECK(flags.model(inside));
        CHECK(flags.prepared(inside));
        CHECK_FALSE(flags.model(outside));
        CHECK_FALSE(flags.prepared(outside));
    }
}

// A perspective model has no image of a point on or behind the camera plane.
template <class Model>
void check_perspective_behind(const Flags<Model>& flags) {
    const Vec3 points[] = {{0.3, -0.2, 0.0}, {0.3, -0.2, -1.0}, {0.0, 0.0, -2.0}, {0.0, 0.0, 0.0}, {1e-3, 0.0, -1.0},
                           {5.0, 4.0, -1e-9}};
    for (const Vec3& point : points) {
        INFO(describe(point));
        CHECK_FALSE(flags.model(point));
        CHECK_FALSE(flags.prepared(point));
    }
}

// A model that sees behind the camera images a point behind it, midway between 90
// degrees and its valid radius, at an azimuth off every axis (not on a model's excluded
// axis); a lens folding over before 90 degrees does not.
template <class Model>
void check_sees_behind(const Flags<Model>& flags, double radius) {
    const double reach = std::min(radius, std::numbers::pi);
    const double theta = reach > std::numbers::pi / 2 ? (std::numbers::pi / 2 + reach) / 2 : 0.6 * std::numbers::pi;
    const Vec3 behind = 2.5 * direction_at(theta, 0.7);
    INFO("theta " << theta << " rad, valid radius " << radius << ": " << describe(behind));
    const bool expected = theta < radius;
    CHECK(flags.model(behind) == expected);
    CHECK(flags.prepared(behind) == expected);
}

}  // namespace

TEST_CASE("harness: the validity flag at the domain's edge, behind the camera and past the fold", "[harness]") {
    for_each_model([]<class Model>(const LensInfo& info, const LensCase& lens_case) {
        const PreparedCamera& camera = prepared_camera(lens_case);
        const Flags<Model> flags{Model::parameters(lens_case.camera.lens.coefficients), camera};
        const double radius = camera.valid_radius();
        CHECK(radius == double(flags.parameters.valid_radius));
        if (const auto by_hand = hand_worked_fold_radius(info, lens_case.camera.lens)) {
            INFO("fold-over radius by hand " << *by_hand);
            CHECK(std::abs(radius - *by_hand) <= 1e-14 * *by_hand);
        }
        const double edge = info.sees_behind_camera ? camera.valid_angle() : radius;
        // An angle at or past pi bounds nothing. The edge at each azimuth (a domain that is
        // not round about the axis: edge_angle_of).
        const bool bounded = info.sees_behind_camera ? edge < std::numbers::pi : std::isfinite(edge);
        const auto edge_at = [&](double phi) { return info.sees_behind_camera ? edge_angle_of(lens_case.camera.lens, phi) : edge; };
        INFO("valid radius " << radius << ", domain's edge " << edge);
        if (bounded) check_radius_edge(info, flags, edge_at);
        if (info.sees_behind_camera) {
            check_sees_behind(flags, edge_at(0.7));
        } else {
            check_perspective_behind(flags);
        }
    });
}

// ---------------------------------------------------------------------------------
// 4. float against double

namespace {

// The model in float against the model in double on the same point (the point rounded
// to float, then given to both, so that only the evaluation differs): within 16 eps_f of
// max(1, |m|). A model's m is a few dozen operations deep, each rounding by eps_f / 2 of
// an intermediate seldom larger than max(1, |m|), mostly cancelling, and the
// coefficients rounded to float move m by about as much again: a few eps_f (the worst
// seen is 2.7 eps_f, OPENCV14 mild at |(x/z, y/z)| = 2.5), and 16 leaves a factor of 6.
constexpr double kFloatProjection = 16 * kFloatEpsilon;

template <class Model>
void check_float_projection(const Lens& lens, const std::vector<Vec3>& points) {
    using ModelFloat = LensInScalar<Model, float>;
    const auto parameters = Model::parameters(lens.coefficients);
    const auto parameters_float = ModelFloat::parameters(lens.coefficients);
    Worst worst;
    Mismatches flagged;
    for (const Vec3& point : points) {
        const Eigen::Vector3f point_float = point.cast<float>();
        Vec2 m = Vec2::Zero();
        Eigen::Vector2f m_float = Eigen::Vector2f::Zero();
        if (!Model::project(parameters, point_float.cast<double>(), m)) {
            FAIL("a point of the valid domain flagged: " << describe(point_float));
        }
        if (!ModelFloat::project(parameters_float, point_float, m_float)) {
            flagged.add(describe(point_float));
            continue;
        }
        const double error = (m_float.cast<double>() - m).cwiseAbs().maxCoeff() / std::max(1.0, m.cwiseAbs().maxCoeff());
        worst.update(error, describe(point_float));
    }
    INFO("flagged in float only: " << flagged.first);
    CHECK(flagged.count == 0);
    INFO("worst " << worst.value / kFloatEpsilon << " eps_f (bound 16) at " << worst.where);
    CHECK(worst.value <= kFloatProjection);
}

// Unprojector<float> against Unprojector<double>, method exact, on the same pixels (each
// exactly a float): the same flags (both settle validity in double, unprojector.hpp), and
// rays that reproject (through PreparedCamera, in double) to pixels within
// 96 eps_f (1 + |m|) of each other, in units of m (the pixel distance over the larger
// focal length). The float solver certifies a residual of 64 eps_f (1 + |m|) as float
// evaluates it; float's evaluation of the model differs from double's by up to 16 eps_f
// (above), and rounding the pixel (K^-1) and the ray to float adds a few eps_f more (the
// worst seen is 1.3 eps_f (1 + |m|): the solver converges far below its tolerance).
// Compared where the solver certifies, in the image, not as angles: near a fold an angle
// is the residual over a slope that tends to 0.
constexpr double kFloatUnprojection = 96 * kFloatEpsilon;

void check_float_unprojector(const PreparedCamera& camera, const std::vector<Vec2>& grid) {
    const Unprojector<float> in_float(camera);
    const Unprojector<double>& in_double = camera.unprojector();
    const Points2<float> pixels_float = as_points2<float>(grid);
    Points2<double> pixels;
    pixels.x.assign(pixels_float.x.begin(), pixels_float.x.end());
    pixels.y.assign(pixels_float.y.begin(), pixels_float.y.end());
    Points3<float> rays_float;
    Points3<double> rays;
    ValidFlags valid_float, valid;
    in_float.unproject(pixels_float, UnprojectMethod::Exact, rays_float, valid_float);
    in_double.unproject(pixels, UnprojectMethod::Exact, rays, valid);

    const Intrinsics& k = camera.camera().intrinsics;
    const double focal = std::max(k.fx, k.fy);
    Mismatches flags;
    Worst worst;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        const Vec2 pixel(pixels.x[i], pixels.y[i]);
        if (valid_float[i] != valid[i]) flags.add(describe(pixel) + (valid[i] ? " valid in double" : " valid in float"));
        if (!valid[i] || !valid_float[i]) continue;
        const Vec3 ray(rays.x[i], rays.y[i], rays.z[i]);
        const Vec3 ray_float(double(rays_float.x[i]), double(rays_float.y[i]), double(rays_float.z[i]));
        const Projection back = camera.project_camera_point(ray), back_float = camera.project_camera_point(ray_float);
        if (!back.valid || !back_float.valid) {
            flags.add(describe(pixel) + ": a ray flagged on the way back");
            continue;
        }
        const double m_norm = k.normalized_from_pixel(pixel).norm();
        worst.update((back_float.pixel - back.pixel).norm() / focal / (1 + m_norm), describe(pixel));
    }
    INFO("flags differ at " << flags.first);
    CHECK(flags.count == 0);
    INFO("worst " << worst.value / kFloatEpsilon << " eps_f (1 + |m|) (bound 96) at pixel " << worst.where);
    CHECK(worst.value <= kFloatUnprojection);
}

}  // namespace

TEST_CASE("harness: float agrees with double within a multiple of float's epsilon", "[sweep][harness]") {
    for_each_model([]<class Model>(const LensInfo& info, const LensCase& lens_case) {
        check_float_projection<Model>(lens_case.camera.lens, sample_points(info, lens_case.camera));
        check_float_unprojector(prepared_camera(lens_case), pixels_past_edges(lens_case.camera.size, 41, 31));
    });
}

// ---------------------------------------------------------------------------------
// 5. The batch engine against the one-point calls, bit for bit

namespace {

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

template <class Vector>
bool same_bits(const Vector& a, const Vector& b) {
    for (int i = 0; i < a.size(); ++i) {
        if (!same_bits(a(i), b(i))) return false;
    }
    return true;
}

// Points over the domain, and some the batch path treats apart: outside the domain
// (behind the camera, on its plane, at the origin, on the coordinate axes, past the
// fold), at extreme scales (its second pass, camera/detail/point_scale.hpp), not finite.
std::vector<Vec3> batch_points(const LensInfo& info, const Camera& camera) {
    const std::vector<Vec3> inside = sample_points(info, camera);
    std::vector<Vec3> points = inside;
    const std::vector<Vec3> outside{{0.3, -0.2, 0.0}, {0.3, -0.2, -1.0}, {0, 0, -2}, {0, 0, 0}, {0, 1, 0},
                                    {1, 0, 0},        {1e-3, 0, -1},      {1e200, 0, 1e-200}};
    points.insert(points.end(), outside.begin(), outside.end());
    const double edge = domain_edge_of(camera.lens);
    if (info.sees_behind_camera ? edge < 0.99 * std::numbers::pi : std::isfinite(edge)) {
        points.push_back(point_at_radius(info, 1.01 * edge, 0.3));
    }
    for (std::size_t i = 0; i < inside.size(); i += 7) {
        for (double scale : {1e-300, 1e300, 4e-320}) points.push_back(inside[i] * scale);
    }
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    points.insert(points.end(), {{nan, 0, 1}, {0, 0, inf}, {inf, 1, 1}});
    return points;
}

struct ProjectedBatch {
    Points2<double> pixels;
    ValidFlags valid;
};

ProjectedBatch project_batch(const Projector<double>& projector, const Points3<double>& points, int threads) {
    ProjectedBatch out;
    projector.project(points, out.pixels, out.valid, threads);
    return out;
}

// Projector<double> (1 and 2 threads) and PreparedCamera::project_camera_points against
// PreparedCamera::project_camera_point, point by point.
void check_projector_bits(const PreparedCamera& camera, const std::vector<Vec3>& points) {
    const Projector<double> projector(camera);
    const Points3<double> batch = as_points3<double>(points);
    const ProjectedBatch one_thread = project_batch(projector, batch, 1), two_threads = project_batch(projector, batch, 2);
    const std::vector<Projection> list = camera.project_camera_points(points);
    Mismatches mismatches;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Projection single = camera.project_camera_point(points[i]);
        const auto compare = [&](const char* path, const Vec2& pixel, bool valid) {
            if (valid == single.valid && same_bits(pixel, single.pixel)) return;
            mismatches.add(std::string(path) + " at " + describe(points[i]) + ": " + describe(pixel) +
                           (valid ? " valid" : " invalid") + ", project_camera_point " + describe(single.pixel) +
                           (single.valid ? " valid" : " invalid"));
        };
        compare("Projector, 1 thread", Vec2(one_thread.pixels.x[i], one_thread.pixels.y[i]), one_thread.valid[i] != 0);
        compare("Projector, 2 threads", Vec2(two_threads.pixels.x[i], two_threads.pixels.y[i]), two_threads.valid[i] != 0);
        compare("project_camera_points", list[i].pixel, list[i].valid);
    }
    INFO(points.size() << " points; first mismatch: " << mismatches.first);
    CHECK(mismatches.count == 0);
}

struct UnprojectedBatch {
    Points3<double> rays;
    ValidFlags valid;
};

UnprojectedBatch unproject_batch(const Unprojector<double>& unprojector, const Points2<double>& pixels,
                                 UnprojectMethod method, int threads) {
    UnprojectedBatch out;
    unprojector.unproject(pixels, method, out.rays, out.valid, threads);
    return out;
}

// One answer against the one-pixel call's: the same flag, and where valid the same ray
// (the one-pixel call leaves its output alone where invalid; the batch writes 0).
void compare_ray(Mismatches& mismatches, const std::string& path, const Vec2& pixel, const Vec3& ray, bool valid,
                 const Vec3& single_ray, bool single_valid) {
    const bool same = valid == single_valid && same_bits(ray, valid ? single_ray : Vec3::Zero().eval());
    if (same) return;
    mismatches.add(path + " at pixel " + describe(pixel) + ": " + describe(ray) + (valid ? " valid" : " invalid") +
                   ", one pixel " + describe(single_ray) + (single_valid ? " valid" : " invalid"));
}

// Unprojector<double>::unproject on a batch (each method, 1 and 2 threads) against its
// one-pixel call, and PreparedCamera::unproject on a list (1 and 2 threads) against its
// one-pixel call.
void check_unprojector_bits(const PreparedCamera& camera, const std::vector<Vec2>& grid) {
    const Unprojector<double>& unprojector = camera.unprojector();
    const Points2<double> pixels = as_points2<double>(grid);
    Mismatches mismatches;
    for (UnprojectMethod method : kUnprojectMethods) {
        const UnprojectedBatch one_thread = unproject_batch(unprojector, pixels, method, 1);
        const UnprojectedBatch two_threads = unproject_batch(unprojector, pixels, method, 2);
        const std::string name(method_name(method));
        for (std::size_t i = 0; i < grid.size(); ++i) {
            Vec3 single = Vec3::Zero();
            const bool single_valid = unprojector.unproject(grid[i], method, single);
            for (const auto* batch : {&one_thread, &two_threads}) {
                const Vec3 ray(batch->rays.x[i], batch->rays.y[i], batch->rays.z[i]);
                compare_ray(mismatches, name + (batch == &one_thread ? ", 1 thread" : ", 2 threads"), grid[i], ray,
                            batch->valid[i] != 0, single, single_valid);
            }
        }
    }
    for (int threads : {1, 2}) {
        const std::vector<Unprojection> list = camera.unproject(grid, threads);
        for (std::size_t i = 0; i < grid.size(); ++i) {
            const Unprojection single = camera.unproject(grid[i]);
            compare_ray(mismatches, "PreparedCamera list, " + std::to_string(threads) + " thread(s)", grid[i],
                        list[i].direction, list[i].valid, single.direction, single.valid);
        }
    }
    INFO(grid.size() << " pixels; first mismatch: " << mismatches.first);
    CHECK(mismatches.count == 0);
}

// The grid past the edges, random pixels in the image, the principal point, and pixels
// far outside.
std::vector<Vec2> batch_pixels(const Camera& camera) {
    std::vector<Vec2> pixels = pixels_past_edges(camera.size, 33, 25);
    std::mt19937_64 generator(20261122);
    for (int i = 0; i < 40; ++i) {
        pixels.emplace_back(uniform_in(generator, -0.5, double(camera.size.width) - 0.5),
                            uniform_in(generator, -0.5, double(camera.size.height) - 0.5));
    }
    pixels.emplace_back(camera.intrinsics.cx, camera.intrinsics.cy);
    pixels.emplace_back(-1e6, 3e6);
    pixels.emplace_back(1e300, -1e300);
    return pixels;
}

}  // namespace

TEST_CASE("harness: the batch engine gives the one-point calls' bits, with 1 and 2 threads", "[harness][engine]") {
    for_each_model([]<class Model>(const LensInfo& info, const LensCase& lens_case) {
        const PreparedCamera& camera = prepared_camera(lens_case);
        check_projector_bits(camera, batch_points(info, lens_case.camera));
        check_unprojector_bits(camera, batch_pixels(lens_case.camera));
    });
}

// ---------------------------------------------------------------------------------
// 6. The table

TEST_CASE("harness: every row of the model table matches its implementation and has example cameras", "[harness]") {
    const std::vector<LensCase> cases = harness_cases();
    std::set<std::string> case_names;
    for (const LensCase& lens_case : cases) CHECK(case_names.insert(lens_case.name).second);  // names the sections
    for (const LensInfo& info : lens_models()) {
        INFO(info.name);
        const std::span<const std::string_view> names = info.coefficients.view();
        // A variable count's row names the configuration values that lead it.
        if (info.num_coefficients != kVariableCoefficientCount) {
            CHECK(names.size() == static_cast<std::size_t>(info.num_coefficients));
        }
        CHECK(std::set<std::string_view>(names.begin(), names.end()).size() == names.size());
        visit_lens_model<double>(info.type, [&]<class Model>() {
            CHECK(Model::type == info.type);
            CHECK(Model::num_coefficients == info.num_coefficients);
            // Solved exactly for the models the iterative solver unprojects.
            CHECK(SolvedLensModel<Model> == (info.inverse == Inverse::Solved));
        });
        // A row without an example camera would pass every check above untested; a model
        // that sees behind the camera needs a camera whose domain reaches past 90 degrees.
        int examples = 0, seeing_behind = 0;
        for (const LensCase& lens_case : cases) {
            if (lens_case.camera.lens.type != info.type) continue;
            ++examples;
            seeing_behind += valid_angle_of(lens_case.camera.lens) > std::numbers::pi / 2 ? 1 : 0;
        }
        CHECK(examples > 0);
        if (info.sees_behind_camera) CHECK(seeing_behind > 0);
    }
}
