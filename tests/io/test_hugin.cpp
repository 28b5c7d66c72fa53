// Hugin's .pto: image lines read as cameras, checked against Hugin itself. pano_trafo
// (Debian's hugin-tools) maps a panorama's pixel to an image's (-r) by Hugin's own
// transforms; the panorama written here is a rectilinear camera whose rays are worked by
// hand, so the image pixel it names is the libcam camera's projection of that ray.
// Skipped, with a warning, where pano_trafo is absent.

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "error_message.hpp"
#include "temp_dir.hpp"
#include "shell_output.hpp"

using namespace libcam;

namespace {

using libcam::test::shell_output;

bool pano_trafo_present() {
    if (std::system("command -v pano_trafo > /dev/null 2>&1") == 0) return true;
    WARN("skipped: no pano_trafo (Debian's hugin-tools) on the PATH");
    return false;
}

// A rectilinear panorama of W x H pixels and `fov` degrees across, as a ray per pixel:
// Hugin's pixels are OpenCV's (the centre at ((W - 1) / 2, (H - 1) / 2)) and its focal
// length (W / 2) / tan(fov / 2).
constexpr double kPanoWidth = 1200, kPanoHeight = 900, kPanoFov = 80;

Vec3 panorama_ray(const Vec2& pixel) {
    const double f = kPanoWidth / 2.0 / std::tan(kPanoFov / 2.0 * std::numbers::pi / 180.0);
    return {(pixel.x() - (kPanoWidth - 1) / 2.0) / f, (pixel.y() - (kPanoHeight - 1) / 2.0) / f, 1.0};
}

std::string project_file(const std::string& image_line) {
    std::ostringstream out;
    out << "# hugin project file\n"
        << "p f0 w" << kPanoWidth << " h" << kPanoHeight << " v" << kPanoFov << " n\"TIFF_m\"\n"
        << "m i0\n"
        << image_line << "\n";
    return out.str();
}

// Every panorama pixel of `pixels` through pano_trafo -r (the image's pixel) against the
// camera libcam reads from the same file.
void check_against_pano_trafo(const std::string& image_line, double tolerance) {
    const test::TempDir dir;
    const auto path = write_file(dir, "project.pto", project_file(image_line));
    const std::vector<Vec2> pixels = {{0, 0}, {1199, 899}, {100, 800}, {599.5, 449.5}, {900, 120}, {333, 444}};
    std::string input;
    for (const Vec2& p : pixels) input += std::to_string(p.x()) + " " + std::to_string(p.y()) + "\n";
    const auto points = write_file(dir, "points.txt", input);
    std::istringstream output(shell_output("pano_trafo -r '" + path.string() + "' 0 < '" + points.string() + "'"));
    const PreparedCamera camera(read_camera_file(path).camera);
    for (const Vec2& pixel : pixels) {
        Vec2 hugin;
        REQUIRE(output >> hugin.x() >> hugin.y());
        const Projection projected = camera.project(std::vector<Vec3>{panorama_ray(pixel)})[0];
        INFO(image_line << "\npanorama " << pixel.transpose() << ": Hugin " << hugin.transpose() << ", libcam "
                        << projected.pixel.transpose());
        REQUIRE(projected.valid);
        CHECK((projected.pixel - hugin).norm() < tolerance);
    }
}

}  // namespace

// pano_trafo prints six decimals: 1e-3 px is what it can say.
TEST_CASE("Hugin: a rectilinear image's a b c d e against pano_trafo", "[io][hugin]") {
    if (!pano_trafo_present()) return;
    check_against_pano_trafo("i w1500 h1000 f0 v70 a0.01 b-0.02 c0.005 d12.5 e-7 g0 t0 r0 p0 y0 n\"a.jpg\"", 1e-3);
    check_against_pano_trafo("i w1000 h1500 f0 v50 a0 b-0.01 c0 d0 e0 g0 t0 r0 p0 y0 n\"portrait.jpg\"", 1e-3);
}

TEST_CASE("Hugin: a fisheye image's b against pano_trafo", "[io][hugin]") {
    if (!pano_trafo_present()) return;
    check_against_pano_trafo("i w1600 h1200 f3 v150 a0 b0.02 c0 d3 e-4 g0 t0 r0 p0 y0 n\"fisheye.jpg\"", 1e-3);
    check_against_pano_trafo("i w1200 h1200 f21 v170 a0 b0 c0 d0 e0 g0 t0 r0 p0 y0 n\"equisolid.jpg\"", 1e-3);
}

