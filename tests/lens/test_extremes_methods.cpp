// The batch paths at the extremes: Unprojector's exact, fast and lut methods
// and the batch Projector, in double and in float, at the extremes the public path is
// measured at (test_extremes_lens.cpp), against the same 113-bit reference.
//
// A batch takes its input in its own scalar type: a float batch gets the pixels (or
// points) rounded to float, and the reference starts from those same values with the
// camera's double K, so the error is the batch path's own, K^-1 (or K) in float
// included.
//
// The bounds, per pixel, with f the larger focal length, c the larger of |cx|, |cy| and
// p the larger pixel coordinate:
// - where the ray lands [px], less what rounding the exact ray to the scalar type moves
//   its pixel (4 eps f | |d m / d ray| |ray| |; negligible except where the projection is
//   ill-conditioned, as near the edge of a unified model's unbounded image):
//   exact in double, the 1e-9 px target; exact in float, the
//   solver's residual 64 eps f (1 + |m|) plus K^-1 in float, 4 eps (p + c); fast and
//   lut, the 0.01 px they are held to (their cells are checked to 0.005 px,
//   UnprojectorOptions) plus the same two terms in their scalar type;
// - the ray's angle [rad]: that landing bound through the lens's local inverse, a
//   pixel error e moves the ray by at most e / (f sigma), sigma the smallest singular
//   value of d m / d ray across the ray (-> 0 at a fold): twice that.
// - SPLINED_STEREOGRAPHIC: less 4 eps f |u| besides, u the stereographic point, where m =
//   u + delta(u) cancels (below).

#include <catch2/catch.hpp>
#include <cstdint>
#include <sstream>

#include "extremes_lens.hpp"
#include "libcam/camera/projector.hpp"
#include "libcam/camera/unprojector.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

constexpr double kApproximationPx = 0.01;  // fast and lut: as in test_unprojector.cpp
constexpr double kExactPx = 1e-9;          // exact in double: the 1e-9 px target

template <class Scalar>
constexpr int type_index = std::is_same_v<Scalar, float> ? 1 : 0;

// ------------------------------------------------------------ the lens's local gain

// The smallest singular value of d m / d ray across the unit ray (in its tangent
// plane), from the lens's local projection there: a change of angle a moves m by at
// least sigma a.
Quad smallest_gain(const LocalProjection& local, const Vec3Q& unit_ray) {
    // An orthonormal basis of the plane across the ray, from the axis least aligned with it.
    Eigen::Index axis = 0;
    unit_ray.cwiseAbs().minCoeff(&axis);
    const Vec3Q first = unit_ray.cross(Vec3Q::Unit(axis)).normalized();
    Eigen::Matrix<Quad, 3, 2> across;
    across << first, unit_ray.cross(first);
    const Eigen::Matrix<Quad, 2, 2> a = local.d_m_d_point * across;
    // sigma_min^2 = 2 det^2 / (F + sqrt(F^2 - 4 det^2)), F the squared Frobenius norm:
    // the smaller root of sigma^4 - F sigma^2 + det^2, without cancellation.
    const Quad det = a.determinant(), frobenius = a.squaredNorm();
    const Quad discriminant = frobenius * frobenius - 4 * det * det;
    return sqrt(2 * det * det / (frobenius + sqrt(discriminant > 0 ? discriminant : Quad(0))));
}

// ---------------------------------------------------------------- unprojection

struct MethodWorst {
    // [type index]: 0 double, 1 float.
    Worst rad[2], px[2];
    double rad_bound[2] = {0, 0}, px_bound[2] = {0, 0};
    std::size_t pixels[2] = {0, 0}, wrong_flags[2] = {0, 0};
};

// One extreme: the worst per method.
struct ExtremeWorst {
    MethodWorst of[3];  // indexed like kUnprojectMethods
    MethodWorst& operator[](UnprojectMethod method) { return of[static_cast<int>(method)]; }
};

