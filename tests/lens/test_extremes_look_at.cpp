// The look-at camera and its conversions at the extremes, against the 113-bit
// reference: libcam's own templated formulas (look_at_formulas.hpp, pinhole_from_fov,
// look_at_formula_in) run in Quad from the very same inputs. Each extreme is a group of
// rows (extremes.hpp) with a documented bound; the test cases assert the bounds and
// `test_extremes "[table]"` prints the measured values.

#include <catch2/catch.hpp>
#include <iomanip>
#include <sstream>

#include "extremes.hpp"
#include "libcam/convert/look_at_convert.hpp"
#include "libcam/error.hpp"
#include "reference.hpp"
#include "support.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

constexpr double kEpsDouble = std::numeric_limits<double>::epsilon();
constexpr double kEpsFloat = std::numeric_limits<float>::epsilon();

// ---------------------------------------------------------------- the cameras swept

constexpr FovAxis kAxes[] = {FovAxis::Horizontal, FovAxis::Vertical, FovAxis::Diagonal, FovAxis::Both};

// 1x1 to 100000x100000 and aspect ratios to 1:10000 both ways.
const std::vector<ImageSize>& extreme_sizes() {
    static const std::vector<ImageSize> sizes{{1, 1},     {3, 3},     {1920, 1080}, {100000, 100000},
                                              {1, 10000}, {10000, 1}, {10, 100000}, {100000, 10}};
    return sizes;
}

const std::vector<double>& fov_sweep() {
    static const std::vector<double> fovs{1e-6, 1e-4, 1e-2, 1, 30, 90, 150, 179, 179.9, 179.99, 179.999};
    return fovs;
}

// A camera with a random pose (eye within 100 of the origin, up at least ~6 degrees
// from the gaze), the given fov, axis and size.
LookAtCamera swept_camera(double fov, FovAxis axis, ImageSize size) {
    LookAtCamera camera = random_look_at_camera(size, axis);
    camera.fov_deg = fov;
    return camera;
}

// The same camera with every input rounded to float: the float code and its reference
// both start from these, so the float error measured is the computation's, not the
// inputs' rounding. (Written into a fresh camera: GCC 12.2 at -O2 drops the rounding of
// fov_deg when the same camera is rounded in place, member by member; a test case
// below checks the result.)
LookAtCamera rounded_to_float(const LookAtCamera& camera) {
    LookAtCamera rounded = camera;
    rounded.eye = camera.eye.cast<float>().cast<double>();
    rounded.gaze = camera.gaze.cast<float>().cast<double>();
    rounded.up = camera.up.cast<float>().cast<double>();
    rounded.fov_deg = static_cast<float>(camera.fov_deg);
    return rounded;
}

// The OpenCV pixels whose rays are checked: the corners of the image (pixel edges), the
// corner, edge-centre and centre pixels.
std::vector<Vec2> probe_pixels(const ImageSize& size) {
    const double w = static_cast<double>(size.width), h = static_cast<double>(size.height);
    return {{-0.5, -0.5}, {w - 0.5, h - 0.5},         {-0.5, h - 0.5},      {0, 0},          {w - 1, h - 1}, {w - 1, 0},
            {0, h - 1},   {(w - 1) / 2, (h - 1) / 2}, {w - 1, (h - 1) / 2}, {(w - 1) / 2, 0}};
}

std::string describe(const LookAtCamera& camera) {
    std::ostringstream out;
    out << "fov " << camera.fov_deg << " " << to_string(camera.fov_axis) << " " << camera.size.width << "x"
        << camera.size.height;
    return out.str();
}

// ------------------------------------------------------------- the reference camera

// The pixel (OpenCV, top-left rows) that a world direction lands on, through the Quad
// pinhole camera.
Vec2Q reference_pixel(const FovPinholeT<Quad>& pinhole, const Vec3Q& direction) {
    const Vec3Q p = pinhole.R * direction;
    return {pinhole.focal.x() * p.x() / p.z() + pinhole.principal_point.x(),
            pinhole.focal.y() * p.y() / p.z() + pinhole.principal_point.y()};
}

