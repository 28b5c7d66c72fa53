// The lens models at the extremes, against the 113-bit reference: the same
// model templates (lens/*.hpp) and the same solver (undistort.hpp) run in Quad.
//
// Double goes through the public Camera API (K^-1 included); its reference starts from
// the exact pixel. Float goes through the model templates from the normalised point
// rounded to float; its reference starts from that same float point, so the float
// error is the model's and the solver's, not the rounding of the input.
//
// The batch paths (Projector, Unprojector's exact, fast and lut) are swept at the same
// extremes in test_extremes_methods.cpp; the inputs are in extremes_lens.hpp.

#include <catch2/catch.hpp>
#include <cstdint>
#include <sstream>

#include "extremes_lens.hpp"
#include "libcam/error.hpp"
#include "libcam/lens/arctangent.hpp"
#include "libcam/lens/sine_cosine.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

// Double, through PreparedCamera::unproject; the reference from the exact pixel. The
// pixel error is where the computed ray lands in the reference camera.
void unproject_double(const std::string& name, const Camera& camera, const std::vector<Vec2>& pixels,
                      UnprojectionWorst& worst) {
    const std::vector<Unprojection> rays = PreparedCamera(camera).unproject(pixels);
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

// ----------------------------------------------------------------- the extremes

// Every model's lens (mild and strong) on a 100000-pixel-wide sensor, at its corners.
std::vector<Row> large_image_rows() {
    UnprojectionWorst worst;
    for (const LensCase& c : large_image_cases()) unproject_both(c.name, c.camera, corner_pixels(c.camera.size), worst);
    return unprojection_rows("corners of a 100000-px-wide image, every model, mild and strong", worst,
                             "Newton from the radial 1-D root, bracketed; residual <= 64 eps (1 + |m|)");
}

// The real wide lens (6016x4016, OPENCV8), a 151x101 grid with the corners (test_unproject checks 601x401
// against OpenCV; the 113-bit reference costs more).
std::vector<Row> wide_lens_rows() {
    UnprojectionWorst worst;
    const Camera camera = wide_reference_camera();
    unproject_both("wide lens", camera, pixel_grid(camera.size, 151, 101), worst);
    return unprojection_rows("the real wide lens (6016x4016 OPENCV8), 151x101 grid with the corners", worst,
                             "as above");
}

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
    rows.push_back({"fold-over radius, OPENCV4/5/8/12/14, FISHEYE and CAHVOR (by hand)", "valid_radius vs r_max [ulp]",
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
        extreme << "fold radius: |m| = d_max (1 -+ " << delta << "), " << hand_folds().size()
                << " lenses x 16 directions, inside and outside";
        const std::vector<Row> more =
            unprojection_rows(extreme.str(), inside, "the solver's bracket stops at valid_radius");
        rows.insert(rows.end(), more.begin(), more.end());
    }
    return rows;
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

// Numbers in [0, 1), a fixed sequence from a seed (splitmix64).
class Uniform {
public:
    explicit Uniform(std::uint64_t seed) : state_(seed) {}
    double operator()() {
        state_ += 0x9e3779b97f4a7c15ULL;
        std::uint64_t z = state_;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1p-53;
    }

private:
    std::uint64_t state_;
};

// angle_from_axis (lens/arctangent.hpp), the fisheye models' theta, against atan2 in Quad:
// every octant (the eight sign and order cases of y, |x|), the reduction's edges (t near
// 0.66 and 1), the axes and diagonals, and tiny and huge ratios.
template <class Scalar>
Worst angle_from_axis_worst() {
    Worst worst;
    const auto check = [&](double y_value, double x_value) {
        const Scalar y = static_cast<Scalar>(y_value), x = static_cast<Scalar>(x_value);
        const Quad reference = atan2(Quad(y), Quad(x));
        const auto where = [&] {
            std::ostringstream out;
            out.precision(17);
            out << "atan2(" << y << ", " << x << ")";
            return out.str();
        };
        worst.update(ulps(angle_from_axis(y, x), reference), where);
        worst.update(ulps(lane_value(angle_from_axis(Lane<Scalar>(y), Lane<Scalar>(x))), reference), where);
    };
    Uniform uniform(12345);
    for (int i = 0; i < 200000; ++i) {
        const double scale = std::ldexp(1.0, static_cast<int>(uniform() * 120) - 60);
        const double ratio = i % 4 == 0   ? std::ldexp(uniform(), -static_cast<int>(uniform() * 60))  // near an axis
                             : i % 4 == 1 ? 0.6 + 0.1 * uniform()  // at t = 0.66
                             : i % 4 == 2 ? 0.45 + 0.2 * uniform()  // below it, where a = t is largest
                                          : uniform();
        const double a = scale, b = scale * ratio;
        for (const double x : {a, -a, b, -b}) check(x == a || x == -a ? b : a, x);
    }
    for (const double x : {1.0, -1.0, 0.0, -0.0, 1e-300, -1e-300}) check(1.0, x);
    for (const double y : {0.0, 1e-300, 1.0}) check(y, 1.0), check(y, -1.0);
    return worst;
}

std::vector<Row> angle_rows() {
    const Worst in_double = angle_from_axis_worst<double>(), in_float = angle_from_axis_worst<float>();
    return {{"angle_from_axis(y, x) = atan2(y, x) for y >= 0: 8e5 points over every octant at 2^-60..2^60, t = "
             "0.45..0.7, near the axes, the axes and diagonals; and in Lane",
             "angle vs reference [ulp]", in_double.value, in_float.value, 2, 2,
             "Cephes' atan: t = min / max, past t = 0.66 pi/4 + atan((t - 1) / (t + 1)); k pi/4 in two parts",
             in_double.where}};
}

// sine_cosine (lens/sine_cosine.hpp), the fisheye and FOV models' ray from an angle,
// against sin and cos in Quad: (sin, cos) as a vector, in ulps at its norm 1 (as a ray's
// direction is measured), over [0, pi]: uniform, at the reduction's edges (the octants
// k pi/4 and next to them), tiny angles and pi itself.
template <class Scalar>
Worst sine_cosine_worst() {
    Worst worst;
    const auto check = [&](double x_value) {
        const Scalar x = static_cast<Scalar>(x_value);
        const Eigen::Matrix<Quad, 2, 1> reference(sin(Quad(x)), cos(Quad(x)));
        const auto where = [&] {
            std::ostringstream out;
            out.precision(17);
            out << "x = " << x;
            return out.str();
        };
        Scalar s, c;
        sine_cosine(x, s, c);
        worst.update(ulps(Eigen::Matrix<Scalar, 2, 1>(s, c), reference), where);
        Lane<Scalar> lane_s, lane_c;
        sine_cosine(Lane<Scalar>(x), lane_s, lane_c);
        worst.update(ulps(Eigen::Matrix<Scalar, 2, 1>(lane_value(lane_s), lane_value(lane_c)), reference), where);
    };
    Uniform uniform(6789);
    for (int i = 0; i < 200000; ++i) check(std::numbers::pi * uniform());
    for (int k = 0; k <= 4; ++k) {
        const double edge = k * std::numbers::pi / 4;
        for (int e = 1; e <= 40; ++e) {
            for (const double offset : {std::ldexp(1.0, -e), -std::ldexp(1.0, -e)}) {
                if (edge + offset >= 0 && edge + offset <= std::numbers::pi) check(edge + offset);
            }
        }
        check(edge);
        check(std::nextafter(edge, 0.0));
        check(std::nextafter(edge, 4.0));
    }
    for (int e = 1; e <= 300; e += 7) check(std::ldexp(1.0, -e));
    check(0.0);
    return worst;
}

std::vector<Row> sine_cosine_rows() {
    const Worst in_double = sine_cosine_worst<double>(), in_float = sine_cosine_worst<float>();
    return {{"sine_cosine(x) = (sin x, cos x) for x in [0, pi]: 2e5 uniform points, the octants k pi/4 and 2^-1..2^-40 "
             "either side, tiny angles; and in Lane",
             "(sin, cos) vs reference [ulp of 1]", in_double.value, in_float.value, 2, 2,
             "Cephes' sin and cos: x - j pi/4 (j even) with pi/4 in three parts, a polynomial for each",
             in_double.where}};
}

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

std::vector<Row> camera_plane_rows() {
    ProjectionWorst perspective, behind, distorted_unified, distorted_fisheye, panotools_fisheye;
    std::size_t perspective_behind_valid = 0;
    for (const LensCase& c : lens_cases()) {
        const std::vector<Vec3> points = points_towards_the_camera_plane();
        const bool sees_behind = lens_info(c.camera.lens.type).sees_behind_camera;
        const LensType type = c.camera.lens.type;
        const bool two_step_fisheye = type == LensType::ThinPrismFisheye || type == LensType::RadTanThinPrismFisheye;
        const bool panotools = panotools_polynomial(type) && sees_behind;
        project_both(c.camera.lens, points,
                     type == LensType::Mei    ? distorted_unified
                     : two_step_fisheye       ? distorted_fisheye
                     : panotools              ? panotools_fisheye
                     : sees_behind            ? behind
                                              : perspective,
                     c.name);
        if (lens_info(c.camera.lens.type).sees_behind_camera) continue;
        const PreparedCamera camera(c.camera);
        for (std::size_t i = 0; i < points.size(); ++i) {
            if (points[i].z() > 0) continue;
            perspective_behind_valid += camera.project_camera_point(points[i]).valid ? 1 : 0;
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
        projection_rows("points at z = +-1e-320 to +-1, FISHEYE, STEREOGRAPHIC, LONLAT, LATLON, DOUBLE_SPHERE, UCM, EUCM",
                        behind, 4, 4, "atan2; |p| + z as rho^2 / (|p| - z) for z < 0");
    rows.insert(rows.end(), more.begin(), more.end());
    // MEI is two steps, UCM's q and then OPENCV4's distortion of it: each rounds by a few
    // ulps, and the second multiplies the first's error by its slope (1.8 at EuRoC's rim).
    const std::vector<Row> unified = projection_rows("points at z = +-1e-320 to +-1, MEI", distorted_unified, 16, 16,
                                                     "UCM's q, then OPENCV4's distortion of q");
    rows.insert(rows.end(), unified.begin(), unified.end());
    // COLMAP's thin-prism fisheyes add decentering and prism terms to the radial part
    // (RAD_TAN_THIN_PRISM_FISHEYE after it): more terms, each rounding, and at 90 degrees
    // COLMAP's test lens (k1 = -0.471) has terms of 1.2 and 1.4 that cancel to 1.
    const std::vector<Row> thin_prism =
        projection_rows("points at z = +-1e-320 to +-1, THIN_PRISM_FISHEYE, RAD_TAN_THIN_PRISM_FISHEYE",
                        distorted_fisheye, 16, 16, "FISHEYE's theta, then the radial, decentering and prism terms");
    rows.insert(rows.end(), thin_prism.begin(), thin_prism.end());
    // The fisheye projections with PanoTools' polynomial are two steps too: the projected
    // radius P(theta) (up to 11 at 160 degrees for the stereographic one), then
    // 1 + c r + b r^2 + a r^3, whose terms of the strong Samyang cancel there by ~2x.
    const std::vector<Row> panotools = projection_rows(
        "points at z = +-1e-320 to +-1, EQUIDISTANT_RADIAL, EQUISOLID_RADIAL, STEREOGRAPHIC_RADIAL", panotools_fisheye, 16,
        16, "the projection's point, then PanoTools' polynomial of its radius");
    rows.insert(rows.end(), panotools.begin(), panotools.end());
    return rows;
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

// Through PreparedCamera::project_camera_points (double, pixels against K m of the reference).
std::vector<Row> scale_rows() {
    Worst px;
    std::size_t wrong_flags = 0, compared = 0;
    std::vector<LensCase> cases = lens_cases();
    for (const LensCase& c : fisheye_lenses()) cases.push_back(c);
    const std::vector<Vec3> points = points_at_every_scale();
    for (const LensCase& c : cases) {
        const std::vector<Projection> projections = PreparedCamera(c.camera).project_camera_points(points);
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
            const double condition = projection_condition(c.camera.lens, points[i].cast<Quad>());
            px.update(ulps(projections[i].pixel, expected_pixel) / condition, [&] {
                std::ostringstream out;
                out << c.name << " point (" << points[i].transpose() << ")";
                return out.str();
            });
        }
    }
    const std::string extreme = "points at scales 4.9e-324 to 1.7e308, every model (PreparedCamera::project_camera_points)";
    return {
        {extreme, "pixel vs reference [ulp of |pixel| / the projection's condition number]", px.value,
         kNotApplicable, 16, kNotApplicable, "the point scaled by a power of two into [1, 2) first (exact)",
         px.where},
        {extreme, "wrong flags [count of " + std::to_string(compared) + "]", static_cast<double>(wrong_flags),
         kNotApplicable, 0, kNotApplicable, "a pixel past the largest double is flagged", ""},
    };
}

void sweep_lens(const Camera& camera, SweepCount& in_double, SweepCount& in_float) {
    const std::vector<Vec3> points = sweep_points();
    const PreparedCamera prepared(camera);
    const std::vector<Projection> projections = prepared.project_camera_points(points);
    for (std::size_t i = 0; i < points.size(); ++i) {
        in_double.add(projections[i].valid, projections[i].pixel.allFinite(),
                      describe_camera(camera) + " project " + show(points[i]));
    }
    const std::vector<Vec2> pixels = sweep_pixels(camera);
    const std::vector<Unprojection> rays = prepared.unproject(pixels);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        const bool finite = rays[i].direction.allFinite() && !rays[i].direction.isZero(0.0);
        in_double.add(rays[i].valid, finite, describe_camera(camera) + " unproject " + show(pixels[i]));
        const Ray ray = prepared.ray(pixels[i]);
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

// The look-at cameras at every extreme: to_camera either throws or gives finite K, R, t,
// and every probe ray is finite.
void sweep_fov(SweepCount& in_double) {
    rng().seed(17);
    for (double fov : {1e-6, 1e-3, 1.0, 90.0, 179.0, 179.999}) {
        for (const ImageSize size :
             {ImageSize{1, 1}, ImageSize{100000, 100000}, ImageSize{1, 10000}, ImageSize{100000, 10}}) {
            for (FovAxis axis : {FovAxis::Horizontal, FovAxis::Vertical, FovAxis::Diagonal, FovAxis::Both}) {
                for (double eye_scale : {0.0, 1e7, 1e300}) {
                    LookAtCamera look_at_camera = random_look_at_camera(size, axis);
                    look_at_camera.fov_deg = fov;
                    look_at_camera.eye = random_unit() * eye_scale;
                    Camera camera;
                    try {
                        camera = to_camera(look_at_camera);
                    } catch (const Error&) {
                        in_double.add(false, false, "");
                        continue;
                    }
                    const bool finite =
                        camera.intrinsics.K().allFinite() && camera.pose.R.allFinite() && camera.pose.t.allFinite();
                    in_double.add(true, finite,
                                  "look-at camera fov " + std::to_string(fov) + " eye " + std::to_string(eye_scale));
                    const PreparedCamera prepared(camera);
                    for (const Vec2& pixel : corner_pixels(size)) {
                        const Ray ray = prepared.ray(pixel);
                        in_double.add(ray.valid, ray.direction.allFinite() && ray.origin.allFinite(),
                                      "look-at camera ray " + show(pixel));
                        const Vec3 look_at = look_at_camera.look_at_ray(pixel, PixelOrigin::TopLeft);
                        in_double.add(true, look_at.allFinite(), "FOV look-at ray " + show(pixel));
                    }
                }
            }
        }
    }
}

std::vector<Row> sweep_rows() {
    SweepCount in_double, in_float;
    std::size_t refused = 0;
    for (const Camera& camera : sweep_cameras(&refused)) sweep_lens(camera, in_double, in_float);
    sweep_fov(in_double);
    const std::string extreme =
        "sweep: every model and extreme above, points at scales 5e-324 to 1.7e308, pixels to 1e300 px away, FOV "
        "cameras with eye to 1e300 (" + std::to_string(refused) + " cameras that image nothing refused)";
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
TEST_CASE("extremes: the fisheye models' angle from the axis against atan2") { check_rows(angle_rows()); }
TEST_CASE("extremes: the fisheye and FOV models' sine and cosine against sin and cos") { check_rows(sine_cosine_rows()); }
TEST_CASE("extremes: FISHEYE at theta -> 0") { check_rows(fisheye_axis_rows()); }
TEST_CASE("extremes: FISHEYE near 90 and 180 degrees") { check_rows(fisheye_wide_rows()); }
TEST_CASE("extremes: points at z -> 0+ and behind the camera") { check_rows(camera_plane_rows()); }
TEST_CASE("extremes: strong and near-zero distortion coefficients") { check_rows(coefficient_rows()); }
TEST_CASE("extremes: points at any scale") { check_rows(scale_rows()); }
TEST_CASE("extremes: nothing is NaN or infinite without the invalid flag") { check_rows(sweep_rows()); }

namespace libcam::test {

std::vector<Row> lens_rows() {
    std::vector<Row> rows;
    for (const auto& group : {large_image_rows, wide_lens_rows, fold_rows, angle_rows, sine_cosine_rows, fisheye_axis_rows, fisheye_wide_rows,
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
    const Camera camera = lens_camera(LensType::OpenCv8, {0.1, 0.02, 1e-4, -1e-4, 0.001, 0.12, 0.015, 0.0005});
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
