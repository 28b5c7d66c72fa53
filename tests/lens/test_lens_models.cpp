// Lens models: projection against cv::projectPoints, cv::fisheye::projectPoints and
// mrcal_project; Jacobians against central differences in long double and against
// ceres::Jet; the valid domain (behind the camera, fold-over radius) against formulas
// worked by hand.

#include <ceres/jet.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <numbers>
#include <thread>
#include <opencv2/calib3d.hpp>

#include "lens_cases.hpp"
#include "libcam/interop/mrcal.hpp"
#include "libcam/interop/detail/mrcal_c.hpp"
#include "libcam/interop/opencv.hpp"
#include "libcam/camera/projector.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/lens/lens_models.hpp"
#include "support.hpp"
#include "real_cameras.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

constexpr double kPixelTolerance = 1e-9;

// mrcal's name for the model, with the configuration mrcal keeps in it (CAHVORE's
// linearity, here 0.5).
std::string mrcal_name_of(LensType type) {
    const std::string name = "LENSMODEL_" + std::string(lens_info(type).name);
    if (type == LensType::Cahvore) return name + "_linearity=0.5";
    if (type == LensType::SplinedStereographic) return name + "_order=3_Nx=4_Ny=5_fov_x_deg=120";
    return name;
}

// A lens of the model with zero coefficients and the configuration mrcal_name_of names.
std::vector<double> zero_coefficients(LensType type) {
    if (type == LensType::SplinedStereographic) {
        std::vector<double> k(4 + 2 * 4 * 5, 0.0);
        k[0] = 3, k[1] = 4, k[2] = 5, k[3] = 120;
        return k;
    }
    std::vector<double> k(static_cast<std::size_t>(lens_info(type).num_coefficients), 0.0);
    if (type == LensType::Cahvore) k.back() = 0.5;
    return k;
}

bool mrcal_has(LensType type) {
    mrcal_lensmodel_t model;
    return mrcal_lensmodel_from_name(&model, mrcal_name_of(type).c_str());
}

// Points spread over the model's valid domain (well inside the fold-over radius), at
// several depths, on a grid and at random. For OpenCV's models z > 0; for the others
// every direction but the model's singular axis.
// max_degrees bounds the angle from the optical axis for the models that see behind.
std::vector<Vec3> sample_points(const Camera& camera, double max_degrees) {
    const LensType type = camera.lens.type;
    const double limit = domain_edge_of(camera.lens);
    std::vector<Vec3> directions;
    if (type == LensType::Fisheye || type == LensType::Stereographic || type == LensType::Lonlat ||
        type == LensType::Latlon) {
        // By angle from the optical axis (short of the fold-over angle).
        const double max_theta = std::min(radians_from_degrees(max_degrees), 0.98 * limit);
        for (int i = 0; i <= 40; ++i) {
            for (int j = 0; j < 36; ++j) {
                const double theta = max_theta * i / 40.0, phi = 2 * std::numbers::pi * (j + 0.25) / 36.0;
                directions.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            }
        }
        for (int i = 0; i < 300; ++i) {
            const Vec3 d = random_unit();
            if (std::atan2(std::hypot(d.x(), d.y()), d.z()) < max_theta) directions.push_back(d);
        }
    } else {
        const double reach = std::min(1.6, 0.98 * limit / std::sqrt(2.0));
        for (int i = 0; i <= 40; ++i)
            for (int j = 0; j <= 40; ++j) directions.emplace_back(reach * (i / 20.0 - 1), reach * (j / 20.0 - 1), 1.0);
        for (int i = 0; i < 300; ++i) directions.emplace_back(uniform(-reach, reach), uniform(-reach, reach), 1.0);
    }
    // Off the axis where no pixel sees it (lens_cases.hpp's axis_margin_of).
    const double margin = axis_margin_of(camera.lens);
    std::erase_if(directions, [&](const Vec3& d) { return margin > 0 && std::atan2(d.head<2>().norm(), d.z()) <= margin; });
    std::vector<Vec3> points;
    for (const Vec3& d : directions) {
        if (type == LensType::Lonlat && std::hypot(d.x(), d.z()) < 1e-3) continue;  // the poles
        if (type == LensType::Latlon && std::hypot(d.y(), d.z()) < 1e-3) continue;
        points.push_back(d * uniform(0.2, 50.0));
    }
    return points;
}

}  // namespace

