// Hugin's .pto: image lines read as cameras, checked against Hugin itself. pano_trafo
// (Debian's hugin-tools) maps a panorama's pixel to an image's (-r) by Hugin's own
// transforms; the panorama written here is a rectilinear camera whose rays are worked by
// hand, so the image pixel it names is the libcam camera's projection of that ray.
// Skipped, with a warning, where pano_trafo is absent.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "temp_dir.hpp"

using namespace libcam;

namespace {

std::string run(const std::string& command) {
    std::FILE* pipe = popen(command.c_str(), "r");
    REQUIRE(pipe != nullptr);
    std::string output;
    char buffer[65536];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) output.append(buffer, n);
    const int status = pclose(pipe);
    INFO(command);
    REQUIRE(status == 0);
    return output;
}

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
    std::istringstream output(run("pano_trafo -r '" + path.string() + "' 0 < '" + points.string() + "'"));
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