// The landing bound at one pixel for `method` in Scalar (see the top of the file).
template <class Scalar>
double landing_bound(UnprojectMethod method, const Camera& camera, const Vec2& pixel, const Vec2Q& m) {
    const double eps = std::numeric_limits<Scalar>::epsilon();
    const Intrinsics& k = camera.intrinsics;
    const double f = std::max(k.fx, k.fy);
    const double rounding = 64 * eps * f * (1 + static_cast<double>(m.norm())) +
                            4 * eps * (pixel.cwiseAbs().maxCoeff() + std::max(std::abs(k.cx), std::abs(k.cy)));
    if (method != UnprojectMethod::Exact) return kApproximationPx + rounding;
    return std::is_same_v<Scalar, double> ? kExactPx : rounding;
}

// The rays of `pixels` (already Scalar values) by `method`, scored against the reference.
template <class Scalar>
void score_method(const std::string& name, const Unprojector<Scalar>& unprojector, UnprojectMethod method,
                  const std::vector<Vec2>& pixels, MethodWorst& worst) {
    const Camera& camera = unprojector.camera();
    Points3<Scalar> directions;
    ValidFlags valid;
    unprojector.unproject(as_points2<Scalar>(pixels), method, directions, valid);
    std::vector<Vec2Q> normalized;
    std::vector<Vec3Q> computed;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        normalized.push_back(normalized_q(camera.intrinsics, pixels[i]));
        computed.emplace_back(Quad(directions.x[i]), Quad(directions.y[i]), Quad(directions.z[i]));
    }
    const std::vector<Unprojected<Quad>> reference = unproject_all<Quad>(camera.lens, normalized);
    const std::vector<Projected<Quad>> landed = project_all<Quad>(camera.lens, computed);
    const double f_min = std::min(camera.intrinsics.fx, camera.intrinsics.fy);
    const double f_max = std::max(camera.intrinsics.fx, camera.intrinsics.fy);
    constexpr int t = type_index<Scalar>;
    worst.pixels[t] += pixels.size();
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        const bool reference_valid = reference[i].valid && landed[i].valid;
        worst.wrong_flags[t] += wrong_flag<Scalar>(valid[i] != 0, reference[i].valid, landed[i], normalized[i]) ? 1 : 0;
        if (!valid[i] || !reference_valid) continue;
        const auto where = [&] { return at_pixel(name + " " + std::string(method_name(method)), pixels[i]); };
        const double px_bound = landing_bound<Scalar>(method, camera, pixels[i], normalized[i]);
        worst.px_bound[t] = std::max(worst.px_bound[t], px_bound);
        // The lens at the reference ray: zero gain where the model does not project it.
        const Vec3Q unit_ray = reference[i].ray.normalized();
        const std::optional<LocalProjection> local = local_projection(camera.lens, unit_ray);
        // No ray in Scalar lands closer than rounding it moves its pixel: near the edge of a
        // unified model's unbounded image that is far more than the target, elsewhere nothing.
        const Quad ray_rounding_px =
            local ? 4 * Quad(std::numeric_limits<Scalar>::epsilon()) * Quad(f_max) * spread_of_m(*local, unit_ray).norm()
                  : Quad(0);
        // SPLINED_STEREOGRAPHIC forms m as the stereographic point u plus the spline's
        // correction delta(u), as mrcal defines it: where the two nearly cancel (around the
        // principal point of a spline with delta(0) != 0, at a focal length that makes the
        // image |m| < 1e-8 wide) the sum rounds by eps |u| however the solver converges.
        Quad correction_rounding_px(0);
        if (camera.lens.type == LensType::SplinedStereographic) {
            const Vec3Q& ray = reference[i].ray;
            const Vec2Q u = Vec2Q(ray.x(), ray.y()) * (2 / (ray.norm() + ray.z()));
            correction_rounding_px = 4 * Quad(std::numeric_limits<Scalar>::epsilon()) * Quad(f_max) * u.norm();
        }
        const Quad landing_px = (pixel_q(camera.intrinsics, landed[i].m) - pixels[i].cast<Quad>()).norm();
        worst.px[t].update(static_cast<double>(std::max(Quad(0), landing_px - ray_rounding_px - correction_rounding_px)),
                           where);
        const Quad gain = local ? smallest_gain(*local, unit_ray) : Quad(0);
        const double rad_bound = gain > 0 ? static_cast<double>(2 * Quad(px_bound / f_min) / gain) : kInfinity;
        worst.rad_bound[t] = std::max(worst.rad_bound[t], rad_bound);
        worst.rad[t].update(static_cast<double>(angle_between<Quad>(computed[i], reference[i].ray)), where);
    }
}