TEST_CASE("The model table agrees with mrcal's metadata for every model both have") {
    for (const LensInfo& info : lens_models()) {
        INFO(info.name);
        // The table's mrcal column names exactly the models libmrcal itself knows by that name.
        CHECK(mrcal_has(info.type) == !info.mrcal.empty());
        if (!mrcal_has(info.type)) continue;
        CHECK(info.mrcal == "LENSMODEL_" + std::string(info.name));
        mrcal_lensmodel_t model;
        REQUIRE(mrcal_lensmodel_from_name(&model, mrcal_name_of(info.type).c_str()));
        // CAHVORE's linearity and SPLINED_STEREOGRAPHIC's grid are in mrcal's name, not its
        // intrinsics.
        const std::vector<double> zeros = zero_coefficients(info.type);
        const int in_name = info.type == LensType::Cahvore ? 1 : info.type == LensType::SplinedStereographic ? 4 : 0;
        CHECK(mrcal_lensmodel_num_params(&model) == 4 + static_cast<int>(zeros.size()) - in_name);
        CHECK(mrcal_lensmodel_name(Lens{info.type, zeros}) == mrcal_name_of(info.type));
        CHECK(mrcal_lensmodel_metadata(&model).can_project_behind_camera == info.sees_behind_camera);
        // The coefficients the row says mrcal keeps in its name are those mrcal's own
        // unconfigured name holds ("LENSMODEL_CAHVORE_linearity=...").
        CHECK(info.mrcal_in_name.leading + info.mrcal_in_name.trailing == in_name);
        CHECK(mrcal_model_name(info.type) == mrcal_lensmodel_name_unconfigured(&model));
    }
    CHECK_FALSE(mrcal_has(LensType::Fisheye));
    CHECK_FALSE(mrcal_has(LensType::OpenCv14));
    CHECK(lens_info(LensType::Fisheye).sees_behind_camera);
}

TEST_CASE("Projection agrees with cv::projectPoints / cv::fisheye::projectPoints and mrcal_project to 1e-9 px") {
    for (const LensCase& c : lens_cases()) {
        INFO(c.name);
        const std::vector<Vec3> front = sample_points(c.camera, 89.5);
        const PreparedCamera camera(c.camera);
        const std::vector<Projection> ours = camera.project_camera_points(front);
        for (const Projection& p : ours) REQUIRE(p.valid);
        double worst_cv = 0, worst_mrcal = 0;
        if (in_opencv(c.camera.lens.type)) {
            const std::vector<Vec2> cv_pixels = opencv_project_points(c.camera, front);
            for (std::size_t i = 0; i < front.size(); ++i) worst_cv = std::max(worst_cv, (ours[i].pixel - cv_pixels[i]).norm());
        }
        if (in_mrcal(c.camera.lens.type)) {
            // mrcal's own models also behind the camera, to 150 degrees: further out mrcal's
            // stereographic |p| + z cancels (libcam's does not; checked by hand below).
            const bool behind = lens_info(c.camera.lens.type).sees_behind_camera;
            const std::vector<Vec3> points = behind ? sample_points(c.camera, 150.0) : front;
            const std::vector<Projection> ours_all = camera.project_camera_points(points);
            const std::vector<Vec2> mrcal_pixels = mrcal_project_points(c.camera, points);
            for (std::size_t i = 0; i < points.size(); ++i) {
                REQUIRE(ours_all[i].valid);
                worst_mrcal = std::max(worst_mrcal, (ours_all[i].pixel - mrcal_pixels[i]).norm());
            }
        }
        CHECK(worst_cv <= kPixelTolerance);
        CHECK(worst_mrcal <= kPixelTolerance);
    }
}

TEST_CASE("CAHVOR gives the pixels mrcal's own projection tests record, and unprojects them back") {
    // mrcal's test/test-projections.py: these intrinsics (fx fy cx cy alpha beta r0 r1 r2)
    // and points, and the pixels mrcal recorded for them (to 1e-8 px).
    const Camera camera = real_camera(LensType::Cahvor, {-0.001, 0.002, -0.637, -0.002, 0.016}, {3942, 2172},
                                      {4842.918, 4842.771, 1970.528, 1085.302});
    const std::vector<Vec3> points = {{1.0, 2.0, 10.0}, {-1.1, 0.3, 1.0}, {-0.9, -1.5, 1.0}};
    const std::vector<Vec2> recorded = {
        {2143.17840406, 1442.93419919}, {-92.63813066, 1653.09646897}, {-249.83199315, -2606.46477164}};
    const PreparedCamera prepared(camera);
    for (std::size_t i = 0; i < points.size(); ++i) {
        INFO("point " << points[i].transpose());
        const Projection projection = prepared.project_camera_point(points[i]);
        REQUIRE(projection.valid);
        CHECK((projection.pixel - recorded[i]).norm() < 1e-7);
        const Unprojection ray = prepared.unproject(recorded[i]);
        REQUIRE(ray.valid);
        // The recorded pixels are rounded to 1e-8 px: about 1e-11 rad here.
        CHECK(angle_between(ray.direction, points[i]) < 1e-10);
    }
}

