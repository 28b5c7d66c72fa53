// lensfun's lens database: lensfun's own regression vectors (its test
// tests/test_modifier_regression.cpp, the expected pixels stored in
// real-data/vectors/lensfun-test-modifier-regression.json, SOURCES.md sections 8 and 9)
// reproduced through the reader and libcam's lens models, and small databases written
// here for the reader's choices and refusals.

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/detail/lensfun_format.hpp"
#include "libcam/lens/lens_models.hpp"
#include "error_message.hpp"
#include "lensfun_reference.hpp"
#include "real_cameras.hpp"
#include "temp_dir.hpp"

using namespace libcam;

namespace {

// The message of the error of type E a call must throw.
template <class E, class Read>
std::string error_message_of(Read&& read) {
    try {
        read();
    } catch (const E& error) {
        return error.what();
    }
    FAIL("no error of the expected type");
    return {};
}

// One case of lensfun's vectors through the reader (lensfun_reference.hpp), each point
// to `tolerance` on either axis.
void check_case(const nlohmann::json& vectors, const std::string& name, double tolerance) {
    if (vectors.is_null()) return;
    const nlohmann::json* c = test::lensfun_vector_case(vectors, name);
    REQUIRE(c != nullptr);
    if (!test::real_data_present(test::lensfun_case_database(*c))) return;
    const test::LensfunCaseMiss miss = test::lensfun_case_miss(*c);
    INFO(name << ": libcam's pixels " << miss.worst_px << " px from lensfun's");
    CHECK(miss.points == (*c)["x"].size());
    CHECK(miss.worst_px < tolerance);
}

}  // namespace

TEST_CASE("lensfun's regression vectors through the reader: poly3, poly5 and ptlens to 1e-3 px", "[io][lensfun]") {
    const nlohmann::json vectors = test::lensfun_vectors();
    for (const char* name : {"verify_dist_poly3", "verify_dist_poly5", "verify_dist_ptlens"}) check_case(vectors, name, 1e-3);
}

TEST_CASE("lensfun's regression vectors through the reader: the equisolid fisheye seen rectilinear, to 0.1 px",
          "[io][lensfun]") {
    check_case(test::lensfun_vectors(), "verify_geom_fisheye_rectlinear", 0.1);
}

TEST_CASE("lensfun's spline between calibrated focal lengths is its cubic Hermite, worked by hand", "[io][lensfun]") {
    // Four values on a line stay on it; the ends use the one-sided difference.
    CHECK(detail::lensfun_interpolate(1.0, 2.0, 3.0, 4.0, 0.25) == Approx(2.25).epsilon(1e-15));
    // y = t^2 sampled at -1, 0, 1, 2: tangents (1 - 1) / 2 = 0 and (4 - 0) / 2 = 2, so at
    // t = 0.5: (0.5) 0 + (0.125) 0 + (0.5) 1 + (-0.125) 2 = 0.25.
    CHECK(detail::lensfun_interpolate(1.0, 0.0, 1.0, 4.0, 0.5) == Approx(0.25).epsilon(1e-15));
    // Without neighbours: tangents y3 - y2 = 1, so the line 2 + t.
    CHECK(detail::lensfun_interpolate(std::nullopt, 2.0, 3.0, std::nullopt, 0.3) == Approx(2.3).epsilon(1e-15));
}

namespace {

constexpr const char* kSmallDatabase = R"(<!DOCTYPE lensdatabase SYSTEM "lensfun-database.dtd">
<lensdatabase version="2">
    <lens>
        <maker>Maker</maker>
        <model>Zoom 10-20mm</model>
        <mount>M</mount>
        <cropfactor>2</cropfactor>
        <aspect-ratio>4:3</aspect-ratio>
        <calibration>
            <distortion model="poly5" focal="10" k1="0.01" k2="-0.002"/>
            <distortion model="poly5" focal="20" k1="0.02" k2="0.001"/>
        </calibration>
    </lens>
    <lens>
        <maker>Maker</maker>
        <model>Zoom 10-20mm Mark II</model>
        <mount>M</mount>
        <focal value="12"/>
        <calibration>
            <distortion model="poly3" focal="12" k1="-0.01"/>
        </calibration>
    </lens>
    <lens>
        <maker>Maker</maker>
        <model>Odd 24mm</model>
        <mount>M</mount>
        <focal value="24"/>
        <calibration>
            <distortion model="ptlens" focal="24" a="0.01" b="-0.02" c="0.003"/>
        </calibration>
    </lens>
</lensdatabase>
)";

}  // namespace