// PanoTools distorts a fisheye's own projection: a b c on the equidistant, equisolid and
// stereographic radius (EQUIDISTANT_RADIAL, EQUISOLID_RADIAL, STEREOGRAPHIC_RADIAL).
TEST_CASE("Hugin: fisheye images' a b c against pano_trafo", "[io][hugin]") {
    if (!pano_trafo_present()) return;
    const std::pair<const char*, LensType> lines[] = {
        {"i w1600 h1200 f3 v150 a0.01 b-0.03 c0.02 d3 e-4 g0 t0 r0 p0 y0 n\"equidistant.jpg\"", LensType::EquidistantRadial},
        {"i w1200 h1200 f21 v170 a-0.02 b0.01 c0.015 d-5 e2 g0 t0 r0 p0 y0 n\"equisolid.jpg\"", LensType::EquisolidRadial},
        {"i w1500 h1000 f10 v160 a0.005 b0.02 c-0.01 d0 e0 g0 t0 r0 p0 y0 n\"stereographic.jpg\"",
         LensType::StereographicRadial}};
    for (const auto& [line, type] : lines) {
        const test::TempDir dir;
        CHECK(read_camera_file(write_file(dir, "project.pto", project_file(line))).camera.lens.type == type);
        check_against_pano_trafo(line, 1e-3);
    }
}

TEST_CASE("Hugin: image lines' models, links and refusals", "[io][hugin]") {
    const test::TempDir dir;
    const auto path = write_file(dir, "project.pto",
                                 project_file("i w1500 h1000 f0 v70 a0.01 b-0.02 c0.005 d0 e0 n\"a.jpg\"\n"
                                              "i w1500 h1000 f0 v=0 a=0 b=0 c=0 d0 e0 n\"b.jpg\"\n"
                                              "i w1500 h1000 f0 v70 b-0.02 n\"c.jpg\""));
    const CameraSet set = read_camera_set(path);
    REQUIRE(set.format == CameraFormat::HuginPto);
    REQUIRE(set.cameras.size() == 3);
    CHECK(set.cameras[0].name == "a.jpg");
    CHECK(set.cameras[0].file.camera.lens.type == LensType::Ptlens);
    CHECK(set.cameras[1].file.camera.lens == set.cameras[0].file.camera.lens);
    CHECK(set.cameras[1].file.camera.intrinsics.fx == set.cameras[0].file.camera.intrinsics.fx);
    // b alone: OpenCV's k1 = b s^2 / d with s = F / 500, F = 750 / tan(35 deg), d = 1.02.
    const double focal = 750.0 / std::tan(35.0 * std::numbers::pi / 180.0);
    const Camera& c = set.cameras[2].file.camera;
    REQUIRE(c.lens.type == LensType::OpenCv4);
    CHECK(c.lens.coefficients[0] == Approx(-0.02 * (focal / 500) * (focal / 500) / 1.02).epsilon(1e-14));
    CHECK(c.intrinsics.fx == Approx(focal * 1.02).epsilon(1e-14));

    const auto sheared = write_file(dir, "sheared.pto", project_file("i w10 h10 f0 v50 g0.1 t0"));
    CHECK_THROWS_AS(read_camera_set(sheared), NotRepresentable);
    const auto orthographic = write_file(dir, "ortho.pto", project_file("i w10 h10 f8 v50"));
    CHECK_THROWS_AS(read_camera_set(orthographic), NotRepresentable);
    const auto bad = write_file(dir, "bad.pto", project_file("i w10 h10 f0 v7x"));
    try {
        read_camera_set(bad);
        FAIL("no error");
    } catch (const FileError& error) {
        CHECK(std::string(error.what()) == bad.string() + ": line 4: v: must be a finite number, got '7x'");
    }
}

namespace {

// An equirectangular panorama of 360 x 180 degrees (p f2 v360): pano_trafo maps an image's
// pixel to the panorama's pixel of its direction, longitude (x - (W - 1) / 2) / F to the
// right and latitude (y - (H - 1) / 2) / F downwards, F = W / (2 pi).
constexpr double kSphereWidth = 3600, kSphereHeight = 1800;

Vec3 sphere_direction(const Vec2& pixel) {
    const double focal = kSphereWidth / (2.0 * std::numbers::pi);
    const double longitude = (pixel.x() - (kSphereWidth - 1) / 2.0) / focal;
    const double latitude = (pixel.y() - (kSphereHeight - 1) / 2.0) / focal;
    return {std::cos(latitude) * std::sin(longitude), std::sin(latitude), std::cos(latitude) * std::cos(longitude)};
}

// The panorama's direction of what a camera's ray sees: the ray itself from the panorama's
// centre; from a translated camera (Hugin's mosaic mode), the point where it meets the
// mosaic plane, here z = 1 (Tpy = Tpp = 0).
Vec3 seen_direction(const Ray& ray) {
    if (ray.origin.isZero()) return ray.direction;
    const double along = (1.0 - ray.origin.z()) / ray.direction.z();
    return (ray.origin + along * ray.direction).normalized();
}

}  // namespace