// The pixel error that an error of one epsilon in a ray's direction makes at `pixel`:
// eps f (1 + tan^2 of the angle off axis), the pixel's own conditioning (d pixel / d
// angle = f / cos^2). A bound on where a ray lands is a small multiple of it.
double pixel_conditioning(const FovPinholeT<Quad>& pinhole, const Vec2& pixel, double epsilon) {
    const Vec2Q off_axis((Quad(pixel.x()) - pinhole.principal_point.x()) / pinhole.focal.x(),
                         (Quad(pixel.y()) - pinhole.principal_point.y()) / pinhole.focal.y());
    return epsilon * static_cast<double>(pinhole.focal.maxCoeff() * (1 + off_axis.squaredNorm()));
}

// Errors of a ray through `pixel` against the reference: angle (rad) and the distance
// (px) between `pixel` and where the computed ray lands in the reference camera.
template <class Scalar>
std::pair<double, double> ray_errors(const Vec3T<Scalar>& ray, const FovPinholeT<Quad>& pinhole,
                                     const LookAtRayFormulaT<Quad>& look_at, const Vec2& pixel) {
    const Vec2Q pixel_q = pixel.cast<Quad>();
    const Vec3Q expected = look_at.ray(pixel_q, PixelOrigin::TopLeft);
    const double angle = angle_error(ray, expected);
    const double px = static_cast<double>((reference_pixel(pinhole, ray.template cast<Quad>()) - pixel_q).norm());
    return {angle, px};
}

// ------------------------------------------------------------------ one fov extreme

struct FovSweepWorst {
    Worst focal_double, focal_float;                 // fx, fy, ulps of their own type
    Worst look_at_rad_double, look_at_rad_float;     // look-at ray, angle
    Worst look_at_px_double, look_at_px_float;       // look-at ray, pixels
    Worst calibrated_rad, calibrated_px;             // PreparedCamera::ray (double only)
    Worst fov_back;                                  // K -> fov, ulps of double against the input fov
    double px_scale_double = 0, px_scale_float = 0;  // the largest pixel_conditioning seen
};

void sweep_camera(const LookAtCamera& camera, FovSweepWorst& worst) {
    const auto where = [&] { return describe(camera); };
    // In double, against the reference from the same inputs.
    const FovPinholeT<Quad> pinhole_q = pinhole_from_fov<Quad>(camera);
    const LookAtRayFormulaT<Quad> look_at_q = look_at_formula_in<Quad>(camera);
    const FovPinholeT<double> pinhole_d = pinhole_from_fov<double>(camera);
    for (int i = 0; i < 2; ++i) worst.focal_double.update(ulps(pinhole_d.focal(i), pinhole_q.focal(i)), where);

    const Camera calibrated = to_camera(camera);
    const PreparedCamera prepared(calibrated);
    const LookAtRayFormula look_at_d = camera.look_at_formula();
    for (const Vec2& pixel : probe_pixels(camera.size)) {
        const auto at = [&] {
            return where() + " pixel (" + std::to_string(pixel.x()) + ", " + std::to_string(pixel.y()) + ")";
        };
        const auto [rad, px] = ray_errors<double>(look_at_d.ray(pixel, PixelOrigin::TopLeft), pinhole_q, look_at_q, pixel);
        worst.px_scale_double = std::max(worst.px_scale_double, pixel_conditioning(pinhole_q, pixel, kEpsDouble));
        worst.look_at_rad_double.update(rad, at);
        worst.look_at_px_double.update(px, at);
        const auto [c_rad, c_px] = ray_errors<double>(prepared.ray(pixel).direction, pinhole_q, look_at_q, pixel);
        worst.calibrated_rad.update(c_rad, at);
        worst.calibrated_px.update(c_px, at);
    }
    const LookAtCamera back = to_look_at_camera(calibrated, camera.fov_axis);
    worst.fov_back.update(ulps(back.fov_deg, Quad(camera.fov_deg)), where);

    // In float, against the reference from the float-rounded inputs.
    const LookAtCamera camera_f = rounded_to_float(camera);
    const FovPinholeT<Quad> pinhole_fq = pinhole_from_fov<Quad>(camera_f);
    const LookAtRayFormulaT<Quad> look_at_fq = look_at_formula_in<Quad>(camera_f);
    const FovPinholeT<float> pinhole_f = pinhole_from_fov<float>(camera_f);
    for (int i = 0; i < 2; ++i) worst.focal_float.update(ulps(pinhole_f.focal(i), pinhole_fq.focal(i)), where);
    const LookAtRayFormulaT<float> look_at_f = look_at_formula_in<float>(camera_f);
    for (const Vec2& pixel : probe_pixels(camera.size)) {
        const auto at = [&] {
            return where() + " pixel (" + std::to_string(pixel.x()) + ", " + std::to_string(pixel.y()) + ")";
        };
        const auto [rad, px] =
            ray_errors<float>(look_at_f.ray(pixel.cast<float>(), PixelOrigin::TopLeft), pinhole_fq, look_at_fq, pixel);
        worst.px_scale_float = std::max(worst.px_scale_float, pixel_conditioning(pinhole_fq, pixel, kEpsFloat));
        worst.look_at_rad_float.update(rad, at);
        worst.look_at_px_float.update(px, at);
    }
}