namespace {

// libcam's rays through a 61 x 41 grid over the camera's image, and how far mrcal's
// projection puts them from their pixels.
struct RaysThroughMrcal {
    std::size_t pixels = 0;
    std::vector<Vec2> with_ray;  // the grid pixels that have a ray
    std::vector<Vec3> directions;
    double worst_px = 0;
};

RaysThroughMrcal rays_through_mrcal(const Camera& camera) {
    RaysThroughMrcal out;
    const std::vector<Vec2> pixels = pixel_grid(camera.size, 61, 41);
    const std::vector<Unprojection> rays = PreparedCamera(camera).unproject(pixels);
    out.pixels = pixels.size();
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        if (!rays[i].valid) continue;
        out.with_ray.push_back(pixels[i]);
        out.directions.push_back(rays[i].direction);
    }
    REQUIRE(out.with_ray.size() > pixels.size() / 2);
    const std::vector<Vec2> back = mrcal_project_points(camera, out.directions);
    for (std::size_t i = 0; i < out.with_ray.size(); ++i) out.worst_px = std::max(out.worst_px, (back[i] - out.with_ray[i]).norm());
    return out;
}

}  // namespace

TEST_CASE("CAHVORE: libcam's rays reproject through mrcal_project onto their pixels (mrcal 2.2 has no unproject for it)", "[sweep]") {
    std::vector<LensCase> cases;
    for (const LensCase& c : lens_cases()) {
        if (c.camera.lens.type != LensType::Cahvore) continue;
        cases.push_back(c);
        // mrcal's three forms of chi: tan(L theta) / L, theta (L = 0), sin(L theta) / L.
        for (double linearity : {0.0, -0.3}) {
            LensCase other = c;
            other.camera.lens.coefficients.back() = linearity;
            other.name += " with linearity " + std::to_string(linearity);
            cases.push_back(other);
        }
    }
    REQUIRE(cases.size() >= 6);
    for (const LensCase& c : cases) {
        INFO(c.name);
        const RaysThroughMrcal through = rays_through_mrcal(c.camera);
        const double worst = through.worst_px;
        WARN(c.name << ": " << through.with_ray.size() << " of " << through.pixels
                    << " pixels have a ray; worst through mrcal_project " << worst << " px");
        CHECK(worst <= kPixelTolerance);
    }
}

namespace {

// A .cameramodel file of mrcal's, read by libcam.
Camera read_cameramodel(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return parse_cameramodel(text.str(), path.string());
}

}  // namespace

TEST_CASE("SPLINED_STEREOGRAPHIC: mrcal's splined calibrations, rays through mrcal_project and mrcal_unproject", "[real]") {
    const std::filesystem::path folder = real_cameras_folder("mrcal");
    if (!real_cameras_present(folder)) return;
    std::vector<LensCase> cases;
    for (const char* name : {"cam0.splined.cameramodel", "splined-0.cameramodel"}) {
        cases.push_back({name, read_cameramodel(folder / name)});
    }
    for (const LensCase& c : lens_cases()) {
        if (c.camera.lens.type == LensType::SplinedStereographic) cases.push_back(c);
    }
    for (const LensCase& c : cases) {
        INFO(c.name);
        REQUIRE(c.camera.lens.type == LensType::SplinedStereographic);
        const PreparedCamera camera(c.camera);
        // libcam's rays land on their pixels through mrcal's projection.
        const RaysThroughMrcal through = rays_through_mrcal(c.camera);
        const std::vector<Vec2>& with_ray = through.with_ray;
        const std::vector<Vec3>& directions = through.directions;
        const double worst = through.worst_px;
        const std::size_t pixels = through.pixels;
        // mrcal's own unprojection (converged to about 1e-8 px, its dogleg's tolerance):
        // the angle between its ray and libcam's. Near the image's edge mrcal can land on
        // another preimage, past the spline's grid, where its extrapolated edge patches
        // fold the image back onto itself: those rays are outside libcam's domain.
        const std::vector<Vec3> theirs = mrcal_unproject_pixels(c.camera, with_ray);
        const std::vector<Projection> theirs_here = camera.project_camera_points(theirs);
        double worst_angle = 0;
        int elsewhere = 0, unconverged = 0;
        for (std::size_t i = 0; i < with_ray.size(); ++i) {
            if (!theirs[i].allFinite()) {
                ++unconverged;
            } else if (!theirs_here[i].valid) {
                ++elsewhere;
            } else {
                worst_angle = std::max(worst_angle, angle_between(theirs[i], directions[i]));
            }
        }
        const double focal = c.camera.intrinsics.fx;
        WARN(c.name << ": " << with_ray.size() << " of " << pixels << " pixels have a ray; worst through "
                    << "mrcal_project " << worst << " px; mrcal_unproject's rays within " << worst_angle << " rad ("
                    << worst_angle * focal << " px at f) of libcam's; " << elsewhere
                    << " of mrcal's past the grid, " << unconverged << " not converged");
        CHECK(worst <= kPixelTolerance);
        CHECK(worst_angle * focal <= 1e-6);
        CHECK(elsewhere + unconverged <= static_cast<int>(with_ray.size()) / 20);
    }
}