// Every method, in double and in float, on the pixels of one camera. `options` sets the
// table (the default unless a sweep needs a cheaper one).
void score_methods(const std::string& name, const Camera& camera, const std::vector<Vec2>& pixels,
                   ExtremeWorst& worst, UnprojectorOptions options = {}) {
    const Unprojector<double> in_double(camera, options);
    const Unprojector<float> in_float(camera, options);
    const std::vector<Vec2> pixels_f = cast_all<double>(cast_all<float>(pixels));  // float values, held in double
    for (UnprojectMethod method : kUnprojectMethods) {
        score_method(name, in_double, method, pixels, worst[method]);
        score_method(name, in_float, method, pixels_f, worst[method]);
    }
}

std::vector<Row> method_rows(const std::string& extreme, ExtremeWorst& worst, const std::string& formulation) {
    std::vector<Row> rows;
    std::size_t wrong[2] = {0, 0}, pixels = 0;
    for (UnprojectMethod method : kUnprojectMethods) {
        const MethodWorst& w = worst[method];
        const std::string prefix = std::string(method_name(method)) + ": ";
        rows.push_back({extreme, prefix + "ray vs reference [rad]", w.rad[0].value, w.rad[1].value, w.rad_bound[0],
                        w.rad_bound[1], formulation, w.rad[0].where});
        rows.push_back({extreme, prefix + "where the ray lands [px]", w.px[0].value, w.px[1].value, w.px_bound[0],
                        w.px_bound[1], formulation, w.px[0].where});
        for (int t : {0, 1}) wrong[t] += w.wrong_flags[t];
        pixels += w.pixels[0];
    }
    rows.push_back({extreme, "exact, fast, lut: wrong flags [count of " + std::to_string(pixels) + "]",
                    static_cast<double>(wrong[0]), static_cast<double>(wrong[1]), 0, 0,
                    "a method answers only inside the certified disc; every other pixel goes to the full solver "
                    "in double",
                    ""});
    return rows;
}

// ------------------------------------------------------------------ the extremes

std::vector<Row> large_image_method_rows() {
    ExtremeWorst worst;
    for (const LensCase& c : large_image_cases()) {
        std::vector<Vec2> pixels = corner_pixels(c.camera.size);
        for (const Vec2& p : pixel_grid(c.camera.size, 17, 13)) pixels.push_back(p);
        score_methods(c.name, c.camera, pixels, worst);
    }
    return method_rows("batch: corners and a 17x13 grid of a 100000-px-wide image, every model", worst,
                       "cells whose estimate misses 0.005 px (most, at 260 px per cell) go to the full solver");
}

std::vector<Row> wide_lens_method_rows() {
    ExtremeWorst worst;
    const Camera camera = wide_reference_camera();
    score_methods("wide lens", camera, pixel_grid(camera.size, 151, 101), worst);
    return method_rows("batch: the real wide lens, 151x101 grid", worst, "table start, Newton in the model");
}

std::vector<Row> fold_method_rows() {
    ExtremeWorst worst;
    for (const HandFold& fold : hand_folds()) {
        std::vector<Vec2> pixels;
        for (double delta : {1e-3, 1e-6, 1e-9}) {
            for (int i = 0; i < 16; ++i) {
                const double phi = 2 * std::numbers::pi * i / 16 + 0.1;
                pixels.push_back(pixel_at_radius(fold.camera, fold.d_max * (1 - Quad(delta)), phi));
                pixels.push_back(pixel_at_radius(fold.camera, fold.d_max * (1 + Quad(delta)), phi));
            }
        }
        score_methods(fold.name, fold.camera, pixels, worst);
    }
    return method_rows("batch: fold radius, |m| = d_max (1 -+ 1e-3, 1e-6, 1e-9), " + std::to_string(hand_folds().size()) +
                           " lenses x 16 directions",
                       worst,
                       "past the certified disc only the full solver answers");
}