// The bounds, the same at every fov extreme:
// - fx, fy: the tangent rounds once, the aspect ratio (or hypot for the diagonal) and
//   W / (2 tan) add at most 4 more roundings: 3 ulps.
// - a ray's direction: held as three numbers, it is resolved to about eps in angle;
//   the look-at formula's sum alpha u + beta v + w and R^T K^-1 add a few roundings: 4 eps.
// - where a ray lands: 4 eps f (1 + tan^2 off axis), its conditioning (above). At fov
//   1e-6 deg over 100000 px, f = 5.7e12 and one pixel is 1.7e-13 rad, so eps alone is
//   6e-4 px; at 179.999 deg the corner rays are 89.9995 deg off axis, cos^2 = 8e-11.
// - fov -> K -> fov: fx's 3 ulps carry through atan (slope <= 1 relative) plus one
//   rounding: 3 ulps.
constexpr double kFocalUlps = 3, kRayEps = 4, kPixelConditionings = 4, kFovBackUlps = 3;

std::vector<Row> fov_extreme_rows(const std::string& extreme, const std::vector<LookAtCamera>& cameras) {
    FovSweepWorst worst;
    for (const LookAtCamera& camera : cameras) sweep_camera(camera, worst);
    const std::string tangent = "tan(fov/2) in long double, by its complement above 90 deg; one rounding to the type";
    return {
        {extreme, "fx, fy vs reference [ulp]", worst.focal_double.value, worst.focal_float.value, kFocalUlps,
         kFocalUlps, tangent + "; fx = W / (2 tan_x)",
         worst.focal_double.where + "; float: " + worst.focal_float.where},
        {extreme, "look-at ray alpha u + beta v + w [rad]", worst.look_at_rad_double.value, worst.look_at_rad_float.value,
         kRayEps * kEpsDouble, kRayEps * kEpsFloat, "alpha = tan_x (2x - W + 1) / W: 2x - W + 1 exact",
         worst.look_at_rad_double.where},
        {extreme, "look-at ray, where it lands [px]", worst.look_at_px_double.value, worst.look_at_px_float.value,
         kPixelConditionings * worst.px_scale_double, kPixelConditionings * worst.px_scale_float,
         "bound: 4 eps f / cos^2(angle off axis), the pixel's own conditioning", worst.look_at_px_double.where},
        {extreme, "calibrated ray R^T K^-1 [x y 1] [rad]", worst.calibrated_rad.value, kNotApplicable,
         kRayEps * kEpsDouble, kNotApplicable, "K^-1: (x - cx) / fx, x - cx exact", worst.calibrated_rad.where},
        {extreme, "calibrated ray, where it lands [px]", worst.calibrated_px.value, kNotApplicable,
         kPixelConditionings * worst.px_scale_double, kNotApplicable, "as above", worst.calibrated_px.where},
        {extreme, "fov -> K -> fov round trip [ulp]", worst.fov_back.value, kNotApplicable, kFovBackUlps,
         kNotApplicable, "2 atan(W / (2 fx)) in long double, by the complement above 90 deg", worst.fov_back.where},
    };
}

// The same cameras every time, whichever test case (or the table) asks first.
std::vector<LookAtCamera> cameras_at(const std::vector<double>& fovs, const std::vector<ImageSize>& sizes) {
    rng().seed(5);
    std::vector<LookAtCamera> cameras;
    for (double fov : fovs)
        for (const ImageSize& size : sizes)
            for (FovAxis axis : kAxes) cameras.push_back(swept_camera(fov, axis, size));
    return cameras;
}