// Each image's pixels through pano_trafo (image to panorama) against libcam's ray of the
// same pixel, turned by the pose into the panorama's world: the direction pano_trafo's
// panorama pixel has. pano_trafo prints six decimals, 2e-9 rad on this panorama; an image
// with a b c is mapped through Hugin's approximate inverse of its polynomial (pano_trafo
// and pano_trafo -r disagree by 2e-4 px on turned.jpg's corner), 2e-7 rad here.
TEST_CASE("Hugin: each image's y p r and TrX TrY TrZ against pano_trafo on an equirectangular panorama",
          "[io][hugin]") {
    if (!pano_trafo_present()) return;
    const std::vector<std::string> images = {
        "i w1000 h800 f0 v60 a0.01 b-0.02 c0.005 d12 e-7 g0 t0 r25 p20 y30 n\"turned.jpg\"",
        "i w1200 h1200 f3 v150 a0 b0.02 c0 d3 e-4 g0 t0 r-40 p-60 y-150 n\"fisheye.jpg\"",
        "i w900 h600 f0 v50 a0 b-0.01 c0 d0 e0 g0 t0 r10 p85 y170 n\"zenith.jpg\"",
        "i w1000 h800 f0 v60 a0 b0 c0 d0 e0 g0 t0 r5 p-8 y20 TrX0.1 TrY-0.05 TrZ0.2 Tpy0 Tpp0 n\"moved.jpg\"",
    };
    std::string project = "# hugin project file\np f2 w3600 h1800 v360 n\"TIFF_m\"\nm i0\n";
    for (const std::string& line : images) project += line + "\n";
    const test::TempDir dir;
    const auto path = write_file(dir, "sphere.pto", project);
    const CameraSet set = read_camera_set(path);
    REQUIRE(set.cameras.size() == images.size());
    std::ostringstream worst;  // each image's largest angle, for the log
    for (std::size_t index = 0; index < images.size(); ++index) {
        double largest = 0.0;
        const Camera& camera = set.cameras[index].file.camera;
        const double w = static_cast<double>(camera.size.width), h = static_cast<double>(camera.size.height);
        const std::vector<Vec2> pixels = {{(w - 1) / 2, (h - 1) / 2}, {10, 20}, {w - 30, h - 12}, {0.3 * w, 0.8 * h},
                                          {0.9 * w, 0.1 * h}};
        std::string input;
        for (const Vec2& p : pixels) input += std::to_string(p.x()) + " " + std::to_string(p.y()) + "\n";
        const auto points = write_file(dir, "points.txt", input);
        std::istringstream output(
            shell_output("pano_trafo '" + path.string() + "' " + std::to_string(index) + " < '" + points.string() + "'"));
        const PreparedCamera prepared(camera);
        for (const Vec2& pixel : pixels) {
            Vec2 panorama;
            REQUIRE(output >> panorama.x() >> panorama.y());
            const Ray ray = prepared.ray(pixel);
            REQUIRE(ray.valid);
            const double angle = angle_between(seen_direction(ray), sphere_direction(panorama));
            INFO(images[index] << "\npixel " << pixel.transpose() << ": panorama " << panorama.transpose());
            CHECK(angle < 1e-6);
            largest = std::max(largest, angle);
        }
        worst << " " << set.cameras[index].name << " " << largest;
    }
    WARN("largest angle between libcam's direction and pano_trafo's, rad:" << worst.str());
}

TEST_CASE("Hugin: the pose's axes, worked by hand", "[io][hugin]") {
    const test::TempDir dir;
    const auto path = write_file(dir, "pose.pto",
                                 project_file("i w100 h100 f0 v90 y90 p0 r0 n\"right.jpg\"\n"
                                              "i w100 h100 f0 v90 y0 p90 r0 n\"up.jpg\"\n"
                                              "i w100 h100 f0 v90 y0 p0 r90 n\"rolled.jpg\"\n"
                                              "i w100 h100 f0 v90 TrX1 TrY2 TrZ3 n\"moved.jpg\""));
    const CameraSet set = read_camera_set(path);
    const auto forward = [&](std::size_t i) { return set.cameras[i].file.camera.pose.R.transpose() * Vec3::UnitZ(); };
    const auto right = [&](std::size_t i) { return set.cameras[i].file.camera.pose.R.transpose() * Vec3::UnitX(); };
    // World axes: x right (yaw 90), y down, z the panorama's centre (yaw 0, pitch 0).
    CHECK((forward(0) - Vec3(1, 0, 0)).norm() < 1e-15);  // yaw 90 looks right
    CHECK((forward(1) - Vec3(0, -1, 0)).norm() < 1e-15);  // pitch 90 looks up
    CHECK((right(2) - Vec3(0, 1, 0)).norm() < 1e-15);     // roll 90 turns the image's x down
    // TrX TrY TrZ: centre (TrX, TrY, -TrZ), the image unturned.
    CHECK((set.cameras[3].file.camera.pose.centre() - Vec3(1, 2, -3)).norm() < 1e-15);
    CHECK(set.cameras[3].file.camera.pose.R == Mat3::Identity());
    const auto bad = write_file(dir, "bad.pto", project_file("i w10 h10 f0 v50 y1e999"));
    CHECK_THAT(test::file_error_of([&] { (void)read_camera_set(bad); }), Catch::EndsWith("y: must be a finite number, got '1e999'"));
}