TEST_CASE("lensfun: a poly5 lens at a calibrated focal length is OpenCV's k1 k2 by lensfun's rescaling, by hand",
          "[io][lensfun]") {
    const test::TempDir dir;
    const auto path = write_file(dir, "db.xml", kSmallDatabase);
    ReadOptions options;
    options.lens = "zoom 10-20mm";  // any case; exact, though "Mark II" also contains it
    options.focal_mm = 20.0;
    options.size = ImageSize{400, 300};
    const CameraSet set = read_camera_set(path, std::nullopt, options);
    REQUIRE(set.format == CameraFormat::Lensfun);
    REQUIRE(set.cameras.size() == 1);
    const Camera& camera = set.cameras[0].file.camera;
    // f_r = 20 mm (poly5), pixels: 20 hypot(400, 300) 2 / hypot(36, 24) = 20000 / hypot(36, 24).
    const double f = 20.0 * 500.0 * 2.0 / std::hypot(36.0, 24.0);
    CHECK(camera.intrinsics.fx == Approx(f).epsilon(1e-14));
    CHECK(camera.intrinsics.cx == 199.5);
    CHECK(camera.intrinsics.cy == 149.5);
    // Half the shorter side of a crop-2 4:3 sensor: hypot(36, 24) / 2 / (5 / 3) / 2 mm.
    const double s = 20.0 / (std::hypot(36.0, 24.0) / 2.0 / (5.0 / 3.0) / 2.0);
    REQUIRE(camera.lens.type == LensType::OpenCv4);
    CHECK(camera.lens.coefficients[0] == Approx(0.02 * s * s).epsilon(1e-14));
    CHECK(camera.lens.coefficients[1] == Approx(0.001 * s * s * s * s).epsilon(1e-14));
}

TEST_CASE("lensfun: the reader says which lens, focal length and size it needs, in one line", "[io][lensfun]") {
    const test::TempDir dir;
    const auto path = write_file(dir, "db.xml", kSmallDatabase);
    ReadOptions options;
    options.size = ImageSize{400, 300};
    CHECK(error_message_of<InvalidArgument>([&] { read_camera_file(path, {}, std::nullopt, options); }) ==
          path.string() + ": holds 3 lenses: name one (--lens \"MODEL\"), e.g. 'Zoom 10-20mm'");
    options.lens = "zoom";
    CHECK(error_message_of<InvalidArgument>([&] { read_camera_file(path, {}, std::nullopt, options); }) ==
          path.string() + ": 'zoom' names 2 lenses ('Zoom 10-20mm', 'Zoom 10-20mm Mark II'): give more of the name");
    options.lens = "Zoom 10-20mm";
    CHECK(error_message_of<InvalidArgument>([&] { read_camera_file(path, {}, std::nullopt, options); }) ==
          path.string() + ": lens 'Zoom 10-20mm': is calibrated at several focal lengths: give the focal length "
                          "(--focal MM)");
    options.lens = "mark ii";  // a prime: its own focal length
    options.size.reset();
    CHECK(error_message_of<InvalidArgument>([&] { read_camera_file(path, {}, std::nullopt, options); }) ==
          path.string() + ": lens 'Zoom 10-20mm Mark II': a lens database records no image size; give the size "
                          "(--image-size WxH)");
    options.size = ImageSize{400, 300};
    const Camera prime = read_camera_file(path, {}, std::nullopt, options).camera;
    // poly3 f_r = 12 (1 - k1) = 12.12 mm on a crop-1 3:2 sensor (lensfun's defaults).
    CHECK(prime.intrinsics.fx == Approx(12.12 * 500.0 / std::hypot(36.0, 24.0)).epsilon(1e-14));
    const double s = 12.12 / 12.0;
    CHECK(prime.lens.coefficients[0] == Approx(-0.01 * s * s / std::pow(1.01, 3)).epsilon(1e-14));
    options.crop_factor = 0.9;  // a sensor bigger than the one calibrated
    CHECK_THROWS_AS(read_camera_file(path, {}, std::nullopt, options), NotRepresentable);
}