std::vector<Row> tiny_fov_rows() {
    return fov_extreme_rows("fov 1e-6 deg, every axis, 1x1 to 100000x100000, aspect to 1:10000",
                            cameras_at({1e-6}, extreme_sizes()));
}

std::vector<Row> wide_fov_rows() {
    return fov_extreme_rows("fov 179.999 deg, every axis, 1x1 to 100000x100000, aspect to 1:10000",
                            cameras_at({179.999}, extreme_sizes()));
}

std::vector<Row> fov_sweep_rows() {
    return fov_extreme_rows("fov 1e-6 to 179.999 deg (11 values), every axis, every size above",
                            cameras_at(fov_sweep(), extreme_sizes()));
}

// ------------------------------------------------- far eye, near target, up near gaze

// The basis vectors' angle errors against the reference, the worst of u, v, w.
template <class Scalar>
double basis_error(const BasisT<Scalar>& basis, const BasisT<Quad>& reference) {
    return std::max(
        {angle_error(basis.u, reference.u), angle_error(basis.v, reference.v), angle_error(basis.w, reference.w)});
}

// A look-at camera through look_at, for the pose extremes (fov and size are ordinary).
LookAtCamera posed_camera(const Vec3& eye, const Vec3& target, const Vec3& up) {
    return LookAtCamera::look_at(eye, target, up, 60.0, FovAxis::Horizontal, {1920, 1080});
}

// Eye 1e7 units from the origin, target 1 unit away. t = -R eye is ~1e7 long, so its
// ulp is 1.9e-9: that is all R|t can say about where the camera is, and about a point
// 1 unit in front of it (whose camera-frame position R X + t is a difference of two
// 1e7-long vectors). Double keeps 16 - 7 = 9 digits of such a point; float keeps none.
// The reference for a point X is R (X - eye) in Quad, which has no such cancellation.
std::vector<Row> far_eye_rows() {
    rng().seed(7);
    Worst t_ulps_d, t_ulps_f, eye_d, eye_f, target_d, target_float, pixel_d;
    for (int i = 0; i < 200; ++i) {
        const Vec3 eye = random_unit() * 1e7;
        const Vec3 target = eye + random_unit();
        const LookAtCamera camera = posed_camera(eye, target, random_unit());
        const auto where = [&] {
            return "eye (" + std::to_string(eye.x()) + ", " + std::to_string(eye.y()) + ", " + std::to_string(eye.z()) +
                   ")";
        };
        // Double: t, the eye back from R|t, the target in the camera frame and its pixel.
        const FovPinholeT<Quad> q = pinhole_from_fov<Quad>(camera);
        const Camera calibrated = to_camera(camera);
        t_ulps_d.update(ulps(calibrated.pose.t, q.t), where);
        eye_d.update((calibrated.pose.centre() - camera.eye).norm(), where);
        const Vec3Q target_q = q.R * (target.cast<Quad>() - camera.eye.cast<Quad>());
        target_d.update(static_cast<double>((calibrated.pose.camera_from_world(target).cast<Quad>() - target_q).norm()),
                        where);
        const Vec2Q pixel_q(q.focal.x() * target_q.x() / target_q.z() + q.principal_point.x(),
                            q.focal.y() * target_q.y() / target_q.z() + q.principal_point.y());
        pixel_d.update(static_cast<double>((PreparedCamera(calibrated).project(target).pixel.cast<Quad>() - pixel_q).norm()), where);
        // Float, from the float-rounded inputs.
        const LookAtCamera camera_f = rounded_to_float(camera);
        const Vec3 target_f = target.cast<float>().cast<double>();
        const FovPinholeT<Quad> qf = pinhole_from_fov<Quad>(camera_f);
        const FovPinholeT<float> pf = pinhole_from_fov<float>(camera_f);
        t_ulps_f.update(ulps(pf.t, qf.t), where);
        const Vec3T<float> eye_back_f = centre_from_translation<float>(pf.R, pf.t);
        eye_f.update(static_cast<double>((eye_back_f.cast<Quad>() - camera_f.eye.cast<Quad>()).norm()), where);
        const Vec3T<float> target_in_camera_f = pf.R * target_f.cast<float>() + pf.t;
        const Vec3Q target_fq = qf.R * (target_f.cast<Quad>() - camera_f.eye.cast<Quad>());
        target_float.update(static_cast<double>((target_in_camera_f.cast<Quad>() - target_fq).norm()), where);
    }
    const std::string extreme = "eye 1e7 from the origin, target 1 away";
    std::ostringstream digits;
    digits << "R X + t: 1e7-long terms cancel to 1 (" << std::setprecision(2)
           << std::max(0.0, digits_from_relative(target_d.value))
           << " digits of the 1-unit distance survive in double, "
           << std::max(0.0, digits_from_relative(target_float.value)) << " in float)";
    // Bounds: t within 4 ulps (R's own error of ~eps per entry times |eye|, plus three
    // roundings); the eye and the target within 4 eps |eye|; the target's pixel is
    // f = 1663 px times its camera-frame error.
    const double far_double = 4 * 1e7 * kEpsDouble, far_float = 4 * 1e7 * kEpsFloat;
    return {
        {extreme, "t = -R eye vs reference [ulp of |t|]", t_ulps_d.value, t_ulps_f.value, 4, 4,
         "-(R * eye): three roundings per component", t_ulps_d.where},
        {extreme, "eye back = -R^T t [units]", eye_d.value, eye_f.value, far_double, far_float, "-(R^T t)",
         eye_d.where},
        {extreme, "target in the camera frame [units]", target_d.value, target_float.value, far_double, far_float,
         digits.str(), target_d.where},
        {extreme, "target's pixel [px]", pixel_d.value, kNotApplicable, 1663 * far_double, kNotApplicable,
         "f = 1663 px times the line above", pixel_d.where},
    };
}