TEST_CASE("FISHEYE beyond 90 degrees follows theta_d = theta (1 + k1 theta^2 + ... + k4 theta^8)") {
    const std::vector<double> k{0.01, -0.002, 0.0003, -0.00002};  // theta_d' > 0 up to pi
    const auto parameters = FisheyeLens<double>::parameters(k);
    REQUIRE(parameters.valid_radius == std::numbers::pi);
    for (double degrees : {60.0, 90.0, 100.0, 135.0, 170.0}) {
        const double theta = radians_from_degrees(degrees), phi = 0.7;
        const Vec3 point = 3.0 * Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        const double t2 = theta * theta;
        const double theta_d = theta * (1 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3]))));
        Vec2 m = Vec2::Zero();
        INFO(degrees);
        REQUIRE(FisheyeLens<double>::project(parameters, point, m));
        CHECK(std::abs(m.x() - theta_d * std::cos(phi)) < 1e-14);
        CHECK(std::abs(m.y() - theta_d * std::sin(phi)) < 1e-14);
    }
}

TEST_CASE("STEREOGRAPHIC stays accurate near the backward axis: m = 2 tan(theta / 2)") {
    const StereographicLens<double>::Parameters none;
    for (double degrees : {10.0, 120.0, 179.0, 179.999}) {
        const long double theta = static_cast<long double>(radians_from_degrees(degrees));
        const Vec3 point(double(std::sin(theta) * 0.6L), double(std::sin(theta) * -0.8L), double(std::cos(theta)));
        // The hand formula in long double, from the point as rounded to double.
        const long double rho = std::hypot(static_cast<long double>(point.x()), static_cast<long double>(point.y()));
        const long double half_tan = std::tan(std::atan2(rho, static_cast<long double>(point.z())) / 2);
        Vec2 m = Vec2::Zero();
        INFO(degrees);
        REQUIRE(StereographicLens<double>::project(none, point, m));
        CHECK(std::abs(m.x() / double(2 * half_tan * point.x() / rho) - 1) < 1e-15);
        CHECK(std::abs(m.y() / double(2 * half_tan * point.y() / rho) - 1) < 1e-15);
    }
}

TEST_CASE("Points behind the camera and on its plane are flagged, not mirrored as cv::projectPoints does") {
    const Camera camera = lens_camera(LensType::OpenCv5, {-0.05, 0.01, 2e-4, -3e-4, 0.001});
    const std::vector<Vec3> points{{0.3, -0.2, 0.0}, {0.3, -0.2, -1.0}, {0.0, 0.0, -2.0}, {0.0, 0.0, 0.0}};
    for (const Projection& p : PreparedCamera(camera).project_camera_points(points)) CHECK_FALSE(p.valid);
    // What OpenCV does instead: (x, y, -1) lands where (-x, -y, 1) does.
    const std::vector<Vec2> cv_pixels = opencv_project_points(camera, {{0.3, -0.2, -1.0}, {-0.3, 0.2, 1.0}});
    CHECK((cv_pixels[0] - cv_pixels[1]).norm() < 1e-9);

    for (const LensInfo& info : lens_models()) {
        if (!info.sees_behind_camera) {
            const Camera c = lens_camera(info.type, std::vector<double>(static_cast<std::size_t>(info.num_coefficients), 0.0));
            INFO(info.name);
            for (const Projection& p : PreparedCamera(c).project_camera_points(points)) CHECK_FALSE(p.valid);
        }
    }
    struct Expectation {
        LensType type;
        Vec3 point;
        bool valid;
    };
    const Expectation expectations[] = {
        {LensType::Fisheye, {0, 0, -1}, false},          {LensType::Fisheye, {0, 0, 0}, false},
        {LensType::Fisheye, {1, 0.5, 0}, true},          {LensType::Fisheye, {1, 0.5, -0.4}, true},
        {LensType::Stereographic, {0, 0, -1}, false},    {LensType::Stereographic, {0, 0, 0}, false},
        {LensType::Stereographic, {1e-3, 0, -1}, true},  {LensType::Lonlat, {0, 1, 0}, false},
        {LensType::Lonlat, {0, 0, -1}, true},            {LensType::Lonlat, {0.2, -1, -0.3}, true},
        {LensType::Latlon, {-1, 0, 0}, false},           {LensType::Latlon, {0, 0, -1}, true},
        {LensType::Cylindrical, {0, -2, 0}, false},      {LensType::Cylindrical, {0, 0, -1}, true},
        {LensType::Cylindrical, {1e-170, 1, 0}, false},  // x^2 + z^2 underflows: on the Y axis as far as double tells
    };
    for (const Expectation& e : expectations) {
        const Camera c = lens_camera(e.type, std::vector<double>(static_cast<std::size_t>(lens_info(e.type).num_coefficients), 0.0));
        INFO(lens_info(e.type).name << " " << e.point.transpose());
        CHECK(PreparedCamera(c).project_camera_point(e.point).valid == e.valid);
    }
}