TEST_CASE("lensfun: an entry of a model lensfun does not know is refused, naming the lens and the model",
          "[io][lensfun]") {
    // lensfun's parser refuses the whole database on such a model (database.cpp at 0.3.95:
    // "Bad attribute value"); skipping the entry would interpolate the others instead.
    const test::TempDir dir;
    ReadOptions options;
    options.lens = "Zoom 10-20mm";
    options.focal_mm = 15.0;
    options.size = ImageSize{400, 300};
    const auto refusal = [&](const std::string& from, const std::string& to) {
        std::string text = kSmallDatabase;
        text.replace(text.find(from), from.size(), to);
        const auto path = write_file(dir, "db.xml", text);
        return test::file_error_of([&] { read_camera_file(path, {}, std::nullopt, options); });
    };
    const std::string path = (dir / "db.xml").string();
    const std::string as_lensfun = " (read as lensfun database XML, by its extension .xml and its keys)";
    CHECK(refusal(R"(<distortion model="poly5" focal="20")", R"(<distortion model="poly7" focal="20")") ==
          path + ": line 11: lens 'Zoom 10-20mm' <distortion> model: 'poly7' is not one of lensfun's (none, poly3, poly5, "
              "ptlens, acm)" + as_lensfun);
    CHECK(refusal("        </calibration>\n    </lens>\n    <lens>",
                  "            <tca model=\"quadratic\" focal=\"10\"/>\n        </calibration>\n    </lens>\n    <lens>") ==
          path + ": line 12: lens 'Zoom 10-20mm' <tca> model: 'quadratic' is not one of lensfun's (none, linear, poly3, acm)" + as_lensfun);
    CHECK(refusal("        </calibration>\n    </lens>\n    <lens>",
                  "            <vignetting model=\"cos4\" focal=\"10\" aperture=\"4\" distance=\"10\"/>\n"
                  "        </calibration>\n    </lens>\n    <lens>") ==
          path + ": line 12: lens 'Zoom 10-20mm' <vignetting> model: 'cos4' is not one of lensfun's (none, pa, acm)" + as_lensfun);
}

TEST_CASE("PTLENS: its formula and its Jacobian on the axis, worked by hand", "[io][lensfun]") {
    // m = u (1 + c r + b r^2 + a r^3): at u = (0.3, 0.4), r = 0.5.
    const Lens lens{LensType::Ptlens, {0.2, -0.1, 0.05}};
    Camera camera;
    camera.size = {100, 100};
    camera.intrinsics = {1.0, 1.0, 0.0, 0.0, 0.0};
    camera.lens = lens;
    const PreparedCamera prepared(camera);
    const double factor = 1.0 + 0.05 * 0.5 - 0.1 * 0.25 + 0.2 * 0.125;
    const Projection p = prepared.project_camera_point(Vec3(0.3, 0.4, 1.0));
    REQUIRE(p.valid);
    CHECK(p.pixel.x() == Approx(0.3 * factor).epsilon(1e-15));
    CHECK(p.pixel.y() == Approx(0.4 * factor).epsilon(1e-15));
    // On the axis d m / d u is the identity: c |u| u has derivative 0 there.
    Eigen::Matrix<double, 2, 3> jacobian;
    Vec2 m;
    const auto parameters = PtlensLens<double>::parameters(lens.coefficients);
    REQUIRE(PtlensLens<double>::project(parameters, Vec3(0.0, 0.0, 2.0), m, &jacobian));
    CHECK(m.norm() == 0.0);
    CHECK(jacobian(0, 0) == 0.5);
    CHECK(jacobian(1, 1) == 0.5);
    CHECK(jacobian(0, 1) == 0.0);
    CHECK(jacobian(0, 2) == 0.0);
}