// Target 1e-9 from an eye within 100 of the origin: target - eye is exact (Sterbenz),
// and the basis is scale-free, so the basis is as accurate as at any distance. The
// input's own limit: the target is rounded to ulp(|eye|) ~ 1.4e-14, so the direction
// the user meant is known only to ulp(|eye|) / 1e-9 ~ 1e-5 rad (a row below says how
// much). At 1e7 from the origin 1e-9 is below the eye's ulp (1.9e-9): look_at refuses
// (target equals eye), tested below.
std::vector<Row> near_target_rows() {
    rng().seed(9);
    Worst basis_d, basis_f, input_limit;
    for (int i = 0; i < 200; ++i) {
        const Vec3 eye = random_vector(100.0);
        const LookAtCamera camera = posed_camera(eye, eye + 1e-9 * random_unit(), random_unit());
        const auto where = [&] { return "gaze " + std::to_string(camera.gaze.norm()); };
        basis_d.update(basis_error(camera.basis(), basis_from_gaze_up<Quad>(camera.gaze.cast<Quad>(),
                                                                            camera.up.cast<Quad>(), Handedness::Left)),
                       where);
        const LookAtCamera camera_f = rounded_to_float(camera);
        basis_f.update(
            basis_error(
                basis_from_gaze_up<float>(camera_f.gaze.cast<float>(), camera_f.up.cast<float>(), Handedness::Left),
                basis_from_gaze_up<Quad>(camera_f.gaze.cast<Quad>(), camera_f.up.cast<Quad>(), Handedness::Left)),
            where);
        input_limit.update(
            static_cast<double>(ulp_of<double>(Quad(camera.eye.cwiseAbs().maxCoeff())) / Quad(camera.gaze.norm())),
            where);
    }
    const std::string extreme = "target 1e-9 from the eye (eye within 100 of the origin)";
    return {
        {extreme, "basis u, v, w [rad]", basis_d.value, basis_f.value, kRayEps * kEpsDouble, kRayEps * kEpsFloat,
         "target - eye exact; basis from powers-of-two-scaled gaze", basis_d.where},
        {extreme, "input limit: ulp(eye) / |target - eye| [rad]", input_limit.value, kNotApplicable, kNotApplicable,
         kNotApplicable, "(the target's own rounding, not libcam's)", input_limit.where},
    };
}

// Up at a small angle from the gaze, a toward a random perpendicular.
LookAtCamera up_near_gaze(double angle) {
    const Vec3 gaze = random_unit() * uniform(0.1, 10.0);
    const Vec3 across = gaze.unitOrthogonal();
    return posed_camera(Vec3::Zero(), gaze,
                        (std::cos(angle) * gaze.normalized() + std::sin(angle) * across) * uniform(0.1, 10.0));
}