TEST_CASE("The fold-over radius matches the roots worked by hand") {
    const auto opencv8 = [](std::vector<double> k) { return OpenCv8Lens<double>::valid_radius(k); };
    // d = r (1 + k1 r^2): d' = 1 + 3 k1 r^2 = 0.
    CHECK(OpenCv4Lens<double>::valid_radius(std::vector<double>{-0.5, 0, 0, 0}) == Approx(std::sqrt(1 / 1.5)).epsilon(1e-14));
    // d' = 1 + 3 k1 s + 5 k2 s^2: the smaller root.
    const double k1 = -0.3, k2 = 0.02;
    const double s = (-3 * k1 - std::sqrt(9 * k1 * k1 - 20 * k2)) / (10 * k2);
    CHECK(OpenCv4Lens<double>::valid_radius(std::vector<double>{k1, k2, 1e-3, 1e-3}) == Approx(std::sqrt(s)).epsilon(1e-14));
    // d = r / (1 + k4 r^2): d' = (1 - k4 s) / Q^2 = 0 at s = 1 / k4.
    CHECK(opencv8({0, 0, 0, 0, 0, 0.5, 0, 0}) == Approx(std::sqrt(2.0)).epsilon(1e-14));
    // k4 < 0: d' > 0 throughout, but Q = 1 + k4 s reaches 0 at s = -1 / k4.
    CHECK(opencv8({0, 0, 0, 0, 0, -0.25, 0, 0}) == Approx(2.0).epsilon(1e-14));
    // Barrel-free lenses never fold over.
    CHECK(std::isinf(OpenCv5Lens<double>::valid_radius(std::vector<double>{0.1, 0.01, 0, 0, 0.001})));
    // FISHEYE: 1 + 3 k1 theta^2 = 0, and never beyond pi.
    CHECK(FisheyeLens<double>::valid_radius(std::vector<double>{-0.2, 0, 0, 0}) == Approx(std::sqrt(1 / 0.6)).epsilon(1e-14));
    CHECK(FisheyeLens<double>::valid_radius(std::vector<double>{0, 0, 0, 0}) == std::numbers::pi);

    // Projection flags the points past the radius.
    const auto lens = OpenCv4Lens<double>::parameters(std::vector<double>{-0.5, 0, 0, 0});
    Vec2 m = Vec2::Zero();
    CHECK(OpenCv4Lens<double>::project(lens, Vec3(0.81, 0, 1), m));
    CHECK_FALSE(OpenCv4Lens<double>::project(lens, Vec3(0.82, 0, 1), m));
    CHECK_FALSE(OpenCv4Lens<double>::project(lens, Vec3(0, -5, 1), m));
}