namespace {

// One lens entry as lensfun's database holds it: its projection, the crop factor and
// aspect ratio it was calibrated on, and one distortion calibration at `focal`.
struct LensfunEntry {
    std::string type;  // fisheye, equisolid, stereographic
    double crop = 1.0;
    double aspect = 1.5;
    std::string model;  // poly3, poly5, ptlens
    std::vector<double> terms;
    double focal = 0.0;
};

// lensfun's own steps for one pixel (x, y) of the corrected image, projected rectilinear
// (EnableDistortionCorrection and EnableProjectionTransform(LF_RECTILINEAR), for a
// camera of crop factor `crop`), transcribed from its sources at the snapshot SOURCES.md
// names, in double where lensfun computes in float: the source pixel it reads.
//   modifier.cpp, lfModifier::lfModifier: NormScale, CenterX, CenterY;
//   database.cpp: the real focal length of a calibration without one;
//   mod-coord.cpp, rescale_polynomial_coefficients and ApplyGeometryDistortion; the
//   callbacks in their order (geometry at priority 500, then distortion at 750):
//   Rect_ERect, ERect_<lens type>, Dist_<model>.
Vec2 lensfun_source(const LensfunEntry& lens, double crop, int width, int height, double x, double y) {
    const std::vector<double>& t = lens.terms;
    const double real_focal = lens.model == "ptlens" ? lens.focal * (1 - t[0] - t[1] - t[2])
                              : lens.model == "poly3" ? lens.focal * (1 - t[0])
                                                      : lens.focal;
    const double w = width - 1.0, h = height - 1.0;
    const double norm_scale = std::hypot(36.0, 24.0) / crop / std::hypot(w + 1.0, h + 1.0) / real_focal;
    const double centre_x = w / 2.0 * norm_scale, centre_y = h / 2.0 * norm_scale;
    double px = x * norm_scale - centre_x, py = y * norm_scale - centre_y;
    // Rect_ERect.
    const double lon = std::atan2(px, 1.0), lat = std::atan2(py, std::sqrt(1 + px * px));
    // ERect_<lens type>.
    if (lens.type == "equisolid") {
        const double k1 = std::sqrt(2.0 / (1 + std::cos(lat) * std::cos(lon)));
        px = k1 * std::cos(lat) * std::sin(lon);
        py = k1 * std::sin(lat);
    } else if (lens.type == "stereographic") {
        const double ksp = 2.0 / (1.0 + std::cos(lat) * std::cos(lon));
        px = ksp * std::cos(lat) * std::sin(lon);
        py = ksp * std::sin(lat);
    } else {  // fisheye
        double theta = -lat + std::numbers::pi / 2, xx = lon;
        const double s = std::sin(theta);
        const double vx = s * std::sin(xx), vy = std::cos(theta);
        const double r = std::sqrt(vx * vx + vy * vy);
        theta = std::atan2(r, s * std::cos(xx));
        px = theta * vx / r;
        py = theta * vy / r;
    }
    // rescale_polynomial_coefficients, then Dist_<model>.
    const double hugin_scale_mm = std::hypot(36.0, 24.0) / lens.crop / std::hypot(lens.aspect, 1.0) / 2.0;
    const double s = real_focal / hugin_scale_mm;
    const double r2 = px * px + py * py, r = std::sqrt(r2);
    double factor = 1.0;
    if (lens.model == "ptlens") {
        const double d = 1 - t[0] - t[1] - t[2];
        const double a = t[0] * std::pow(s, 3) / std::pow(d, 4), b = t[1] * s * s / std::pow(d, 3), c = t[2] * s / (d * d);
        factor = a * r2 * r + b * r2 + c * r + 1;
    } else if (lens.model == "poly3") {
        const double k1 = t[0] * s * s / std::pow(1 - t[0], 3);
        factor = k1 * r2 + 1;
    } else {  // poly5
        factor = 1 + t[0] * s * s * r2 + t[1] * std::pow(s, 4) * r2 * r2;
    }
    return {(px * factor + centre_x) / norm_scale, (py * factor + centre_y) / norm_scale};
}

// The entry's camera read by libcam, against lensfun's steps over a grid of the corrected
// rectilinear image: the largest miss in pixels.
double worst_against_lensfun(const std::filesystem::path& database, const std::string& name, const LensfunEntry& lens,
                             double crop, int width, int height, LensType expected_model) {
    ReadOptions options;
    options.lens = name;
    options.focal_mm = lens.focal;
    options.crop_factor = crop;
    options.size = ImageSize{width, height};
    const Camera camera = read_camera_file(database, {}, std::nullopt, options).camera;
    CHECK(camera.lens.type == expected_model);
    const PreparedCamera prepared(camera);
    double worst = 0.0;
    for (int i = 0; i <= 10; ++i) {
        for (int j = 0; j <= 10; ++j) {
            const double x = (width - 1.0) * i / 10.0, y = (height - 1.0) * j / 10.0;
            const Vec2 libcam = test::lensfun_source_pixel(prepared, x, y);
            const Vec2 expected = lensfun_source(lens, crop, width, height, x, y);
            INFO(name << " at (" << x << ", " << y << "): libcam " << libcam.transpose() << ", lensfun " << expected.transpose());
            REQUIRE(std::isfinite(libcam.x()));
            worst = std::max(worst, (libcam - expected).norm());
        }
    }
    return worst;
}

}  // namespace