// FISHEYE next to the principal point (1e-30 to 0.1 px) and at the pixels of rays near
// 90 and 180 degrees.
std::vector<Row> fisheye_method_rows() {
    ExtremeWorst worst;
    const Quad pi = pi_in<Quad>();
    for (const LensCase& c : fisheye_lenses()) {
        const Vec2 centre = c.camera.intrinsics.pixel_from_normalized(Vec2(Vec2::Zero()));
        std::vector<Vec2> pixels{centre};
        for (int e = 1; e <= 30; ++e) {
            const double phi = 0.37 * e;
            pixels.push_back(centre + std::pow(10.0, -e) * Vec2(std::cos(phi), std::sin(phi)));
        }
        std::vector<Vec3Q> rays;
        for (int e = 1; e <= 15; ++e) {
            const Quad small = pow(Quad(10), -e);
            for (const Quad& theta : {pi / 2 - small, pi / 2 + small, pi - small})
                rays.push_back(direction_at(theta, 0.3 * e).cast<Quad>());
        }
        for (const Projected<Quad>& p : project_all<Quad>(c.camera.lens, rays)) {
            if (p.valid) pixels.push_back(pixel_q(c.camera.intrinsics, p.m).cast<double>());
        }
        score_methods(c.name, c.camera, pixels, worst);
    }
    return method_rows("batch: FISHEYE 1e-30 to 0.1 px from the principal point, and theta near 90 and 180 degrees",
                       worst, "sin(theta) / theta; theta = 0 on the axis exactly");
}

std::vector<Row> coefficient_method_rows() {
    ExtremeWorst worst;
    // 96 table nodes, not 384: 26 lenses, 336 pixels each.
    for (const LensCase& c : coefficient_extremes())
        score_methods(c.name, c.camera, pixel_grid(c.camera.size, 21, 16), worst, UnprojectorOptions{.table_nodes = 96});
    return method_rows("batch: coefficients x 1e-8 .. 4.9e-324 and strong, 21x16 grids (96-node tables)", worst,
                       "as the public path");
}

// Every lens behind the focal lengths of the FOV extremes: a 1e-6-degree camera's
// (f = 5.7e12 px over 100000 px: the image spans |m| < 1e-8) and a 179.999-degree one's
// (f = 4.4e-6 over 1600 px: |m| to 2e8, mostly past the domain).
std::vector<Row> focal_extreme_method_rows() {
    ExtremeWorst worst;
    std::size_t kept = 0, refused = 0;
    for (const LensCase& c : lens_cases()) {
        for (double f : {5.7e12, 4.4e-6}) {
            Camera camera = c.camera;
            if (f > 1) camera = scaled_camera(camera, 100000.0 / static_cast<double>(camera.size.width));
            camera.intrinsics.fx = camera.intrinsics.fy = f;
            if (!images_something(camera)) {
                ++refused;
                continue;
            }
            ++kept;
            std::vector<Vec2> pixels = corner_pixels(camera.size);
            for (const Vec2& p : pixel_grid(camera.size, 11, 9)) pixels.push_back(p);
            score_methods(c.name + " f " + std::to_string(f), camera, pixels, worst, UnprojectorOptions{.table_nodes = 96});
        }
    }
    return method_rows("batch: every model at f = 5.7e12 px (fov 1e-6 deg over 100000 px) and f = 4.4e-6 px (179.999 "
                       "deg over 1600 px), corners and 11x9 grids (96-node tables): " +
                           std::to_string(kept) + " cameras, " + std::to_string(refused) + " that image nothing refused",
                       worst, "as above");
}

// ------------------------------------------------------------------ projection

struct BatchProjectionWorst {
    Worst ulps[2];
    std::size_t points[2] = {0, 0}, wrong_flags[2] = {0, 0};
    std::string first_wrong;
};