namespace {

// dm/d(coefficients) against central differences in long double; the worst error,
// relative to each column's size, into `worst`.
// The step moves m by about 1e-7 of max(1, |m|) at the analytic slope (a coefficient of a
// high power of the radius, as Blender's polynomial in millimetres has, needs a far
// smaller step than 1e-7 itself), and each perturbed lens has its domain worked out again,
// as a camera with those coefficients would.
template <class ModelLong, class Parameters, class Jacobian>
void check_coefficient_jacobian(const Parameters& lens_long, const Vec3& point, const Jacobian& d_coefficients, double& worst) {
    Eigen::Matrix<long double, 2, 1> m = Eigen::Matrix<long double, 2, 1>::Zero();
    REQUIRE(ModelLong::project(lens_long, point.template cast<long double>(), m));
    const long double m_scale = std::max(1.0L, m.cwiseAbs().maxCoeff());
    const auto with_domain = [](Parameters lens) {
        std::vector<double> rounded(static_cast<std::size_t>(lens.coefficients.size()));
        for (std::size_t i = 0; i < rounded.size(); ++i) rounded[i] = static_cast<double>(lens.coefficients(static_cast<Eigen::Index>(i)));
        lens.valid_radius = ModelLong::parameters(rounded).valid_radius;
        return lens;
    };
    for (int j = 0; j < ModelLong::num_coefficients; ++j) {
        const long double speed = d_coefficients.col(j).cwiseAbs().maxCoeff() / m_scale;
        const long double h = 1e-7L * (speed > 1 ? 1 / speed : 1.0L);
        Parameters plus = lens_long, minus = lens_long;
        plus.coefficients(j) += h;
        minus.coefficients(j) -= h;
        plus = with_domain(plus);
        minus = with_domain(minus);
        Eigen::Matrix<long double, 2, 1> m_plus = Eigen::Matrix<long double, 2, 1>::Zero(), m_minus = m_plus;
        REQUIRE(ModelLong::project(plus, point.template cast<long double>(), m_plus));
        REQUIRE(ModelLong::project(minus, point.template cast<long double>(), m_minus));
        const Eigen::Matrix<long double, 2, 1> numeric = (m_plus - m_minus) / (2 * h);
        const double column_scale = std::max(1.0, d_coefficients.col(j).cwiseAbs().maxCoeff());
        const long double difference = (numeric - d_coefficients.col(j).template cast<long double>()).cwiseAbs().maxCoeff();
        worst = std::max(worst, double(difference) / column_scale);
    }
}

// Analytic Jacobians in double against central differences of the same model in long double.
template <class Model, class ModelLong>
void check_jacobians(const Camera& camera, const std::vector<Vec3>& points) {
    constexpr int N = Model::num_coefficients;
    const auto lens = Model::parameters(camera.lens.coefficients);
    const auto lens_long = ModelLong::parameters(camera.lens.coefficients);
    using Vec3L = Eigen::Matrix<long double, 3, 1>;
    using Vec2L = Eigen::Matrix<long double, 2, 1>;
    const long double h = 1e-7L;
    double worst_point = 0, worst_coefficient = 0;
    for (const Vec3& point : points) {
        Vec2 m = Vec2::Zero();
        Eigen::Matrix<double, 2, 3> d_point;
        Eigen::Matrix<double, 2, N> d_coefficients;
        REQUIRE(Model::project(lens, point, m, &d_point, &d_coefficients));
        const double scale = std::max(1.0, d_point.cwiseAbs().maxCoeff());
        for (int j = 0; j < 3; ++j) {
            Vec3L plus = point.template cast<long double>(), minus = plus;
            const long double step = h * std::max(1.0L, std::abs(plus(j)));
            plus(j) += step;
            minus(j) -= step;
            Vec2L m_plus = Vec2L::Zero(), m_minus = Vec2L::Zero();
            REQUIRE(ModelLong::project(lens_long, plus, m_plus));
            REQUIRE(ModelLong::project(lens_long, minus, m_minus));
            const Vec2L numeric = (m_plus - m_minus) / (2 * step);
            worst_point = std::max(worst_point, double((numeric - d_point.col(j).template cast<long double>()).cwiseAbs().maxCoeff()) / scale);
        }
        if constexpr (N > 0) check_coefficient_jacobian<ModelLong>(lens_long, point, d_coefficients, worst_coefficient);
    }
    CHECK(worst_point < 1e-8);
    CHECK(worst_coefficient < 1e-8);
}

// The same Jacobian by forward-mode automatic differentiation through the model's own
// formula, evaluated in ceres::Jet.
template <class Model, class ModelJet>
void check_against_jet(const Camera& camera, const std::vector<Vec3>& points) {
    using Jet = ceres::Jet<double, 3>;
    const auto lens = Model::parameters(camera.lens.coefficients);
    const auto lens_jet = ModelJet::parameters(camera.lens.coefficients);
    double worst = 0;
    for (const Vec3& point : points) {
        Vec2 m = Vec2::Zero();
        Eigen::Matrix<double, 2, 3> d_point;
        REQUIRE(Model::project(lens, point, m, &d_point));
        const Eigen::Matrix<Jet, 3, 1> point_jet(Jet(point.x(), 0), Jet(point.y(), 1), Jet(point.z(), 2));
        Eigen::Matrix<Jet, 2, 1> m_jet = Eigen::Matrix<Jet, 2, 1>::Zero();
        REQUIRE(ModelJet::project(lens_jet, point_jet, m_jet));
        for (int i = 0; i < 2; ++i) {
            CHECK(std::abs(m_jet(i).a - m(i)) <= 1e-15 * std::max(1.0, std::abs(m(i))));
            worst = std::max(worst, (m_jet(i).v.transpose() - d_point.row(i)).cwiseAbs().maxCoeff() /
                                        std::max(1.0, d_point.cwiseAbs().maxCoeff()));
        }
    }
    CHECK(worst < 1e-13);
}

}  // namespace