// lensfun distorts a fisheye's own projection: its geometry step first, then the distortion
// polynomial on the projected radius (EQUIDISTANT_RADIAL, EQUISOLID_RADIAL,
// STEREOGRAPHIC_RADIAL). Its regression vectors hold no fisheye with distortion, so the
// expected pixels are lensfun's steps transcribed above, on the real lenses of
// slr-pentax.xml and mil-olympus.xml at a calibrated focal length.
TEST_CASE("lensfun: real fisheyes with distortion against lensfun's own steps, to 1e-6 px", "[io][lensfun]") {
    const auto pentax = test::real_data_path("lensfun/data/db/slr-pentax.xml");
    const auto olympus = test::real_data_path("lensfun/data/db/mil-olympus.xml");
    if (!test::real_data_present(pentax) || !test::real_data_present(olympus)) return;
    const LensfunEntry fish_10_17{"equisolid", 1.538, 1.5, "ptlens", {-0.03518, 0.12586, -0.09198}, 10.0};
    CHECK(worst_against_lensfun(pentax, "smc Pentax-DA Fish-Eye 10-17mm f/3.5-4.5 ED IF", fish_10_17, 1.538, 3000, 2000,
                                LensType::EquisolidRadial) < 1e-6);
    const LensfunEntry zuiko_8{"equisolid", 2.0, 4.0 / 3.0, "poly3", {-0.00531}, 8.0};
    CHECK(worst_against_lensfun(olympus, "Olympus M.Zuiko Digital ED 8mm f/1.8 Fisheye Pro", zuiko_8, 2.0, 4000, 3000,
                                LensType::EquisolidRadial) < 1e-6);
    const LensfunEntry body_cap_9{"stereographic", 2.0, 4.0 / 3.0, "poly3", {-0.03111}, 9.0};
    CHECK(worst_against_lensfun(olympus, "Olympus 9mm Body Cap Lens Fisheye", body_cap_9, 2.0, 4000, 3000,
                                LensType::StereographicRadial) < 1e-6);
}