// Up 1e-12 and 5e-10 rad from the gaze, below kMinUpGazeAngleRad: to_camera refuses
// each with InvalidArgument naming up and the threshold; the row counts those it
// did not refuse so.
Row refused_up_row() {
    rng().seed(13);
    std::size_t accepted = 0, cameras = 0;
    for (double angle : {1e-12, 5e-10}) {
        for (int i = 0; i < 100; ++i, ++cameras) {
            try {
                to_camera(up_near_gaze(angle));
                ++accepted;
            } catch (const InvalidArgument& error) {
                const std::string message = error.what();
                const bool clear = message.find("up: parallel to the gaze") != std::string::npos &&
                                   message.find("minimum 1e-09 rad") != std::string::npos;
                accepted += clear ? 0 : 1;
            }
        }
    }
    return {
        "up 1e-12 and 5e-10 rad from the gaze",
        "not refused with 'up: parallel to the gaze ... minimum 1e-09 rad' [count of " + std::to_string(cameras) + "]",
        static_cast<double>(accepted),
        kNotApplicable,
        0,
        kNotApplicable,
        "angle_between by atan2(|a x b|, a.b) against kMinUpGazeAngleRad = 1e-9",
        ""};
}

// Up 1e-6 rad (and down to just above the threshold, 1.1e-9 rad) from the gaze: u =
// gaze x up is a small vector; the accurate cross product keeps its direction to a few
// ulps, so the basis is right to eps, though u then moves by eps / angle when up moves
// by one ulp (the input's conditioning, not libcam's error).
std::vector<Row> up_near_gaze_rows() {
    rng().seed(11);
    Worst at_1e6_d, at_1e6_f, sweep_d, round_trip_d;
    for (double angle : {1e-6, 1e-7, 1e-8, 2e-9, 1.1e-9}) {
        for (int i = 0; i < 100; ++i) {
            const LookAtCamera camera = up_near_gaze(angle);
            const auto where = [&] { return "angle " + std::to_string(angle); };
            const BasisT<Quad> reference =
                basis_from_gaze_up<Quad>(camera.gaze.cast<Quad>(), camera.up.cast<Quad>(), Handedness::Left);
            const double error = basis_error(camera.basis(), reference);
            sweep_d.update(error, where);
            // K, R, t -> look-at -> basis: the way back returns the camera's own up (v).
            round_trip_d.update(basis_error(to_look_at_camera(to_camera(camera), FovAxis::Horizontal).basis(), reference),
                                where);
            if (angle != 1e-6) continue;
            at_1e6_d.update(error, where);
            const LookAtCamera camera_f = rounded_to_float(camera);
            at_1e6_f.update(
                basis_error(
                    basis_from_gaze_up<float>(camera_f.gaze.cast<float>(), camera_f.up.cast<float>(), Handedness::Left),
                    basis_from_gaze_up<Quad>(camera_f.gaze.cast<Quad>(), camera_f.up.cast<Quad>(), Handedness::Left)),
                where);
        }
    }
    const std::string formulation = "u = gaze x up by Kahan's fma difference of products";
    return {
        {"up 1e-6 rad from the gaze", "basis u, v, w [rad]", at_1e6_d.value, at_1e6_f.value, kRayEps * kEpsDouble,
         kRayEps * kEpsFloat, formulation, at_1e6_d.where},
        {"up 1.1e-9 to 1e-6 rad from the gaze", "basis u, v, w [rad]", sweep_d.value, kNotApplicable,
         kRayEps * kEpsDouble, kNotApplicable, formulation, sweep_d.where},
        {"up 1.1e-9 to 1e-6 rad from the gaze", "K, R, t -> look-at -> basis [rad]", round_trip_d.value, kNotApplicable,
         kRayEps * kEpsDouble, kNotApplicable, "gaze, up = rows of R", round_trip_d.where},
        refused_up_row(),
    };
}