// The batch Projector in Scalar on the points (already Scalar values), against K m of
// the reference: flagged where the reference is, or where its pixel passes Scalar's range.
template <class Scalar>
void score_projector(const std::string& name, const Camera& camera, const std::vector<Vec3>& points,
                     BatchProjectionWorst& worst) {
    Points2<Scalar> pixels;
    ValidFlags valid;
    Projector<Scalar>(camera).project(as_points3<Scalar>(points), pixels, valid);
    const std::vector<Projected<Quad>> reference = project_all<Quad>(camera.lens, cast_all<Quad>(points));
    constexpr int t = type_index<Scalar>;
    const Quad largest(std::numeric_limits<Scalar>::max());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Vec2Q expected_pixel = pixel_q(camera.intrinsics, reference[i].m);
        Expect expect = expected<Scalar>(reference[i], camera.lens, points[i].cast<Quad>());
        if (expect == Expect::Valid && expected_pixel.cwiseAbs().maxCoeff() > largest) expect = Expect::Flagged;
        const auto where = [&] {
            std::ostringstream out;
            out << name << (t == 0 ? " double" : " float") << " point (" << points[i].transpose() << ")";
            return out.str();
        };
        ++worst.points[t];
        if ((expect == Expect::Flagged && valid[i]) || (expect == Expect::Valid && !valid[i])) {
            if (worst.wrong_flags[0] + worst.wrong_flags[1] == 0) worst.first_wrong = where();
            ++worst.wrong_flags[t];
        }
        if (expect == Expect::Flagged || !valid[i] || !reference[i].valid) continue;
        const Vec2T<Scalar> pixel(pixels.x[i], pixels.y[i]);
        worst.ulps[t].update(ulps(pixel, expected_pixel) / projection_condition(camera.lens, points[i].cast<Quad>()),
                             where);
    }
}

std::vector<Row> projector_rows() {
    BatchProjectionWorst worst;
    std::vector<LensCase> cases = lens_cases();
    for (const LensCase& c : fisheye_lenses()) cases.push_back(c);
    std::vector<Vec3> points = points_at_every_scale();
    for (const Vec3& p : points_towards_the_camera_plane()) points.push_back(p);
    // OCAMCALIB in float, apart: its ray's forward part g(r) = 1 + k1 r + ... + k5 r^5
    // cancels where r is large (near the backward axis), so the coefficients' rounding to
    // float, not the projection, sets its error there (40 ulps of the condition number at
    // (1e-20, 1e-20, -1) on the fisheye case); its flags count with the others'.
    BatchProjectionWorst ocamcalib_float;
    for (const LensCase& c : cases) {
        score_projector<double>(c.name, c.camera, points, worst);
        const bool ocamcalib = c.camera.lens.type == LensType::OcamCalib;
        score_projector<float>(c.name, c.camera, cast_all<double>(cast_all<float>(points)), ocamcalib ? ocamcalib_float : worst);
    }
    worst.wrong_flags[1] += ocamcalib_float.wrong_flags[1];
    worst.points[1] += ocamcalib_float.points[1];
    if (worst.first_wrong.empty()) worst.first_wrong = ocamcalib_float.first_wrong;
    const std::string extreme =
        "batch Projector: points at scales 4.9e-324 to 1.7e308 and at z = +-1e-320 to +-1, every model";
    return {
        {extreme, "pixel vs reference [ulp of |pixel| / the projection's condition number]", worst.ulps[0].value, worst.ulps[1].value, 16, 16,
         "a point past 2^+-(max exponent / 4) scaled by a power of two first (exact)", worst.ulps[0].where + " / " + worst.ulps[1].where},
        {extreme + " (OCAMCALIB in float)", "pixel vs reference [ulp of |pixel| / the projection's condition number]",
         kNotApplicable, ocamcalib_float.ulps[1].value, kNotApplicable, 48,
         "its coefficients rounded to float cancel in g(r) where r is large", ocamcalib_float.ulps[1].where},
        {extreme, "wrong flags [count of " + std::to_string(worst.points[0]) + "]",
         static_cast<double>(worst.wrong_flags[0]), static_cast<double>(worst.wrong_flags[1]), 0, 0,
         "valid only in the domain and if the pixel is finite", worst.first_wrong},
    };
}

// ------------------------------------------------------ the NaN / infinity sweep