// The equidistant fisheye with odd terms (as lensfun's Nikon 10.5 mm and Sigma 10 mm
// entries are) and poly5 on an equisolid lens, in a database written here.
TEST_CASE("lensfun: an equidistant fisheye with ptlens and an equisolid one with poly5 against lensfun's steps",
          "[io][lensfun]") {
    const test::TempDir dir;
    const auto path = write_file(dir, "fisheyes.xml", R"(<lensdatabase version="2">
    <lens>
        <maker>Maker</maker>
        <model>Fisheye 10.5mm</model>
        <mount>M</mount>
        <type>fisheye</type>
        <cropfactor>1.5</cropfactor>
        <calibration>
            <distortion model="ptlens" focal="10.5" a="0.012" b="-0.035" c="0.02"/>
        </calibration>
    </lens>
    <lens>
        <maker>Maker</maker>
        <model>Equisolid 8mm</model>
        <mount>M</mount>
        <type>equisolid</type>
        <cropfactor>2</cropfactor>
        <aspect-ratio>4:3</aspect-ratio>
        <calibration>
            <distortion model="poly5" focal="8" k1="-0.01" k2="0.002"/>
        </calibration>
    </lens>
</lensdatabase>
)");
    const LensfunEntry equidistant{"fisheye", 1.5, 1.5, "ptlens", {0.012, -0.035, 0.02}, 10.5};
    CHECK(worst_against_lensfun(path, "Fisheye 10.5mm", equidistant, 1.5, 1500, 1000, LensType::EquidistantRadial) < 1e-6);
    const LensfunEntry equisolid{"equisolid", 2.0, 4.0 / 3.0, "poly5", {-0.01, 0.002}, 8.0};
    CHECK(worst_against_lensfun(path, "Equisolid 8mm", equisolid, 2.0, 1200, 900, LensType::EquisolidRadial) < 1e-6);
}

TEST_CASE("EQUIDISTANT_RADIAL, EQUISOLID_RADIAL, STEREOGRAPHIC_RADIAL: the formula and the Jacobian on the axis, by hand",
          "[io][lensfun]") {
    // At (0.3, 0.4, 1): theta = atan(0.5), the projected radius r = P(theta), and
    // m = r (1 + c r + b r^2 + a r^3 + k2 r^4) (0.6, 0.8).
    const double theta = std::atan(0.5);
    const std::pair<LensType, double> projections[] = {{LensType::EquidistantRadial, theta},
                                                       {LensType::EquisolidRadial, 2 * std::sin(theta / 2)},
                                                       {LensType::StereographicRadial, 2 * std::tan(theta / 2)}};
    for (const auto& [type, r] : projections) {
        INFO(lens_info(type).name);
        Camera camera;
        camera.size = {100, 100};
        camera.intrinsics = {1.0, 1.0, 0.0, 0.0, 0.0};
        camera.lens = {type, {0.2, -0.1, 0.05, 0.03}};
        const double factor = 1.0 + 0.05 * r - 0.1 * r * r + 0.2 * r * r * r + 0.03 * r * r * r * r;
        const Projection p = PreparedCamera(camera).project_camera_point(Vec3(0.3, 0.4, 1.0));
        REQUIRE(p.valid);
        CHECK(p.pixel.x() == Approx(0.6 * r * factor).epsilon(1e-14));
        CHECK(p.pixel.y() == Approx(0.8 * r * factor).epsilon(1e-14));
        // On the axis every projection is theta to first order and c |u| u has derivative 0:
        // d m / d point = diag(1 / z, 1 / z), 0 along z.
        Eigen::Matrix<double, 2, 3> jacobian;
        Vec2 m;
        const bool valid = visit_lens_model<double>(type, [&]<class Model>() {
            return Model::project(Model::parameters(camera.lens.coefficients), Vec3(0.0, 0.0, 2.0), m, &jacobian);
        });
        REQUIRE(valid);
        CHECK(m.norm() == 0.0);
        CHECK(jacobian(0, 0) == Approx(0.5).epsilon(1e-15));
        CHECK(jacobian(1, 1) == Approx(0.5).epsilon(1e-15));
        CHECK(jacobian(0, 1) == 0.0);
        CHECK(jacobian(0, 2) == 0.0);
    }
}