// K -> fov angles of a camera whose principal point is off centre, up to 10000 image
// sides away (not a look-at camera: the way back reports its angles and frustum). The
// reference: atan(high) - atan(low) in Quad, the edges' tangents from the same K.
std::vector<Row> off_centre_rows() {
    Worst worst;
    const auto spanned_deg = [](const Quad& centre, const Quad& f, long side) {
        const Quad low = (Quad(-0.5) - centre) / f, high = (Quad(side) - Quad(0.5) - centre) / f;
        return (atan(high) - atan(low)) * 180 / pi_in<Quad>();
    };
    for (double fov : fov_sweep()) {
        for (double offset : {0.1, 10.0, 1e4}) {
            for (const ImageSize size : {ImageSize{100, 50}, ImageSize{1920, 1080}, ImageSize{100000, 10}}) {
                Camera camera;
                camera.size = size;
                const double w = static_cast<double>(size.width), h = static_cast<double>(size.height);
                const double f = 0.5 * w / tan_half_angle_deg(fov);
                camera.intrinsics = {f, f, size.centre_x() + offset * w, size.centre_y() - offset * h, 0.0};
                const FovDescription description = describe_fov(camera);
                const auto where = [&] {
                    return "fov " + std::to_string(fov) + " offset " + std::to_string(offset) + " width " +
                           std::to_string(size.width);
                };
                const Intrinsics& k = camera.intrinsics;
                worst.update(ulps(description.fov_deg.horizontal, spanned_deg(k.cx, k.fx, size.width)), where);
                worst.update(ulps(description.fov_deg.vertical, spanned_deg(k.cy, k.fy, size.height)), where);
            }
        }
    }
    return {{"principal point 0.1 to 10000 image sides off centre, fov 1e-6 to 179.999 deg",
             "K -> horizontal, vertical fov [ulp]", worst.value, kNotApplicable, 4, kNotApplicable,
             "atan2(W / fx, 1 + low high) for atan(high) - atan(low)", worst.where}};
}

}  // namespace

TEST_CASE("extremes: the float-rounded inputs are floats") {
    for (const LookAtCamera& camera : cameras_at(fov_sweep(), {{3, 3}})) {
        const LookAtCamera rounded = rounded_to_float(camera);
        REQUIRE(static_cast<float>(rounded.fov_deg) == rounded.fov_deg);
        REQUIRE(rounded.up.cast<float>().cast<double>() == rounded.up);
        REQUIRE(rounded.fov_deg == static_cast<double>(static_cast<float>(camera.fov_deg)));
    }
}

TEST_CASE("extremes: fov 1e-6 degrees on every axis and size") { check_rows(tiny_fov_rows()); }
TEST_CASE("extremes: fov 179.999 degrees on every axis and size") { check_rows(wide_fov_rows()); }
TEST_CASE("extremes: fov from 1e-6 to 179.999 degrees on every axis and size") { check_rows(fov_sweep_rows()); }
TEST_CASE("extremes: eye 1e7 from the origin, target 1 away") { check_rows(far_eye_rows()); }
TEST_CASE("extremes: fov angles of a camera with its principal point far off centre") { check_rows(off_centre_rows()); }
TEST_CASE("extremes: target 1e-9 from the eye") {
    check_rows(near_target_rows());
    // At 1e7 from the origin, 1e-9 is below the eye's ulp (1.9e-9): the target rounds to
    // the eye and look_at says so.
    const Vec3 eye(1e7, -1e7, 1e7);
    REQUIRE_THROWS_WITH(posed_camera(eye, eye + 1e-9 * Vec3(1, 1, -1).normalized(), {0, 0, 1}),
                        Catch::Matchers::Contains("target: equals eye"));
}
TEST_CASE("extremes: up near the gaze, a correct basis above kMinUpGazeAngleRad and a clear error below") {
    check_rows(up_near_gaze_rows());
    REQUIRE_THROWS_WITH(
        to_camera(posed_camera({0, 0, 0}, {0, 0, -1}, {0, 1e-12, -1})),
        Catch::Matchers::Contains("up: parallel to the gaze") && Catch::Matchers::Contains("minimum 1e-09 rad"));
}

namespace libcam::test {

std::vector<Row> fov_rows() {
    std::vector<Row> rows;
    for (const auto& group : {tiny_fov_rows, wide_fov_rows, fov_sweep_rows, far_eye_rows, near_target_rows,
                              up_near_gaze_rows, off_centre_rows}) {
        const std::vector<Row> more = group();
        rows.insert(rows.end(), more.begin(), more.end());
    }
    return rows;
}

}  // namespace libcam::test