TEST_CASE("The fold-over radius is the same on every call: more lenses than the per-thread memo holds, two threads") {
    // Worked by hand as above; six lenses in turn, so that the memo (4 entries) evicts.
    struct HandRadius {
        LensType type;
        std::vector<double> k;
        double radius;
    };
    const double k1 = -0.3, k2 = 0.02;
    const std::vector<HandRadius> lenses{
        {LensType::OpenCv4, {-0.5, 0, 0, 0}, std::sqrt(1 / 1.5)},
        {LensType::OpenCv4, {k1, k2, 1e-3, 1e-3}, std::sqrt((-3 * k1 - std::sqrt(9 * k1 * k1 - 20 * k2)) / (10 * k2))},
        {LensType::OpenCv8, {0, 0, 0, 0, 0, 0.5, 0, 0}, std::sqrt(2.0)},
        {LensType::OpenCv8, {0, 0, 0, 0, 0, -0.25, 0, 0}, 2.0},
        {LensType::Fisheye, {-0.2, 0, 0, 0}, std::sqrt(1 / 0.6)},
        {LensType::Fisheye, {0, 0, 0, 0}, std::numbers::pi},
    };
    const auto sweep = [&lenses](int rounds) {
        int wrong = 0;
        for (int round = 0; round < rounds; ++round) {
            for (const HandRadius& lens : lenses) {
                const double radius = valid_radius_of(Lens{lens.type, lens.k});
                wrong += std::abs(radius - lens.radius) <= 1e-14 * lens.radius ? 0 : 1;
            }
        }
        return wrong;
    };
    int wrong_on_thread = -1;
    std::thread other([&] { wrong_on_thread = sweep(50); });
    CHECK(sweep(50) == 0);
    other.join();
    CHECK(wrong_on_thread == 0);
}

TEST_CASE("Jacobians match central differences in long double and ceres::Jet", "[sweep]") {
    for (const LensCase& c : lens_cases()) {
        INFO(c.name);
        std::vector<Vec3> points = sample_points(c.camera, lens_info(c.camera.lens.type).sees_behind_camera ? 170.0 : 89.5);
        points.resize(std::min<std::size_t>(points.size(), 400));
        if (c.camera.lens.type == LensType::Fisheye) points.emplace_back(1e-5, -2e-5, 1.0);  // the series near the axis
        visit_lens_model<double>(c.camera.lens.type, [&]<class Model>() {
            check_jacobians<Model, LensInScalar<Model, long double>>(c.camera, points);
            check_against_jet<Model, LensInScalar<Model, ceres::Jet<double, 3>>>(c.camera, points);
        });
    }
}

TEST_CASE("Every model compiles and agrees in float") {
    for (const LensCase& c : lens_cases()) {
        INFO(c.name);
        const std::vector<Vec3> points = sample_points(c.camera, 89.5);
        visit_lens_model<double>(c.camera.lens.type, [&]<class Model>() {
            using ModelFloat = LensInScalar<Model, float>;
            {
                const auto lens = Model::parameters(c.camera.lens.coefficients);
                const auto lens_float = ModelFloat::parameters(c.camera.lens.coefficients);
                for (std::size_t i = 0; i < points.size(); i += 7) {
                    Vec2 m = Vec2::Zero();
                    Eigen::Vector2f m_float = Eigen::Vector2f::Zero();
                    REQUIRE(Model::project(lens, points[i], m));
                    if (!ModelFloat::project(lens_float, points[i].template cast<float>(), m_float)) continue;  // at the domain's edge in float
                    CHECK((m_float.template cast<double>() - m).norm() <= 1e-5 * std::max(1.0, m.norm()));
                }
            }
        });
    }
}