// A batch's results are flagged or finite (and a valid ray is not zero).
struct BatchSweepCount {
    std::size_t results[2] = {0, 0}, unflagged_non_finite[2] = {0, 0};
    std::string first[2];
    void add(int t, bool valid, bool finite, const std::string& what) {
        ++results[t];
        if (valid && !finite && unflagged_non_finite[t]++ == 0) first[t] = what;
    }
};

template <class Scalar>
void sweep_batches(const Camera& camera, BatchSweepCount& count) {
    constexpr int t = type_index<Scalar>;
    Points2<Scalar> pixels;
    ValidFlags valid;
    Projector<Scalar>(camera).project(as_points3<Scalar>(sweep_points()), pixels, valid);
    for (std::size_t i = 0; i < valid.size(); ++i) {
        count.add(t, valid[i] != 0, std::isfinite(pixels.x[i]) && std::isfinite(pixels.y[i]),
                  describe_camera(camera) + " project");
    }
    // A small table: the flags do not depend on it, and 135 cameras x 2 types must be quick.
    const Unprojector<Scalar> unprojector(camera, UnprojectorOptions{.table_nodes = 48});
    const Points2<Scalar> sweep = as_points2<Scalar>(sweep_pixels(camera));
    for (UnprojectMethod method : kUnprojectMethods) {
        Points3<Scalar> rays;
        unprojector.unproject(sweep, method, rays, valid);
        for (std::size_t i = 0; i < valid.size(); ++i) {
            const Vec3T<Scalar> ray(rays.x[i], rays.y[i], rays.z[i]);
            count.add(t, valid[i] != 0, ray.allFinite() && !ray.isZero(Scalar(0)),
                      describe_camera(camera) + " " + std::string(method_name(method)) + " " +
                          show(Vec2(sweep.x[i], sweep.y[i])));
        }
    }
}

std::vector<Row> batch_sweep_rows() {
    BatchSweepCount count;
    std::size_t refused = 0;
    for (const Camera& camera : sweep_cameras(&refused)) {
        sweep_batches<double>(camera, count);
        sweep_batches<float>(camera, count);
    }
    return {{"batch sweep: the cameras, points and pixels of the sweep above (" + std::to_string(refused) +
                 " cameras that image nothing refused), Projector and every method",
             "valid but NaN, infinite or zero [count of " + std::to_string(count.results[0]) + " double, " +
                 std::to_string(count.results[1]) + " float]",
             static_cast<double>(count.unflagged_non_finite[0]), static_cast<double>(count.unflagged_non_finite[1]), 0,
             0, "a result is valid only if finite", count.first[0] + "; float: " + count.first[1]}};
}

}  // namespace

TEST_CASE("extremes: batch methods at the corners of a 100000-pixel-wide image") { check_rows(large_image_method_rows()); }
TEST_CASE("extremes: batch methods on the real wide lens") { check_rows(wide_lens_method_rows()); }
TEST_CASE("extremes: batch methods just inside and just outside the fold-over radius") {
    check_rows(fold_method_rows());
}
TEST_CASE("extremes: batch methods on FISHEYE at theta -> 0 and near 90 and 180 degrees") {
    check_rows(fisheye_method_rows());
}
TEST_CASE("extremes: batch methods with strong and near-zero distortion coefficients") {
    check_rows(coefficient_method_rows());
}
TEST_CASE("extremes: batch methods at the focal lengths of 1e-6 and 179.999-degree cameras") {
    check_rows(focal_extreme_method_rows());
}
TEST_CASE("extremes: batch Projector at any scale and at z -> 0") { check_rows(projector_rows()); }
TEST_CASE("extremes: batch paths give nothing NaN or infinite without the invalid flag") {
    check_rows(batch_sweep_rows());
}

namespace libcam::test {

std::vector<Row> batch_rows() {
    std::vector<Row> rows;
    for (const auto& group : {large_image_method_rows, wide_lens_method_rows, fold_method_rows, fisheye_method_rows,
                              coefficient_method_rows, focal_extreme_method_rows, projector_rows, batch_sweep_rows}) {
        const std::vector<Row> more = group();
        rows.insert(rows.end(), more.begin(), more.end());
    }
    return rows;
}

}  // namespace libcam::test
