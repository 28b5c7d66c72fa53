// Issue 5, the lens models at the extremes, against the 113-bit reference: the same
// model templates (lens/*.hpp) and the same solver (undistort.hpp) run in Quad.
//
// Double goes through the public Camera API (K^-1 included); its reference starts from
// the exact pixel. Float goes through the model templates from the normalised point
// rounded to float; its reference starts from that same float point, so the float
// error is the model's and the solver's, not the rounding of the input.
//
// Only the `exact` unprojection exists on this branch; `fast` and `lut` need the same
// sweep once they land.

#include <catch2/catch.hpp>
#include <sstream>

#include "extremes.hpp"
#include "lens_cases.hpp"
#include "libcam/error.hpp"
#include "libcam/lens/lens_models.hpp"
#include "reference.hpp"
#include "support.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

constexpr double kEpsDouble = std::numeric_limits<double>::epsilon();
constexpr double kEpsFloat = std::numeric_limits<float>::epsilon();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

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
Vec2Q normalized_q(const Intrinsics& k, const Vec2& pixel) {
    const Quad y = (Quad(pixel.y()) - k.cy) / k.fy;
    return {(Quad(pixel.x()) - k.cx - Quad(k.skew) * y) / k.fx, y};
}

Vec2Q pixel_q(const Intrinsics& k, const Vec2Q& m) {
    return {Quad(k.fx) * m.x() + Quad(k.skew) * m.y() + k.cx, Quad(k.fy) * m.y() + k.cy};
}

std::string at_pixel(const std::string& name, const Vec2& pixel) {
    std::ostringstream out;
    out << name << " pixel (" << pixel.x() << ", " << pixel.y() << ")";
    return out.str();
}

// --------------------------------------------------------- unprojection errors

