#pragma once
// The inputs of the lens models' extremes and the 113-bit reference they are measured
// against, shared by the Camera path (test_extremes_lens.cpp) and the batch paths
// (test_extremes_methods.cpp): the same lenses, pixels and points, the same reference
// (libcam's model templates and solver run in Quad), the same scoring.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "extremes.hpp"
#include "lens_cases.hpp"
#include "libcam/lens/lens_models.hpp"
#include "reference.hpp"
#include "support.hpp"

namespace libcam::test {

// The models built on FISHEYE's equidistant point u = theta (X, Y) / |(X, Y)|: theta is
// their undistorted radius, and they share its handling of both axes.
inline bool on_equidistant_point(LensType type) {
    return type == LensType::Fisheye || type == LensType::ThinPrismFisheye || type == LensType::RadTanThinPrismFisheye ||
           type == LensType::ThetaPolynomial ||  // WoodScape's, built on the same point
           type == LensType::FThetaForward ||    // NVIDIA's F-theta with its forward polynomial
           type == LensType::EquidistantRadial;  // PanoTools' polynomial on it
}

// The radius PanoTools' polynomial takes on a fisheye projection (EQUIDISTANT_RADIAL,
// EQUISOLID_RADIAL, STEREOGRAPHIC_RADIAL: P(theta), their valid radius's unit); nullopt for
// the other models.
template <class Real>
std::optional<Real> fisheye_radial_radius(LensType type, Real rho, Real z) {
    using std::atan2, std::sin, std::tan;
    const Real theta = atan2(rho, z);
    if (type == LensType::EquidistantRadial) return theta;
    if (type == LensType::EquisolidRadial) return Real(2) * sin(theta / Real(2));
    if (type == LensType::StereographicRadial) return Real(2) * tan(theta / Real(2));
    return std::nullopt;
}


inline constexpr double kEpsDouble = std::numeric_limits<double>::epsilon();
inline constexpr double kEpsFloat = std::numeric_limits<float>::epsilon();
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// ------------------------------------------------------------ models in any scalar

template <class Scalar>
struct Unprojected {
    bool valid = false;
    Vec3T<Scalar> ray = Vec3T<Scalar>::Zero();
};

template <class Scalar>
struct Projected {
    bool valid = false;
    Vec2T<Scalar> m = Vec2T<Scalar>::Zero();
};

// Model<Scalar>::unproject of every normalised point (the domain worked out once).
template <class Scalar>
std::vector<Unprojected<Scalar>> unproject_all(const Lens& lens, const std::vector<Vec2T<Scalar>>& points) {
    return visit_lens_model<Scalar>(lens.type, [&]<class Model>() {
        const typename Model::Parameters parameters = Model::parameters(lens.coefficients);
        std::vector<Unprojected<Scalar>> out(points.size());
        for (std::size_t i = 0; i < points.size(); ++i)
            out[i].valid = Model::unproject(parameters, points[i], out[i].ray);
        return out;
    });
}

// Model<Scalar>::project of every camera point.
template <class Scalar>
std::vector<Projected<Scalar>> project_all(const Lens& lens, const std::vector<Vec3T<Scalar>>& points) {
    return visit_lens_model<Scalar>(lens.type, [&]<class Model>() {
        const typename Model::Parameters parameters = Model::parameters(lens.coefficients);
        std::vector<Projected<Scalar>> out(points.size());
        for (std::size_t i = 0; i < points.size(); ++i) out[i].valid = Model::project(parameters, points[i], out[i].m);
        return out;
    });
}

template <class To, class From, int N>
std::vector<Eigen::Matrix<To, N, 1>> cast_all(const std::vector<Eigen::Matrix<From, N, 1>>& values) {
    std::vector<Eigen::Matrix<To, N, 1>> out;
    out.reserve(values.size());
    for (const auto& v : values) out.push_back(v.template cast<To>());
    return out;
}

// K^-1 and K exactly (to 113 bits).
inline Vec2Q normalized_q(const Intrinsics& k, const Vec2& pixel) {
    const Quad y = (Quad(pixel.y()) - k.cy) / k.fy;
    return {(Quad(pixel.x()) - k.cx - Quad(k.skew) * y) / k.fx, y};
}

inline Vec2Q pixel_q(const Intrinsics& k, const Vec2Q& m) {
    return {Quad(k.fx) * m.x() + Quad(k.skew) * m.y() + k.cx, Quad(k.fy) * m.y() + k.cy};
}

inline std::string at_pixel(const std::string& name, const Vec2& pixel) {
    std::ostringstream out;
    out << name << " pixel (" << pixel.x() << ", " << pixel.y() << ")";
    return out.str();
}

// --------------------------------------------------------- unprojection errors

// d'(r) of a radial lens at the undistorted radius of `ray`, in Quad; 1 for the others.
inline Quad radial_slope(const Lens& lens, const Vec3Q& ray) {
    return visit_lens_model<Quad>(lens.type, [&]<class Model>() -> Quad {
        if constexpr (requires { Model::radial_distortion; }) {
            const typename Model::Parameters parameters = Model::parameters(lens.coefficients);
            // The radius the model's radial part takes: theta for FISHEYE, |q| = rho / (z + xi |p|)
            // in UCM's plane for MEI, rho / z for OpenCV's models.
            const Quad rho = hypot(ray.x(), ray.y());
            Quad r = rho / ray.z();
            if (on_equidistant_point(Model::type)) r = atan2(rho, ray.z());
            if (const auto radius = fisheye_radial_radius(Model::type, rho, ray.z())) r = *radius;
            if (Model::type == LensType::Mei) r = rho / (ray.z() + parameters.coefficients(0) * ray.norm());
            Quad slope;
            Model::radial_distortion(parameters, r, slope);
            return slope;
        } else {
            return Quad(1);
        }
    });
}

// The errors of the rays through a set of pixels, and what bounds them:
// - the angle, by the unprojection's own conditioning eps |m| / d'(r) (an error of eps
//   in m, through the lens's slope; d'(r) -> 0 at the fold): 8 times its largest;
// - where a ray lands, by the solver's stopping residual 64 eps (1 + |m|) in m times f:
//   in double the 1e-9 px target; in float 64 eps_f f (1 + |m|), its largest.
struct UnprojectionWorst {
    Worst rad_double, px_double, rad_float, px_float;
    double conditioning_double = 0, conditioning_float = 0, solver_px_float = 0;
    // Pixels compared, and those valid where the reference has no ray or flagged where
    // it has one: [0] double, [1] float.
    std::size_t pixels[2] = {0, 0};
    std::size_t wrong_flags[2] = {0, 0};
};

// eps |m| / d'(r) at the reference ray through m.
inline double conditioning(const Lens& lens, const Vec2Q& m, const Vec3Q& ray, double epsilon) {
    return static_cast<double>(Quad(epsilon) * m.norm() / radial_slope(lens, ray));
}

// m and d m / d point at a point, in 113-bit: one evaluation serves every measure of the
// lens's local behaviour below (and smallest_gain in test_extremes_methods.cpp).
struct LocalProjection {
    Vec2Q m;
    Eigen::Matrix<Quad, 2, 3> d_m_d_point;
};

// nullopt where the model does not project the point.
inline std::optional<LocalProjection> local_projection(const Lens& lens, const Vec3Q& point) {
    return visit_lens_model<Quad>(lens.type, [&]<class Model>() -> std::optional<LocalProjection> {
        LocalProjection local;
        if (!Model::project(Model::parameters(lens.coefficients), point, local.m, &local.d_m_d_point)) {
            return std::nullopt;
        }
        return local;
    });
}

// |dm/dp| |p| (elementwise absolute values): how far m moves when each coordinate of
// the point moves by its own relative error (one unit), in the units of m. The same at
// any scale of the point.
inline Vec2Q spread_of_m(const LocalProjection& local, const Vec3Q& point) {
    return local.d_m_d_point.cwiseAbs() * point.cwiseAbs();
}

// The projection's relative condition number at a point: by how much a relative error
// of eps in each coordinate grows in |m|, over the 2 of a plain ratio x / z; at least 1.
// No evaluation of a model in a type with epsilon eps can be expected to beat
// eps times it. It is near 1 for every model except where a denominator cancels (the
// unified models with an unbounded image near its edge, where m goes to infinity).
inline double projection_condition(const Lens& lens, const Vec3Q& point) {
    const std::optional<LocalProjection> local = local_projection(lens, point);
    if (!local) return 1.0;
    const Vec2Q spread = spread_of_m(*local, point);
    const Quad size = local->m.norm();
    if (!(size > 0) || !spread.allFinite()) return 1.0;
    return std::max(1.0, static_cast<double>(spread.norm() / (2 * size)));
}

// Whether a validity flag is wrong against the reference. A ray where the reference has
// none is still right when it lies in the model's domain and lands within the solver's
// tolerance, 64 eps (1 + |m|), of m: a pixel that close to the fold is the fold's pixel
// to the type's precision (in float that band is 1e-5 wide in m, wider than d_max 1e-6).
template <class Scalar>
bool wrong_flag(bool valid, bool reference_valid, const Projected<Quad>& landed, const Vec2Q& m) {
    if (valid == reference_valid) return false;
    if (!valid) return true;  // flagged though the reference has a ray
    const Quad tolerance = 64 * Quad(std::numeric_limits<Scalar>::epsilon()) * (1 + m.norm());
    return !(landed.valid && (landed.m - m).norm() <= tolerance);
}

// The image corners and edge centres (pixel edges and pixel centres) and the centre.
inline std::vector<Vec2> corner_pixels(const ImageSize& size) {
    const double w = static_cast<double>(size.width), h = static_cast<double>(size.height);
    std::vector<Vec2> pixels;
    for (double x : {-0.5, 0.0, (w - 1) / 2, w - 1, w - 0.5})
        for (double y : {-0.5, 0.0, (h - 1) / 2, h - 1, h - 0.5}) pixels.emplace_back(x, y);
    return pixels;
}

// The same camera on a sensor `scale` times as large (f, c and the size scaled):
// the same normalised points, at pixel coordinates up to 1e5.
inline Camera scaled_camera(Camera camera, double scale) {
    camera.size = {std::lround(static_cast<double>(camera.size.width) * scale),
                   std::lround(static_cast<double>(camera.size.height) * scale)};
    Intrinsics& k = camera.intrinsics;
    k = {k.fx * scale, k.fy * scale, (k.cx + 0.5) * scale - 0.5, (k.cy + 0.5) * scale - 0.5, k.skew * scale};
    return camera;
}


// Every model's lens (mild and strong) on a 100000-pixel-wide sensor.
inline std::vector<LensCase> large_image_cases() {
    std::vector<LensCase> cases;
    for (const LensCase& c : sanitized_subset(lens_cases()))
        cases.push_back({c.name, scaled_camera(c.camera, 100000.0 / static_cast<double>(c.camera.size.width))});
    return cases;
}

// ----------------------------------------------------------------- the fold-over radius

// Radial-only lenses whose fold is worked by hand (d(r) = r P(r^2) / Q(r^2); r_max where
// d'(r) = 0, d_max = d(r_max)), one per OpenCV model, BROWN_K4 and FISHEYE, in Quad from the
// coefficients as stored (doubles).
struct HandFold {
    std::string name;
    Camera camera;
    Quad r_max, d_max;
};

inline std::vector<HandFold> hand_folds() {
    using boost::multiprecision::pow;
    const auto lens = [](LensType type, std::vector<double> k) {
        return lens_camera(type, std::move(k), {1600, 1200}, 900, 900);
    };
    const Quad k_half(0.5), k_tenth(0.1), k_fifth(0.2), k_quarter(0.25);
    std::vector<HandFold> folds;
    // d = r - 0.5 r^3: d' = 1 - 1.5 r^2.
    const Quad r4 = sqrt(Quad(1) / (3 * k_half));
    folds.push_back({"OPENCV4 k1 = -0.5", lens(LensType::OpenCv4, {-0.5, 0, 0, 0}), r4, r4 * (1 - k_half * r4 * r4)});
    // d = r (1 - 0.1 r^6): d' = 1 - 0.7 r^6.
    const Quad r5 = pow(Quad(1) / (7 * k_tenth), Quad(1) / 6);
    folds.push_back(
        {"OPENCV5 k3 = -0.1", lens(LensType::OpenCv5, {0, 0, 0, 0, -0.1}), r5, r5 * (1 - k_tenth * pow(r5, 6))});
    // d = r / (1 + 0.5 r^2): d' = (1 - 0.5 r^2) / (1 + 0.5 r^2)^2.
    const Quad r8 = sqrt(Quad(1) / k_half);
    folds.push_back(
        {"OPENCV8 k4 = 0.5", lens(LensType::OpenCv8, {0, 0, 0, 0, 0, 0.5, 0, 0}), r8, r8 / (1 + k_half * r8 * r8)});
    // d = r (1 - 0.2 r^4): d' = 1 - r^4.
    const Quad r12 = pow(Quad(1) / (5 * k_fifth), Quad(1) / 4);
    folds.push_back({"OPENCV12 k2 = -0.2", lens(LensType::OpenCv12, {0, -0.2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}), r12,
                     r12 * (1 - k_fifth * pow(r12, 4))});
    // d = r / (1 + 0.25 r^6): d' = (1 - 1.25 r^6) / (1 + 0.25 r^6)^2.
    const Quad r14 = pow(Quad(1) / (5 * k_quarter), Quad(1) / 6);
    folds.push_back({"OPENCV14 k6 = 0.25", lens(LensType::OpenCv14, {0, 0, 0, 0, 0, 0, 0, 0.25, 0, 0, 0, 0, 0, 0}), r14,
                     r14 / (1 + k_quarter * pow(r14, 6))});
    // d = r (1 - 0.1 r^8): d' = 1 - 0.9 r^8.
    const Quad rb = pow(Quad(1) / (9 * k_tenth), Quad(1) / 8);
    folds.push_back({"BROWN_K4 k4 = -0.1", lens(LensType::BrownK4, {0, 0, 0, 0, 0, -0.1}), rb,
                     rb * (1 - k_tenth * pow(rb, 8))});
    // theta_d = theta (1 - 0.2 theta^2): theta_d' = 1 - 0.6 theta^2.
    const Quad rf = sqrt(Quad(1) / (3 * k_fifth));
    folds.push_back({"FISHEYE k1 = -0.2", lens(LensType::Fisheye, {-0.2, 0, 0, 0}), rf, rf * (1 - k_fifth * rf * rf)});
    // CAHVOR with its axis on z: tan(phi') = t (1 - 0.2 t^2), t = tan(phi) = |u|: the same
    // fold as FISHEYE's above, in t.
    folds.push_back({"CAHVOR r1 = -0.2", lens(LensType::Cahvor, {0, 0, 0, -0.2, 0}), rf, rf * (1 - k_fifth * rf * rf)});
    return folds;
}

// The pixel (rounded to double) at the distorted radius `radius` in direction phi.
inline Vec2 pixel_at_radius(const Camera& camera, const Quad& radius, double phi) {
    const Vec2Q m(radius * cos(Quad(phi)), radius * sin(Quad(phi)));
    return pixel_q(camera.intrinsics, m).cast<double>();
}

// Pixels at |m| = d_max (1 - delta) (inside) and d_max (1 + delta) (outside), 16
// directions. Inside: valid, landing within 1e-9 px; the angle is conditioned by the

// ------------------------------------------------------------------ projection errors

struct ProjectionWorst {
    Worst ulps_double, ulps_float;  // m against the reference, normwise ulps
    // [0] double, [1] float: points compared, and valid where the reference is not (or m
    // overflows) or flagged where the reference projects.
    std::size_t points[2] = {0, 0};
    std::size_t wrong_flags[2] = {0, 0};
};

// Whether the OpenCV formula, evaluated in Scalar, forms a number past Scalar's range
// for this camera point although m itself may fit: r^2 = (x/z)^2 + (y/z)^2, and r^4 for
// the thin prism and the tilt (OPENCV12, OPENCV14). libcam flags such points; in double
// they lie within ~1e-154 (r^2) or ~1e-77 (r^4) rad of the camera plane.
template <class Scalar>
bool intermediate_overflows(LensType type, const Vec3Q& point) {
    const bool opencv = type == LensType::OpenCv4 || type == LensType::OpenCv5 || type == LensType::OpenCv8 ||
                        type == LensType::OpenCv12 || type == LensType::OpenCv14;
    if (!opencv || !(point.z() > 0)) return false;
    const Quad r2 = (point.x() * point.x() + point.y() * point.y()) / (point.z() * point.z());
    const Quad largest(std::numeric_limits<Scalar>::max());
    const bool prism_or_tilt = type == LensType::OpenCv12 || type == LensType::OpenCv14;
    return r2 > largest || (prism_or_tilt && r2 * r2 > largest);
}

enum class Expect { Valid, Flagged, Either };

// Near the backward axis STEREOGRAPHIC forms |p| + z as rho^2 / (|p| - z), and FISHEYE
// and FOV (of (a x, a y, z), a = 2 tan(omega / 2)) the direction (x, y) / rho, from the
// point as given, or scaled to a largest coordinate in [1, 2) when that lies outside
// 2^(min exponent / 4) .. 2^(max exponent / 4) (camera/detail/point_scale.hpp): where rho^2 is
// no longer a normal number libcam flags the point. Flagged there, either within a
// factor 8 of the threshold, nullopt elsewhere (and for FISHEYE and FOV wherever their
// series on the forward axis applies, z > 0 and rho < 1e-3 z).
template <class Scalar>
std::optional<Expect> backward_axis_band(const Lens& lens, const Vec3Q& point) {
    const LensType type = lens.type;
    // DIVISION forms m = (x, y) / D with D = 2 k rho^2 / (z - root) behind the camera.
    const bool behind_only = type == LensType::Stereographic || type == LensType::Equisolid ||
                             type == LensType::StereographicRadial || type == LensType::EquisolidRadial ||
                             type == LensType::Division;
    if (!behind_only && !on_equidistant_point(type) && type != LensType::Fov) return std::nullopt;
    Quad rho2 = point.x() * point.x() + point.y() * point.y();
    if (type == LensType::Fov) {
        if (lens.coefficients.at(0) == 0) return std::nullopt;  // the pinhole
        rho2 *= 4 * tan(Quad(lens.coefficients[0]) / 2) * tan(Quad(lens.coefficients[0]) / 2);
    }
    if (behind_only ? !(point.z() < 0) : (point.z() > 0 && rho2 < Quad(1e-6) * point.z() * point.z())) {
        return std::nullopt;
    }
    using Limits = std::numeric_limits<Scalar>;
    const Quad largest = point.cwiseAbs().maxCoeff();
    const bool scaled = largest < ldexp(Quad(1), Limits::min_exponent / 4) || largest > ldexp(Quad(1), Limits::max_exponent / 4);
    rho2 /= scaled ? largest * largest : Quad(1);
    const Quad threshold(std::numeric_limits<Scalar>::min());
    if (rho2 < threshold / 8) return Expect::Flagged;
    if (rho2 < threshold * 8) return Expect::Either;
    return std::nullopt;
}

// The undistorted radius of a camera point in the units of the model's valid_radius
// (|(x/z, y/z)| for OpenCV's models, the angle theta for FISHEYE); 0 for the others.
inline Quad undistorted_radius(LensType type, const Vec3Q& point) {
    const Quad rho = hypot(point.x(), point.y());
    if (on_equidistant_point(type)) return atan2(rho, point.z());
    if (const auto radius = fisheye_radial_radius(type, rho, point.z())) return *radius;
    const bool opencv = type != LensType::Pinhole && lens_info(type).num_coefficients > 0;
    return opencv && point.z() > 0 ? rho / point.z() : Quad(0);
}

// Within 4 ulps of Scalar of the valid radius, the computed radius may land on either
// side: either answer is right there.
template <class Scalar>
bool at_domain_edge(const Lens& lens, const Vec3Q& point) {
    const double limit = valid_radius_of(lens);
    if (!std::isfinite(limit)) return false;
    return abs(undistorted_radius(lens.type, point) - limit) <= 4 * ulp_of<Scalar>(Quad(limit));
}


// The reference's answer for Scalar: valid when the reference projects the point, its m
// fits in Scalar (past the largest number it must be flagged, not returned as inf) and
// no intermediate overflows (above); either at the domain's edge.
template <class Scalar>
Expect expected(const Projected<Quad>& reference, const Lens& lens, const Vec3Q& point) {
    if (at_domain_edge<Scalar>(lens, point)) return Expect::Either;
    // FISHEYE_LENS_POLYNOMIAL measures its valid radius on the image: its edge is the
    // angle valid_angle (pi for Blender's default, the backward axis's neighbourhood),
    // which within a few ulps of Scalar may land on either side. FTHETA's likewise (the
    // angle where its polynomial reaches max_angle or folds).
    if (lens.type == LensType::LensPolynomial || lens.type == LensType::FTheta) {
        const Quad angle = atan2(hypot(point.x(), point.y()), point.z());
        const Quad edge(valid_angle_of(lens));
        if (abs(angle - edge) <= 8 * ulp_of<Scalar>(edge)) return Expect::Either;
    }
    if (const std::optional<Expect> near_axis = backward_axis_band<Scalar>(lens, point)) return *near_axis;
    const bool fits = reference.valid &&
                      reference.m.cwiseAbs().maxCoeff() <= Quad(std::numeric_limits<Scalar>::max()) &&
                      !intermediate_overflows<Scalar>(lens.type, point);
    return fits ? Expect::Valid : Expect::Flagged;
}

// One projection against the reference: a wrong flag is counted, a right value measured.
template <class Scalar, class Describe>
void compare(const Projected<Scalar>& computed, const Projected<Quad>& reference, Expect expect, int type_index,
             Worst& ulps_worst, ProjectionWorst& worst, Describe&& where) {
    ++worst.points[type_index];
    if ((expect == Expect::Flagged && computed.valid) || (expect == Expect::Valid && !computed.valid)) {
        ++worst.wrong_flags[type_index];
    }
    if (expect != Expect::Flagged && computed.valid && reference.valid)
        ulps_worst.update(ulps(computed.m, reference.m), where);
}


// A unit direction at angle theta from the optical axis (Quad, then rounded).
inline Vec3 direction_at(const Quad& theta, double phi) {
    return Vec3Q(sin(theta) * cos(Quad(phi)), sin(theta) * sin(Quad(phi)), cos(theta)).cast<double>();
}

inline const std::vector<LensCase>& fisheye_lenses() {
    static const std::vector<LensCase> lenses{
        {"FISHEYE equidistant", lens_camera(LensType::Fisheye, {0, 0, 0, 0}, {1600, 1200}, 300, 300)},
        {"FISHEYE mild", lens_camera(LensType::Fisheye, {-0.013, -0.0057, 0.0023, -0.0009}, {1600, 1200}, 420, 421)},
        {"FISHEYE strong", lens_camera(LensType::Fisheye, {0.08, -0.06, 0.012, -0.002}, {1600, 1200}, 300, 300)},
    };
    return lenses;
}

// FISHEYE at theta -> 0: theta / |(X, Y)| by its series below t = 1e-3 (no 0/0, no
// cancellation), down to theta = 1e-300; and the pixels next to the principal point.

// ------------------------------------------------------- z -> 0+, behind the camera

// Points (0.3, -0.2, z) for z = 1 down to 1e-320, 0, and behind (-1e-300 to -1).
inline std::vector<Vec3> points_towards_the_camera_plane() {
    std::vector<Vec3> points;
    for (int e = 0; e <= 320; e += 4) points.emplace_back(0.3, -0.2, std::pow(10.0, -e));
    for (double z : {0.0, -0.0, -1e-300, -1e-100, -1e-10, -0.5, -1.0}) points.emplace_back(0.3, -0.2, z);
    points.emplace_back(0, 0, -1);  // the backward axis: no direction for FISHEYE, STEREOGRAPHIC
    return points;
}

// Perspective models (PINHOLE, OPENCV*): valid only for z > 0 and inside the fold radius,
// accurate wherever valid. Models that see behind (FISHEYE, STEREOGRAPHIC, LONLAT, LATLON):
// valid on both sides, accurate.

// ---------------------------------------------------- strong and near-zero distortion

inline Camera with_coefficients_scaled(Camera camera, double scale) {
    for (double& k : camera.lens.coefficients) k *= scale;
    return camera;
}

inline std::vector<LensCase> coefficient_extremes() {
    std::vector<LensCase> cases;
    for (const LensCase& c : lens_cases()) {
        if (c.camera.lens.coefficients.empty() || c.name.find("mild") == std::string::npos) continue;
        for (double scale : {1e-8, 1e-100, 1e-300, 4.9e-324}) {
            std::ostringstream name;
            name << c.name << " x " << scale;
            cases.push_back({name.str(), with_coefficients_scaled(c.camera, scale)});
        }
    }
    cases.push_back({"OPENCV4 k = -2, 1.5", lens_camera(LensType::OpenCv4, {-2, 1.5, 0.01, -0.01})});
    cases.push_back(
        {"OPENCV8 k = 5, 3, .., 6, 4, 2", lens_camera(LensType::OpenCv8, {5, 3, 0.001, 0.001, 1, 6, 4, 2})});
    cases.push_back(
        {"OPENCV12 prism 0.1", lens_camera(LensType::OpenCv12, {0.1, 0, 0, 0, 0, 0, 0, 0, 0.1, -0.1, 0.05, 0.05})});
    cases.push_back(
        {"OPENCV14 tilt 0.3 rad", lens_camera(LensType::OpenCv14, {0.1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.3, -0.3})});
    cases.push_back({"FISHEYE k = 0.5, -0.3, 0.2, -0.05",
                     lens_camera(LensType::Fisheye, {0.5, -0.3, 0.2, -0.05}, {1600, 1200}, 300, 300)});
    return cases;
}


// ------------------------------------------------------------ points at any scale

// Unit directions (both sides of the camera, on and off the axis) at scales 4.9e-324 to
// 1.7e308: every model projects a direction, so the scale must not matter.
inline std::vector<Vec3> points_at_every_scale() {
    std::vector<Vec3> points;
    for (double scale : {4.9e-324, 1e-310, 1e-300, 1e-170, 1e-100, 1.0, 1e100, 1e170, 1e300, 1.7e308}) {
        for (const Vec3& d :
             {Vec3(1, 1, 1), Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(-1, 2, -3), Vec3(3, -2, 1e-20),
              Vec3(1e-20, 0, 1), Vec3(1e-20, 1e-20, -1), Vec3(0, 1, 0), Vec3(0.2, -0.1, 1)}) {
            points.push_back(d.normalized() * scale);
        }
    }
    return points;
}


// ------------------------------------------------------ the NaN / infinity sweep

// Everything at once: every model (mild, strong, near-zero, hand folds), points at every
// scale and side, pixels from the principal point to 1e300 px away, and the look-at cameras
// at their extremes. A result is either flagged (invalid, or an error thrown) or finite.
struct SweepCount {
    std::size_t results = 0, unflagged_non_finite = 0;
    std::string first;
    void add(bool valid, bool finite, const std::string& what) {
        ++results;
        if (valid && !finite) {
            if (unflagged_non_finite++ == 0) first = what;
        }
    }
};

inline std::vector<Vec3> sweep_points() {
    std::vector<Vec3> points = points_towards_the_camera_plane();
    for (const Vec3& p : points_at_every_scale()) points.push_back(p);
    const double inf = kInfinity, nan = std::numeric_limits<double>::quiet_NaN();
    for (const Vec3& p : {Vec3(inf, 0, 1), Vec3(0, 0, inf), Vec3(nan, 0, 1), Vec3(1, 1, -inf)}) points.push_back(p);
    return points;
}

inline std::vector<Vec2> sweep_pixels(const Camera& camera) {
    std::vector<Vec2> pixels = pixel_grid(camera.size, 21, 17);
    const Vec2 centre(camera.intrinsics.cx, camera.intrinsics.cy);
    pixels.push_back(centre);
    for (double distance : {1e-300, 1e-10, 1e4, 1e6, 1e15, 1e150, 1e300}) {
        for (double phi : {0.0, 1.0, 2.5, 4.0})
            pixels.push_back(centre + distance * Vec2(std::cos(phi), std::sin(phi)));
    }
    return pixels;
}

// Whether Camera::validate takes the camera. A real lens's coefficients behind a focal
// length of 4.4e-6 px put the pixel next to the principal point 2.3e5 focal lengths off the
// axis, far past the lens's domain: such a camera images nothing beyond its principal
// point, and libcam refuses it (camera.cpp says the rule) before any batch code sees it.
inline bool images_something(const Camera& camera) {
    try {
        camera.validate();
        return true;
    } catch (const InvalidArgument&) {
        return false;
    }
}

// The cameras of the sweeps; `refused` counts those Camera::validate refuses, left out.
inline std::vector<Camera> sweep_cameras(std::size_t* refused = nullptr) {
    std::vector<Camera> cameras;
    for (const LensCase& c : sanitized_subset(lens_cases())) cameras.push_back(c.camera);
    for (const LensCase& c : coefficient_extremes()) cameras.push_back(c.camera);
    for (const HandFold& fold : hand_folds()) cameras.push_back(fold.camera);
    for (const LensCase& c : fisheye_lenses()) cameras.push_back(c.camera);
    // Focal lengths far from the usual: a 179.999-degree and a 1e-6-degree camera's, on
    // the first camera of each model (each camera here builds the batch engine's table,
    // a tenth of a second; once per model covers every model's code).
    const std::size_t usual = cameras.size();
    std::vector<LensType> seen;
    for (std::size_t i = 0; i < usual; ++i) {
        if (std::find(seen.begin(), seen.end(), cameras[i].lens.type) != seen.end()) continue;
        seen.push_back(cameras[i].lens.type);
        for (double f : {4.4e-6, 5.7e12}) {
            Camera camera = cameras[i];
            camera.intrinsics.fx = camera.intrinsics.fy = f;
            cameras.push_back(camera);
        }
    }
    const auto kept_end = std::stable_partition(cameras.begin(), cameras.end(), images_something);
    if (refused) *refused = static_cast<std::size_t>(cameras.end() - kept_end);
    cameras.erase(kept_end, cameras.end());
    return cameras;
}

inline std::string describe_camera(const Camera& camera) {
    std::ostringstream out;
    out << lens_info(camera.lens.type).name << " fx " << camera.intrinsics.fx << " k0 "
        << (camera.lens.coefficients.empty() ? 0.0 : camera.lens.coefficients[0]);
    return out.str();
}

template <class Vector>
std::string show(const Vector& v) {
    std::ostringstream out;
    out << "(" << v.transpose() << ")";
    return out.str();
}

// Camera (double, public API) and Model<float>: project, unproject, rays.

}  // namespace libcam::test