TEST_CASE("a lens with the wrong number of coefficients is refused and never read past its end") {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {500.0, 500.0, 319.5, 239.5, 0.0};
    camera.lens.type = LensType::OpenCv8;
    camera.lens.coefficients = {0.1, 0.01, 0.0};  // OPENCV8 takes 8
    // Refused when the camera is prepared, before any point or pixel is computed.
    REQUIRE_THROWS_WITH(PreparedCamera(camera),
                        Catch::Matchers::Contains("dist") && Catch::Matchers::Contains("8 coefficients, got 3"));
    REQUIRE_THROWS_AS(Unprojector<double>(camera), InvalidArgument);
    REQUIRE_THROWS_AS(Projector<double>(camera), InvalidArgument);
}

TEST_CASE("The simplest equal lens drops only coefficients that are exactly 0, within the model's family") {
    using L = LensType;
    CHECK(simplest_equal_lens({L::OpenCv8, {0.1, 0.2, 0.3, 0.4, 0, 0, 0, 0}}) == Lens{L::OpenCv4, {0.1, 0.2, 0.3, 0.4}});
    CHECK(simplest_equal_lens({L::OpenCv8, {0.1, 0.2, 0.3, 0.4, 0.5, 0, 0, 0}}) ==
          Lens{L::OpenCv5, {0.1, 0.2, 0.3, 0.4, 0.5}});
    CHECK(simplest_equal_lens({L::OpenCv8, {0, 0, 0, 0, 0, 0, 0, 0}}) == Lens{L::Pinhole, {}});
    // k6 alone keeps OPENCV8: k4..k6 go together; a tiny value is not 0.
    CHECK(simplest_equal_lens({L::OpenCv8, {0.1, 0, 0, 0, 0, 0, 0, 1e-300}}).type == L::OpenCv8);
    CHECK(simplest_equal_lens({L::Mei, {1.2, 0, 0, 0, 0}}) == Lens{L::Ucm, {1.2}});
    // FISHEYE is the smallest of its family; the other fisheye's coefficients are not its prefix.
    CHECK(simplest_equal_lens({L::Fisheye, {0, 0, 0, 0}}).type == L::Fisheye);
    CHECK(simplest_equal_lens({L::RadTanThinPrismFisheye, std::vector<double>(12, 0.0)}).type ==
          L::RadTanThinPrismFisheye);
    // PanoTools' polynomial on the equidistant projection without its odd terms a and c,
    // theta (1 + b theta^2 + k2 theta^4), is FISHEYE's theta (1 + k1 theta^2 + k2 theta^4).
    CHECK(simplest_equal_lens({L::EquidistantRadial, {0, 0.1, 0, -0.02}}) == Lens{L::Fisheye, {0.1, -0.02, 0, 0}});
    CHECK(simplest_equal_lens({L::EquidistantRadial, {0, 0, 0, 0}}) == Lens{L::Fisheye, {0, 0, 0, 0}});
    CHECK(simplest_equal_lens({L::EquidistantRadial, {0, 0.1, 1e-300, 0}}).type == L::EquidistantRadial);
    CHECK(simplest_equal_lens({L::EquidistantRadial, {-0.01, 0.1, 0, 0}}).type == L::EquidistantRadial);
}

TEST_CASE("EQUIDISTANT_RADIAL without odd terms projects as the FISHEYE it is given as, worked by hand") {
    // A ray 0.7 rad off the axis, in direction (0.6, 0.8): theta 0.7, so the distorted
    // angle is 0.7 (1 + 0.1 * 0.49 - 0.02 * 0.2401) = 0.7309386 and the pixel
    // (cx + f 0.7309386 * 0.6, cy + f 0.7309386 * 0.8).
    Camera camera;
    camera.size = {1000, 1000};
    camera.intrinsics = {400.0, 400.0, 499.5, 499.5, 0.0};
    camera.lens = {LensType::EquidistantRadial, {0, 0.1, 0, -0.02}};
    const Camera fisheye = [&] {
        Camera c = camera;
        c.lens = simplest_equal_lens(camera.lens);
        return c;
    }();
    const double theta = 0.7;
    const Vec3 ray(std::sin(theta) * 0.6, std::sin(theta) * 0.8, std::cos(theta));
    const double distorted = 0.7 * (1 + 0.1 * 0.49 - 0.02 * 0.2401);
    const Vec2 expected(499.5 + 400.0 * distorted * 0.6, 499.5 + 400.0 * distorted * 0.8);
    for (const Camera& c : {camera, fisheye}) {
        const Projection p = PreparedCamera(c).project_camera_points(std::vector<Vec3>{ray}).at(0);
        CHECK(p.valid);
        CHECK((p.pixel - expected).norm() < 1e-9);
    }
}