// d'(r) of a radial lens at the undistorted radius of `ray`, in Quad; 1 for the others.
Quad radial_slope(const Lens& lens, const Vec3Q& ray) {
    return visit_lens_model<Quad>(lens.type, [&]<class Model>() -> Quad {
        if constexpr (requires { Model::radial_distortion; }) {
            const typename Model::Parameters parameters = Model::parameters(lens.coefficients);
            const Quad rho = hypot(ray.x(), ray.y());
            const Quad r = Model::type == LensType::Fisheye ? atan2(rho, ray.z()) : rho / ray.z();
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
//   in double the target, 1e-9 px; in float 64 eps_f f (1 + |m|), its largest.
struct UnprojectionWorst {
    Worst rad_double, px_double, rad_float, px_float;
    double conditioning_double = 0, conditioning_float = 0, solver_px_float = 0;
    // Pixels compared, and those valid where the reference has no ray or flagged where
    // it has one: [0] double, [1] float.
    std::size_t pixels[2] = {0, 0};
    std::size_t wrong_flags[2] = {0, 0};
};

// eps |m| / d'(r) at the reference ray through m.
double conditioning(const Lens& lens, const Vec2Q& m, const Vec3Q& ray, double epsilon) {
    return static_cast<double>(Quad(epsilon) * m.norm() / radial_slope(lens, ray));
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

// Double, through Camera::unproject_pixels; the reference from the exact pixel. The
// pixel error is where the computed ray lands in the reference camera.
void unproject_double(const std::string& name, const Camera& camera, const std::vector<Vec2>& pixels,
                      UnprojectionWorst& worst) {
    const std::vector<Unprojection> rays = camera.unproject_pixels(pixels);
    std::vector<Vec2Q> normalized;
    for (const Vec2& pixel : pixels) normalized.push_back(normalized_q(camera.intrinsics, pixel));
    const std::vector<Unprojected<Quad>> reference = unproject_all<Quad>(camera.lens, normalized);
    std::vector<Vec3Q> computed;
    for (const Unprojection& ray : rays) computed.push_back(ray.direction.cast<Quad>());
    const std::vector<Projected<Quad>> landed = project_all<Quad>(camera.lens, computed);
    worst.pixels[0] += pixels.size();
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        const bool reference_valid = reference[i].valid && landed[i].valid;
        worst.wrong_flags[0] += wrong_flag<double>(rays[i].valid, reference_valid, landed[i], normalized[i]) ? 1 : 0;
        if (!rays[i].valid || !reference_valid) continue;
        const auto where = [&] { return at_pixel(name, pixels[i]); };
        worst.conditioning_double =
            std::max(worst.conditioning_double, conditioning(camera.lens, normalized[i], reference[i].ray, kEpsDouble));
        worst.rad_double.update(angle_error(rays[i].direction, reference[i].ray), where);
        worst.px_double.update(
            static_cast<double>((pixel_q(camera.intrinsics, landed[i].m) - pixels[i].cast<Quad>()).norm()), where);
    }
}

// Float, through Model<float>; the reference from the same float normalised point.
void unproject_float(const std::string& name, const Camera& camera, const std::vector<Vec2>& pixels,
                     UnprojectionWorst& worst) {
    std::vector<Vec2T<float>> normalized;
    for (const Vec2& pixel : pixels) normalized.push_back(camera.intrinsics.normalized_from_pixel(pixel).cast<float>());
    const std::vector<Unprojected<float>> rays = unproject_all<float>(camera.lens, normalized);
    const std::vector<Unprojected<Quad>> reference = unproject_all<Quad>(camera.lens, cast_all<Quad>(normalized));
    std::vector<Vec3Q> computed;
    for (const auto& ray : rays) computed.push_back(ray.ray.cast<Quad>());
    const std::vector<Projected<Quad>> landed = project_all<Quad>(camera.lens, computed);
    const Eigen::DiagonalMatrix<Quad, 2> focal(Quad(camera.intrinsics.fx), Quad(camera.intrinsics.fy));
    worst.pixels[1] += pixels.size();
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        const Vec2Q m_q = normalized[i].cast<Quad>();
        worst.wrong_flags[1] += wrong_flag<float>(rays[i].valid, reference[i].valid, landed[i], m_q) ? 1 : 0;
        if (!rays[i].valid || !reference[i].valid || !landed[i].valid) continue;
        const auto where = [&] { return at_pixel(name, pixels[i]); };
        const Vec2Q m = normalized[i].cast<Quad>();
        worst.conditioning_float =
            std::max(worst.conditioning_float, conditioning(camera.lens, m, reference[i].ray, kEpsFloat));
        const double f = std::max(camera.intrinsics.fx, camera.intrinsics.fy);
        worst.solver_px_float =
            std::max(worst.solver_px_float, 64 * kEpsFloat * f * (1 + static_cast<double>(m.norm())));
        worst.rad_float.update(angle_error(rays[i].ray, reference[i].ray), where);
        worst.px_float.update(static_cast<double>((focal * (landed[i].m - normalized[i].cast<Quad>())).norm()), where);
    }
}

void unproject_both(const std::string& name, const Camera& camera, const std::vector<Vec2>& pixels,
                    UnprojectionWorst& worst) {
    unproject_double(name, camera, pixels, worst);
    unproject_float(name, camera, pixels, worst);
}

// The unprojection rows of one extreme, with the bounds of UnprojectionWorst.
std::vector<Row> unprojection_rows(const std::string& extreme, const UnprojectionWorst& worst,
                                   const std::string& formulation) {
    return {
        {extreme, "unproject: ray vs reference [rad]", worst.rad_double.value, worst.rad_float.value,
         8 * worst.conditioning_double, 8 * worst.conditioning_float, formulation, worst.rad_double.where},
        {extreme, "unproject: where the ray lands [px]", worst.px_double.value, worst.px_float.value, 1e-9,
         worst.solver_px_float, formulation, worst.px_double.where},
        {extreme, "unproject: wrong flags [count of " + std::to_string(worst.pixels[0]) + "]",
         static_cast<double>(worst.wrong_flags[0]), static_cast<double>(worst.wrong_flags[1]), 0, 0,
         "valid only inside the fold radius with a converged residual, and finite", ""},
    };
}

// The image corners and edge centres (pixel edges and pixel centres) and the centre.
std::vector<Vec2> corner_pixels(const ImageSize& size) {
    const double w = static_cast<double>(size.width), h = static_cast<double>(size.height);
    std::vector<Vec2> pixels;
    for (double x : {-0.5, 0.0, (w - 1) / 2, w - 1, w - 0.5})
        for (double y : {-0.5, 0.0, (h - 1) / 2, h - 1, h - 0.5}) pixels.emplace_back(x, y);
    return pixels;
}

// The same camera on a sensor `scale` times as large (f, c and the size scaled):
// the same normalised points, at pixel coordinates up to 1e5.
Camera scaled_camera(Camera camera, double scale) {
    camera.size = {std::lround(static_cast<double>(camera.size.width) * scale),
                   std::lround(static_cast<double>(camera.size.height) * scale)};
    Intrinsics& k = camera.intrinsics;
    k = {k.fx * scale, k.fy * scale, (k.cx + 0.5) * scale - 0.5, (k.cy + 0.5) * scale - 0.5, k.skew * scale};
    return camera;
}

// ----------------------------------------------------------------- the extremes

// Every model's lens (mild and strong) on a 100000-pixel-wide sensor, at its corners.
std::vector<Row> large_image_rows() {
    UnprojectionWorst worst;
    for (const LensCase& c : lens_cases()) {
        const Camera camera = scaled_camera(c.camera, 100000.0 / static_cast<double>(c.camera.size.width));
        unproject_both(c.name, camera, corner_pixels(camera.size), worst);
    }
    return unprojection_rows("corners of a 100000-px-wide image, every model, mild and strong", worst,
                             "Newton from the radial 1-D root, bracketed; residual <= 64 eps (1 + |m|)");
}

// Issue 3's wide lens, a 151x101 grid with the corners (test_unproject checks 601x401
// against OpenCV; the 113-bit reference costs more).
std::vector<Row> wide_lens_rows() {
    UnprojectionWorst worst;
    const Camera camera = wide_reference_camera();
    unproject_both("wide lens", camera, pixel_grid(camera.size, 151, 101), worst);
    return unprojection_rows("the real wide lens (6016x4016 OPENCV8), 151x101 grid with the corners", worst,
                             "as above");
}

// ----------------------------------------------------------------- the fold-over radius

// Radial-only lenses whose fold is worked by hand (d(r) = r P(r^2) / Q(r^2); r_max where
// d'(r) = 0, d_max = d(r_max)), one per OpenCV model and FISHEYE, in Quad from the
// coefficients as stored (doubles).
struct HandFold {
    std::string name;
    Camera camera;
    Quad r_max, d_max;
};

std::vector<HandFold> hand_folds() {
    using boost::multiprecision::pow;
    const auto lens = [](LensType type, std::vector<double> k) {
        return lens_camera(type, std::move(k), {1600, 1200}, 900, 900);
    };
    const Quad k_half(0.5), k_tenth(0.1), k_fifth(0.2), k_quarter(0.25);
    std::vector<HandFold> folds;
    // d = r - 0.5 r^3: d' = 1 - 1.5 r^2.
    const Quad r4 = sqrt(Quad(1) / (3 * k_half));
    folds.push_back({"OPENCV4 k1 = -0.5", lens(LensType::Opencv4, {-0.5, 0, 0, 0}), r4, r4 * (1 - k_half * r4 * r4)});
    // d = r (1 - 0.1 r^6): d' = 1 - 0.7 r^6.
    const Quad r5 = pow(Quad(1) / (7 * k_tenth), Quad(1) / 6);
    folds.push_back(
        {"OPENCV5 k3 = -0.1", lens(LensType::Opencv5, {0, 0, 0, 0, -0.1}), r5, r5 * (1 - k_tenth * pow(r5, 6))});
    // d = r / (1 + 0.5 r^2): d' = (1 - 0.5 r^2) / (1 + 0.5 r^2)^2.
    const Quad r8 = sqrt(Quad(1) / k_half);
    folds.push_back(
        {"OPENCV8 k4 = 0.5", lens(LensType::Opencv8, {0, 0, 0, 0, 0, 0.5, 0, 0}), r8, r8 / (1 + k_half * r8 * r8)});
    // d = r (1 - 0.2 r^4): d' = 1 - r^4.
    const Quad r12 = pow(Quad(1) / (5 * k_fifth), Quad(1) / 4);
    folds.push_back({"OPENCV12 k2 = -0.2", lens(LensType::Opencv12, {0, -0.2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}), r12,
                     r12 * (1 - k_fifth * pow(r12, 4))});
    // d = r / (1 + 0.25 r^6): d' = (1 - 1.25 r^6) / (1 + 0.25 r^6)^2.
    const Quad r14 = pow(Quad(1) / (5 * k_quarter), Quad(1) / 6);
    folds.push_back({"OPENCV14 k6 = 0.25", lens(LensType::Opencv14, {0, 0, 0, 0, 0, 0, 0, 0.25, 0, 0, 0, 0, 0, 0}), r14,
                     r14 / (1 + k_quarter * pow(r14, 6))});
    // theta_d = theta (1 - 0.2 theta^2): theta_d' = 1 - 0.6 theta^2.
    const Quad rf = sqrt(Quad(1) / (3 * k_fifth));
    folds.push_back({"FISHEYE k1 = -0.2", lens(LensType::Fisheye, {-0.2, 0, 0, 0}), rf, rf * (1 - k_fifth * rf * rf)});
    return folds;
}

// The pixel (rounded to double) at the distorted radius `radius` in direction phi.
Vec2 pixel_at_radius(const Camera& camera, const Quad& radius, double phi) {
    const Vec2Q m(radius * cos(Quad(phi)), radius * sin(Quad(phi)));
    return pixel_q(camera.intrinsics, m).cast<double>();
}

// Pixels at |m| = d_max (1 - delta) (inside) and d_max (1 + delta) (outside), 16
// directions. Inside: valid, landing within 1e-9 px; the angle is conditioned by the
// lens's slope there, d'(r) -> 0 at the fold: a ray is right to ~eps |m| / d'(r).
std::vector<Row> fold_rows() {
    std::vector<Row> rows;
    Worst radius_ulps;
    for (const HandFold& fold : hand_folds()) {
        const double computed = visit_lens_model<double>(fold.camera.lens.type, [&]<class Model>() {
            return static_cast<double>(Model::parameters(fold.camera.lens.coefficients).valid_radius);
        });
        radius_ulps.update(ulps(computed, fold.r_max), [&] { return fold.name; });
    }
    rows.push_back({"fold-over radius, OPENCV4/5/8/12/14 and FISHEYE (by hand)", "valid_radius vs r_max [ulp]",
                    radius_ulps.value, kNotApplicable, 2, kNotApplicable,
                    "smallest positive root of d'(r)'s numerator: companion matrix, Newton-polished in long double",
                    radius_ulps.where});
    for (double delta : {1e-3, 1e-6, 1e-9}) {
        UnprojectionWorst inside;
        for (const HandFold& fold : hand_folds()) {
            std::vector<Vec2> in, out;
            for (int i = 0; i < 16; ++i) {
                const double phi = 2 * std::numbers::pi * i / 16 + 0.1;
                in.push_back(pixel_at_radius(fold.camera, fold.d_max * (1 - Quad(delta)), phi));
                out.push_back(pixel_at_radius(fold.camera, fold.d_max * (1 + Quad(delta)), phi));
            }
            unproject_both(fold.name, fold.camera, in, inside);
            unproject_both(fold.name, fold.camera, out, inside);  // no ray: flagged, by the reference too
        }
        std::ostringstream extreme;
        extreme << "fold radius: |m| = d_max (1 -+ " << delta << "), 6 lenses x 16 directions, inside and outside";
        const std::vector<Row> more =
            unprojection_rows(extreme.str(), inside, "the solver's bracket stops at valid_radius");
        rows.insert(rows.end(), more.begin(), more.end());
    }
    return rows;
}

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
    const bool opencv = type == LensType::Opencv4 || type == LensType::Opencv5 || type == LensType::Opencv8 ||
                        type == LensType::Opencv12 || type == LensType::Opencv14;
    if (!opencv || !(point.z() > 0)) return false;
    const Quad r2 = (point.x() * point.x() + point.y() * point.y()) / (point.z() * point.z());
    const Quad largest(std::numeric_limits<Scalar>::max());
    const bool prism_or_tilt = type == LensType::Opencv12 || type == LensType::Opencv14;
    return r2 > largest || (prism_or_tilt && r2 * r2 > largest);
}

// The undistorted radius of a camera point in the units of the model's valid_radius
// (|(x/z, y/z)| for OpenCV's models, the angle theta for FISHEYE); 0 for the others.
Quad undistorted_radius(LensType type, const Vec3Q& point) {
    const Quad rho = hypot(point.x(), point.y());
    if (type == LensType::Fisheye) return atan2(rho, point.z());
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

enum class Expect { Valid, Flagged, Either };

// The reference's answer for Scalar: valid when the reference projects the point, its m
// fits in Scalar (past the largest number it must be flagged, not returned as inf) and
// no intermediate overflows (above); either at the domain's edge.
template <class Scalar>
Expect expected(const Projected<Quad>& reference, const Lens& lens, const Vec3Q& point) {
    if (at_domain_edge<Scalar>(lens, point)) return Expect::Either;
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

// Double and float projection of camera points (the float points rounded from these).
void project_both(const Lens& lens, const std::vector<Vec3>& points, ProjectionWorst& worst, const std::string& name) {
    const std::vector<Projected<double>> in_double = project_all<double>(lens, points);
    const std::vector<Projected<Quad>> reference = project_all<Quad>(lens, cast_all<Quad>(points));
    const std::vector<Vec3T<float>> points_f = cast_all<float>(points);
    const std::vector<Projected<float>> in_float = project_all<float>(lens, points_f);
    const std::vector<Projected<Quad>> reference_f = project_all<Quad>(lens, cast_all<Quad>(points_f));
    for (std::size_t i = 0; i < points.size(); ++i) {
        const auto where = [&] {
            std::ostringstream out;
            out << name << " point (" << points[i].transpose() << ")";
            return out.str();
        };
        compare(in_double[i], reference[i], expected<double>(reference[i], lens, points[i].cast<Quad>()), 0,
                worst.ulps_double, worst, where);
        compare(in_float[i], reference_f[i], expected<float>(reference_f[i], lens, points_f[i].cast<Quad>()), 1,
                worst.ulps_float, worst, where);
    }
}

std::vector<Row> projection_rows(const std::string& extreme, const ProjectionWorst& worst, double ulps_double,
                                 double ulps_float, const std::string& formulation) {
    return {
        {extreme, "project: m vs reference [ulp]", worst.ulps_double.value, worst.ulps_float.value, ulps_double,
         ulps_float, formulation, worst.ulps_double.where},
        {extreme, "project: wrong flags [count of " + std::to_string(worst.points[0]) + "]",
         static_cast<double>(worst.wrong_flags[0]), static_cast<double>(worst.wrong_flags[1]), 0, 0,
         "valid only in the domain and if finite; an m or r^2 past the type's range is flagged", ""},
    };
}

// A unit direction at angle theta from the optical axis (Quad, then rounded).
Vec3 direction_at(const Quad& theta, double phi) {
    return Vec3Q(sin(theta) * cos(Quad(phi)), sin(theta) * sin(Quad(phi)), cos(theta)).cast<double>();
}

const std::vector<LensCase>& fisheye_lenses() {
    static const std::vector<LensCase> lenses{
        {"FISHEYE equidistant", lens_camera(LensType::Fisheye, {0, 0, 0, 0}, {1600, 1200}, 300, 300)},
        {"FISHEYE mild", lens_camera(LensType::Fisheye, {-0.013, -0.0057, 0.0023, -0.0009}, {1600, 1200}, 420, 421)},
        {"FISHEYE strong", lens_camera(LensType::Fisheye, {0.08, -0.06, 0.012, -0.002}, {1600, 1200}, 300, 300)},
    };
    return lenses;
}

// FISHEYE at theta -> 0: theta / |(X, Y)| by its series below t = 1e-3 (no 0/0, no
// cancellation), down to theta = 1e-300; and the pixels next to the principal point.
std::vector<Row> fisheye_axis_rows() {
    ProjectionWorst projected;
    UnprojectionWorst unprojected;
    for (const LensCase& c : fisheye_lenses()) {
        std::vector<Vec3> points;
        std::vector<Vec2> pixels;
        for (int e = 1; e <= 300; e += 1) {
            const double phi = 0.37 * e;
            points.push_back(direction_at(pow(Quad(10), -e), phi));
            if (e <= 30)
                pixels.push_back(c.camera.intrinsics.pixel_from_normalized(Vec2(Vec2::Zero())) +
                                 std::pow(10.0, -e) * Vec2(std::cos(phi), std::sin(phi)));
        }
        points.emplace_back(0, 0, 1);
        pixels.push_back(c.camera.intrinsics.pixel_from_normalized(Vec2(Vec2::Zero())));
        project_both(c.camera.lens, points, projected, c.name);
        unproject_both(c.name, c.camera, pixels, unprojected);
    }
    std::vector<Row> rows = projection_rows("FISHEYE theta = 1e-300 to 0.1 rad, and 0", projected, 4, 4,
                                            "theta / rho = atan(t)/t by its series for t < 1e-3");
    const std::vector<Row> more = unprojection_rows("FISHEYE 1e-30 to 0.1 px from the principal point", unprojected,
                                                    "sin(theta) / theta, theta = 0 on the axis exactly");
    rows.insert(rows.end(), more.begin(), more.end());
    return rows;
}

// FISHEYE near 90 and 180 degrees (theta = 90 -+ 1e-k deg, 180 - 1e-k deg): atan2, so
// no loss on either side of the camera plane; valid up to the lens's valid_radius (pi
// when theta_d does not fold before).
std::vector<Row> fisheye_wide_rows() {
    ProjectionWorst projected;
    UnprojectionWorst unprojected;
    const Quad pi = pi_in<Quad>();
    for (const LensCase& c : fisheye_lenses()) {
        std::vector<Vec3> points;
        for (int e = 1; e <= 15; ++e) {
            const Quad small = pow(Quad(10), -e);
            for (const Quad& theta : {pi / 2 - small, pi / 2 + small, pi - small})
                points.push_back(direction_at(theta, 0.3 * e));
        }
        points.emplace_back(1, 0, 0);
        points.emplace_back(0, -1e-300, -1);
        project_both(c.camera.lens, points, projected, c.name);
        // The pixels of the valid ones (by the reference), unprojected.
        std::vector<Vec2> pixels;
        const std::vector<Projected<Quad>> reference = project_all<Quad>(c.camera.lens, cast_all<Quad>(points));
        for (const Projected<Quad>& p : reference) {
            if (p.valid) pixels.push_back(pixel_q(c.camera.intrinsics, p.m).cast<double>());
        }
        unproject_both(c.name, c.camera, pixels, unprojected);
    }
    std::vector<Row> rows = projection_rows("FISHEYE theta = 90 -+ 1e-15..1e-1 rad and 180 - 1e-15..1e-1 rad",
                                            projected, 4, 4, "theta = atan2(rho, z)");
    const std::vector<Row> more =
        unprojection_rows("FISHEYE pixels of those rays", unprojected, "unit ray (sin(theta) u / theta, cos(theta))");
    rows.insert(rows.end(), more.begin(), more.end());
    return rows;
}

// ------------------------------------------------------- z -> 0+, behind the camera

// Points (0.3, -0.2, z) for z = 1 down to 1e-320, 0, and behind (-1e-300 to -1).
std::vector<Vec3> points_towards_the_camera_plane() {
    std::vector<Vec3> points;
    for (int e = 0; e <= 320; e += 4) points.emplace_back(0.3, -0.2, std::pow(10.0, -e));
    for (double z : {0.0, -0.0, -1e-300, -1e-100, -1e-10, -0.5, -1.0}) points.emplace_back(0.3, -0.2, z);
    points.emplace_back(0, 0, -1);  // the backward axis: no direction for FISHEYE, STEREOGRAPHIC
    return points;
}

// Perspective models (PINHOLE, OPENCV*): valid only for z > 0 and inside the fold radius,
// accurate wherever valid. Models that see behind (FISHEYE, STEREOGRAPHIC, LONLAT, LATLON):
// valid on both sides, accurate.
std::vector<Row> camera_plane_rows() {
    ProjectionWorst perspective, behind;
    std::size_t perspective_behind_valid = 0;
    for (const LensCase& c : lens_cases()) {
        const std::vector<Vec3> points = points_towards_the_camera_plane();
        project_both(c.camera.lens, points, lens_info(c.camera.lens.type).sees_behind_camera ? behind : perspective,
                     c.name);
        if (lens_info(c.camera.lens.type).sees_behind_camera) continue;
        for (std::size_t i = 0; i < points.size(); ++i) {
            if (points[i].z() > 0) continue;
            perspective_behind_valid += c.camera.project_camera_point(points[i]).valid ? 1 : 0;
        }
    }
    // 16 ulps: at r = |(x/z, y/z)| ~ 1e3..1e4 (z = 1e-4 here) the OpenCV model's own terms
    // (x R, p2 r^2, s2 r^4, the tilt's projection) cancel by up to ~10x: that is the
    // model's conditioning there, not the formula's; below r = 10 it is 4 ulps.
    std::vector<Row> rows =
        projection_rows("points at z = 1e-320 to 1, PINHOLE and OPENCV*", perspective, 16, 16,
                        "x / z (not x * (1/z)); R in 1/r^2 where P or Q overflows; no 0 * r^4 prism");
    rows.push_back({"points at z = 0 and behind, PINHOLE and OPENCV*", "project: valid [count]",
                    static_cast<double>(perspective_behind_valid), kNotApplicable, 0, kNotApplicable,
                    "z > 0 required (OpenCV takes z = 0 as 1 and mirrors z < 0)", ""});
    const std::vector<Row> more =
        projection_rows("points at z = +-1e-320 to +-1, FISHEYE, STEREOGRAPHIC, LONLAT, LATLON", behind, 4, 4,
                        "atan2; |p| + z as rho^2 / (|p| - z) for z < 0");
    rows.insert(rows.end(), more.begin(), more.end());
    return rows;
}

// ---------------------------------------------------- strong and near-zero distortion

Camera with_coefficients_scaled(Camera camera, double scale) {
    for (double& k : camera.lens.coefficients) k *= scale;
    return camera;
}

std::vector<LensCase> coefficient_extremes() {
    std::vector<LensCase> cases;
    for (const LensCase& c : lens_cases()) {
        if (c.camera.lens.coefficients.empty() || c.name.find("mild") == std::string::npos) continue;
        for (double scale : {1e-8, 1e-100, 1e-300, 4.9e-324}) {
            std::ostringstream name;
            name << c.name << " x " << scale;
            cases.push_back({name.str(), with_coefficients_scaled(c.camera, scale)});
        }
    }
    cases.push_back({"OPENCV4 k = -2, 1.5", lens_camera(LensType::Opencv4, {-2, 1.5, 0.01, -0.01})});
    cases.push_back(
        {"OPENCV8 k = 5, 3, .., 6, 4, 2", lens_camera(LensType::Opencv8, {5, 3, 0.001, 0.001, 1, 6, 4, 2})});
    cases.push_back(
        {"OPENCV12 prism 0.1", lens_camera(LensType::Opencv12, {0.1, 0, 0, 0, 0, 0, 0, 0, 0.1, -0.1, 0.05, 0.05})});
    cases.push_back(
        {"OPENCV14 tilt 0.3 rad", lens_camera(LensType::Opencv14, {0.1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.3, -0.3})});
    cases.push_back({"FISHEYE k = 0.5, -0.3, 0.2, -0.05",
                     lens_camera(LensType::Fisheye, {0.5, -0.3, 0.2, -0.05}, {1600, 1200}, 300, 300)});
    return cases;
}

std::vector<Row> coefficient_rows() {
    UnprojectionWorst worst;
    ProjectionWorst projected;
    for (const LensCase& c : coefficient_extremes()) {
        std::vector<Vec2> pixels = pixel_grid(c.camera.size, 21, 16);
        unproject_both(c.name, c.camera, pixels, worst);
        std::vector<Vec3> points;
        for (const Vec2& pixel : pixels)
            points.emplace_back(c.camera.intrinsics.normalized_from_pixel(pixel).x(),
                                c.camera.intrinsics.normalized_from_pixel(pixel).y(), 1.0);
        project_both(c.camera.lens, points, projected, c.name);
    }
    std::vector<Row> rows =
        unprojection_rows("coefficients x 1e-8 .. 4.9e-324 (mild lenses) and strong (k to 6, prism 0.1, tilt 0.3)",
                          worst, "Horner in r^2; the fold radius from the polynomial's roots");
    const std::vector<Row> more = projection_rows("the same lenses, 21x16 grids", projected, 8, 8, "Horner in r^2");
    rows.insert(rows.end(), more.begin(), more.end());
    return rows;
}

// ------------------------------------------------------------ points at any scale

// Unit directions (both sides of the camera, on and off the axis) at scales 4.9e-324 to
// 1.7e308: every model projects a direction, so the scale must not matter.
std::vector<Vec3> points_at_every_scale() {
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

// Through Camera::project_camera_points (double, pixels against K m of the reference).
std::vector<Row> scale_rows() {
    Worst px;
    std::size_t wrong_flags = 0, compared = 0;
    std::vector<LensCase> cases = lens_cases();
    for (const LensCase& c : fisheye_lenses()) cases.push_back(c);
    const std::vector<Vec3> points = points_at_every_scale();
    for (const LensCase& c : cases) {
        const std::vector<Projection> projections = c.camera.project_camera_points(points);
        const std::vector<Projected<Quad>> reference = project_all<Quad>(c.camera.lens, cast_all<Quad>(points));
        for (std::size_t i = 0; i < points.size(); ++i) {
            const Vec2Q expected_pixel = pixel_q(c.camera.intrinsics, reference[i].m);
            Expect expect = expected<double>(reference[i], c.camera.lens, points[i].cast<Quad>());
            if (expect == Expect::Valid &&
                expected_pixel.cwiseAbs().maxCoeff() > Quad(std::numeric_limits<double>::max())) {
                expect = Expect::Flagged;
            }
            ++compared;
            if ((expect == Expect::Flagged && projections[i].valid) ||
                (expect == Expect::Valid && !projections[i].valid)) {
                ++wrong_flags;
            }
            if (expect == Expect::Flagged || !projections[i].valid || !reference[i].valid) continue;
            px.update(ulps(projections[i].pixel, expected_pixel), [&] {
                std::ostringstream out;
                out << c.name << " point (" << points[i].transpose() << ")";
                return out.str();
            });
        }
    }
    const std::string extreme = "points at scales 4.9e-324 to 1.7e308, every model (Camera::project_camera_points)";
    return {
        {extreme, "pixel vs reference [ulp of |pixel|]", px.value, kNotApplicable, 16, kNotApplicable,
         "the point scaled by a power of two into [1, 2) first (exact)", px.where},
        {extreme, "wrong flags [count of " + std::to_string(compared) + "]", static_cast<double>(wrong_flags),
         kNotApplicable, 0, kNotApplicable, "a pixel past the largest double is flagged", ""},
    };
}

// ------------------------------------------------------ the NaN / infinity sweep

// Everything at once: every model (mild, strong, near-zero, hand folds), points at every
// scale and side, pixels from the principal point to 1e300 px away, and the FOV cameras
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

std::vector<Vec3> sweep_points() {
    std::vector<Vec3> points = points_towards_the_camera_plane();
    for (const Vec3& p : points_at_every_scale()) points.push_back(p);
    const double inf = kInfinity, nan = std::numeric_limits<double>::quiet_NaN();
    for (const Vec3& p : {Vec3(inf, 0, 1), Vec3(0, 0, inf), Vec3(nan, 0, 1), Vec3(1, 1, -inf)}) points.push_back(p);
    return points;
}

std::vector<Vec2> sweep_pixels(const Camera& camera) {
    std::vector<Vec2> pixels = pixel_grid(camera.size, 21, 17);
    const Vec2 centre(camera.intrinsics.cx, camera.intrinsics.cy);
    pixels.push_back(centre);
    for (double distance : {1e-300, 1e-10, 1e4, 1e6, 1e15, 1e150, 1e300}) {
        for (double phi : {0.0, 1.0, 2.5, 4.0})
            pixels.push_back(centre + distance * Vec2(std::cos(phi), std::sin(phi)));
    }
    return pixels;
}

std::vector<Camera> sweep_cameras() {
    std::vector<Camera> cameras;
    for (const LensCase& c : lens_cases()) cameras.push_back(c.camera);
    for (const LensCase& c : coefficient_extremes()) cameras.push_back(c.camera);
    for (const HandFold& fold : hand_folds()) cameras.push_back(fold.camera);
    for (const LensCase& c : fisheye_lenses()) cameras.push_back(c.camera);
    // Focal lengths far from the usual: a 179.999-degree and a 1e-6-degree camera's.
    const std::size_t usual = cameras.size();
    for (std::size_t i = 0; i < usual; ++i) {
        for (double f : {4.4e-6, 5.7e12}) {
            Camera camera = cameras[i];
            camera.intrinsics.fx = camera.intrinsics.fy = f;
            cameras.push_back(camera);
        }
    }
    return cameras;
}

std::string describe_camera(const Camera& camera) {
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
void sweep_lens(const Camera& camera, SweepCount& in_double, SweepCount& in_float) {
    const std::vector<Vec3> points = sweep_points();
    const std::vector<Projection> projections = camera.project_camera_points(points);
    for (std::size_t i = 0; i < points.size(); ++i) {
        in_double.add(projections[i].valid, projections[i].pixel.allFinite(),
                      describe_camera(camera) + " project " + show(points[i]));
    }
    const std::vector<Vec2> pixels = sweep_pixels(camera);
    const std::vector<Unprojection> rays = camera.unproject_pixels(pixels);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        const bool finite = rays[i].direction.allFinite() && !rays[i].direction.isZero(0.0);
        in_double.add(rays[i].valid, finite, describe_camera(camera) + " unproject " + show(pixels[i]));
        const Ray ray = camera.ray(pixels[i]);
        in_double.add(ray.valid, ray.direction.allFinite() && ray.origin.allFinite(),
                      describe_camera(camera) + " ray " + show(pixels[i]));
    }
    const std::vector<Projected<float>> projected_f = project_all<float>(camera.lens, cast_all<float>(points));
    for (std::size_t i = 0; i < points.size(); ++i) {
        in_float.add(projected_f[i].valid, projected_f[i].m.allFinite(),
                     "float " + describe_camera(camera) + " project " + show(points[i]));
    }
    std::vector<Vec2T<float>> normalized;
    for (const Vec2& pixel : pixels) normalized.push_back(camera.intrinsics.normalized_from_pixel(pixel).cast<float>());
    const std::vector<Unprojected<float>> rays_f = unproject_all<float>(camera.lens, normalized);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        in_float.add(rays_f[i].valid, rays_f[i].ray.allFinite(),
                     "float " + describe_camera(camera) + " unproject " + show(pixels[i]));
    }
}

// The FOV cameras at every extreme: to_camera either throws or gives finite K, R, t,
// and every probe ray is finite.
void sweep_fov(SweepCount& in_double) {
    rng().seed(17);
    for (double fov : {1e-6, 1e-3, 1.0, 90.0, 179.0, 179.999}) {
        for (const ImageSize size :
             {ImageSize{1, 1}, ImageSize{100000, 100000}, ImageSize{1, 10000}, ImageSize{100000, 10}}) {
            for (FovAxis axis : {FovAxis::Horizontal, FovAxis::Vertical, FovAxis::Diagonal, FovAxis::Both}) {
                for (double eye_scale : {0.0, 1e7, 1e300}) {
                    FovCamera fov_camera = random_fov_camera(size, axis);
                    fov_camera.fov_deg = fov;
                    fov_camera.eye = random_unit() * eye_scale;
                    Camera camera;
                    try {
                        camera = to_camera(fov_camera);
                    } catch (const Error&) {
                        in_double.add(false, false, "");
                        continue;
                    }
                    const bool finite =
                        camera.intrinsics.K().allFinite() && camera.pose.R.allFinite() && camera.pose.t.allFinite();
                    in_double.add(true, finite,
                                  "FOV camera fov " + std::to_string(fov) + " eye " + std::to_string(eye_scale));
                    for (const Vec2& pixel : corner_pixels(size)) {
                        const Ray ray = camera.ray(pixel);
                        in_double.add(ray.valid, ray.direction.allFinite() && ray.origin.allFinite(),
                                      "FOV camera ray " + show(pixel));
                        const Vec3 seed = fov_camera.seed_ray(pixel, PixelOrigin::TopLeft);
                        in_double.add(true, seed.allFinite(), "FOV seed ray " + show(pixel));
                    }
                }
            }
        }
    }
}

std::vector<Row> sweep_rows() {
    SweepCount in_double, in_float;
    for (const Camera& camera : sweep_cameras()) sweep_lens(camera, in_double, in_float);
    sweep_fov(in_double);
    const std::string extreme =
        "sweep: every model and extreme above, points at scales 5e-324 to 1.7e308, pixels to 1e300 px away, FOV "
        "cameras with eye to 1e300";
    return {{extreme,
             "valid but NaN or infinite [count of " + std::to_string(in_double.results) + " double, " +
                 std::to_string(in_float.results) + " float]",
             static_cast<double>(in_double.unflagged_non_finite), static_cast<double>(in_float.unflagged_non_finite), 0,
             0, "a result is valid only if finite", in_double.first + "; float: " + in_float.first}};
}

}  // namespace

TEST_CASE("extremes: lens corners of a 100000-pixel-wide image") { check_rows(large_image_rows()); }
TEST_CASE("extremes: the real wide lens") { check_rows(wide_lens_rows()); }
TEST_CASE("extremes: the fold-over radius of each OpenCV model and FISHEYE, just inside and just outside") {
    check_rows(fold_rows());
}
TEST_CASE("extremes: FISHEYE at theta -> 0") { check_rows(fisheye_axis_rows()); }
TEST_CASE("extremes: FISHEYE near 90 and 180 degrees") { check_rows(fisheye_wide_rows()); }
TEST_CASE("extremes: points at z -> 0+ and behind the camera") { check_rows(camera_plane_rows()); }
TEST_CASE("extremes: strong and near-zero distortion coefficients") { check_rows(coefficient_rows()); }
TEST_CASE("extremes: points at any scale") { check_rows(scale_rows()); }
TEST_CASE("extremes: nothing is NaN or infinite without the invalid flag") { check_rows(sweep_rows()); }

namespace libcam::test {

std::vector<Row> lens_rows() {
    std::vector<Row> rows;
    for (const auto& group : {large_image_rows, wide_lens_rows, fold_rows, fisheye_axis_rows, fisheye_wide_rows,
                              camera_plane_rows, coefficient_rows, scale_rows, sweep_rows}) {
        const std::vector<Row> more = group();
        rows.insert(rows.end(), more.begin(), more.end());
    }
    return rows;
}

}  // namespace libcam::test

TEST_CASE("extremes: OPENCV Jacobians where R = P/Q is evaluated in 1/r^2") {
    // At r = 1e60 P and Q overflow double, so R and its derivatives come from the 1/r^2
    // form; in Quad (range to 1e4932) the same point takes the plain form. Both agree.
    const Camera camera = lens_camera(LensType::Opencv8, {0.1, 0.02, 1e-4, -1e-4, 0.001, 0.12, 0.015, 0.0005});
    using Model = OpenCv8Lens<double>;
    using ModelQ = OpenCv8Lens<Quad>;
    const auto lens = Model::parameters(camera.lens.coefficients);
    const auto lens_q = ModelQ::parameters(camera.lens.coefficients);
    for (double z : {1e-40, 1e-60, 1e-100}) {
        const Vec3 point(0.3, -0.2, z);
        Vec2 m;
        Model::Jacobian23 d_point;
        Model::CoefficientJacobian d_coefficients;
        REQUIRE(Model::project(lens, point, m, &d_point, &d_coefficients));
        Vec2Q m_q;
        ModelQ::Jacobian23 d_point_q;
        ModelQ::CoefficientJacobian d_coefficients_q;
        REQUIRE(ModelQ::project(lens_q, point.cast<Quad>(), m_q, &d_point_q, &d_coefficients_q));
        INFO("z " << z);
        CHECK(ulps(m, m_q) <= 4);
        for (int row = 0; row < 2; ++row) {
            const Eigen::Matrix<double, 3, 1> d_point_row = d_point.row(row).transpose();
            CHECK(ulps(d_point_row, Eigen::Matrix<Quad, 3, 1>(d_point_q.row(row).transpose())) <= 4);
            const Eigen::Matrix<double, 8, 1> d_coefficients_row = d_coefficients.row(row).transpose();
            CHECK(ulps(d_coefficients_row, Eigen::Matrix<Quad, 8, 1>(d_coefficients_q.row(row).transpose())) <= 4);
        }
    }
}
