// The `libcam` program, run as a user runs it (tests/cli_runner.hpp): the two worked
// example cameras through `libcam rays --json`, `libcam convert` and its file round trips,
// the fov axes, the pixel origin, and bad input.
//
// Every expected value is worked by hand from the look-at formula
//     d = alpha u + beta v + w,  alpha = tan(fov/2) (2x - W + 1) / W,  beta = tan(fov/2) (2y - H + 1) / H
// (rows counted upward, w along the gaze) and from docs/conventions.md
// (K = [W/(2 tan_x), 0, (W-1)/2; 0, H/(2 tan_y), (H-1)/2; 0, 0, 1], rows of R = camera
// axes x right (u), y down (-v), z forward (gaze), t = -R eye), never from the program.

#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "support.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using libcam::test::CliResult;
using libcam::test::read_whole_file;
using libcam::test::run_libcam;
using libcam::test::TempDir;
using libcam::test::write_whole_file;
using nlohmann::json;
using Args = std::vector<std::string>;
namespace fs = std::filesystem;

const double kSqrt2 = std::sqrt(2.0);

Args operator+(Args a, const Args& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

std::string num(double x) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.17g", x);
    return buffer;
}

std::string vec_arg(const Vector3d& v) { return num(v.x()) + "," + num(v.y()) + "," + num(v.z()); }

std::string show(const MatrixXd& m) {
    std::ostringstream out;
    out.precision(17);
    out << m;
    return out.str();
}

std::string joined(const Args& args) {
    std::string text = "libcam";
    for (const std::string& a : args) text += " '" + a + "'";
    return text;
}

// Runs a command that must succeed quietly and print JSON.
json run_json(const Args& args) {
    const CliResult r = run_libcam(args);
    INFO(joined(args) << "\n" << r.describe());
    REQUIRE(r.exit_code == 0);
    REQUIRE(r.err.empty());
    json j;
    REQUIRE_NOTHROW(j = json::parse(r.out));
    return j;
}

// Runs a command that writes a file with -o and prints nothing.
void run_to_file(const Args& args, const fs::path& file) {
    const Args full = args + Args{"-o", file.string()};
    const CliResult r = run_libcam(full);
    INFO(joined(full) << "\n" << r.describe());
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.empty());
    CHECK(r.err.empty());
    REQUIRE(fs::is_regular_file(file));
}

MatrixXd mat(const json& j, int rows, int cols) {
    INFO(j.dump());
    REQUIRE(j.is_array());
    REQUIRE(static_cast<int>(j.size()) == rows);
    MatrixXd m(rows, cols);
    for (int r = 0; r < rows; ++r) {
        REQUIRE(j[r].is_array());
        REQUIRE(static_cast<int>(j[r].size()) == cols);
        for (int c = 0; c < cols; ++c) {
            REQUIRE(j[r][c].is_number());
            m(r, c) = j[r][c].get<double>();
        }
    }
    return m;
}

Vector3d vec3(const json& j) {
    INFO(j.dump());
    REQUIRE(j.is_array());
    REQUIRE(j.size() == 3);
    for (const json& x : j) REQUIRE(x.is_number());
    return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

// Largest |a - b| / max(1, |a|, |b|) over the entries.
double rel_diff(const MatrixXd& a, const MatrixXd& b) {
    REQUIRE(a.rows() == b.rows());
    REQUIRE(a.cols() == b.cols());
    double worst = 0.0;
    for (Eigen::Index i = 0; i < a.size(); ++i) {
        const double x = a.data()[i], y = b.data()[i];
        worst = std::max(worst, std::abs(x - y) / std::max({1.0, std::abs(x), std::abs(y)}));
    }
    return worst;
}

#define CHECK_CLOSE(actual, expected, tol)                                                        \
    do {                                                                                          \
        const MatrixXd actual_ = (actual);                                                        \
        const MatrixXd expected_ = (expected);                                                    \
        INFO(#actual " =\n" << show(actual_) << "\nexpected =\n" << show(expected_));             \
        CHECK(rel_diff(actual_, expected_) <= (tol));                                             \
    } while (false)

// Rodrigues' formula, to check the printed rvec against the printed R.
Matrix3d rodrigues(const Vector3d& r) {
    const double theta = r.norm();
    if (theta == 0.0) return Matrix3d::Identity();
    const Vector3d k = r / theta;
    Matrix3d cross;
    cross << 0, -k.z(), k.y(), k.z(), 0, -k.x(), -k.y(), k.x(), 0;
    return std::cos(theta) * Matrix3d::Identity() + (1 - std::cos(theta)) * k * k.transpose() +
           std::sin(theta) * cross;
}

// `libcam rays --json` for the given pixels; returns the "rays" array.
json rays(const Args& camera, const Args& pixels, const std::string& origin = "bottom-left") {
    const json j = run_json(Args{"rays", "--json", "--pixel-origin", origin} + camera + Args{"--pixels"} + pixels);
    REQUIRE(j.contains("rays"));
    REQUIRE(j["rays"].is_array());
    REQUIRE(j["rays"].size() == pixels.size());
    return j["rays"];
}

// The ray must start at the eye and run along `expected` (any length), by both paths.
void check_ray(const json& ray, const Vector3d& expected, const Vector3d& eye) {
    INFO("ray " << ray.dump());
    const Vector3d e = expected.normalized();
    REQUIRE(ray.at("valid") == true);
    const Vector3d d = vec3(ray.at("direction"));
    const Vector3d s = vec3(ray.at("direction_look_at"));
    CHECK(std::abs(d.norm() - 1.0) < 1e-12);
    CHECK(std::abs(s.norm() - 1.0) < 1e-12);
    CHECK_CLOSE(d, e, 1e-12);
    CHECK_CLOSE(s, e, 1e-12);
    REQUIRE(ray.at("angle_rad").is_number());
    CHECK(ray.at("angle_rad").get<double>() >= 0.0);
    CHECK(ray.at("angle_rad").get<double>() < 1e-12);
    CHECK_CLOSE(vec3(ray.at("origin")), eye, 1e-12);
}

void check_pixel(const json& ray, double x, double y) {
    INFO("ray " << ray.dump());
    REQUIRE(ray.at("pixel").size() == 2);
    CHECK(ray.at("pixel")[0].get<double>() == x);
    CHECK(ray.at("pixel")[1].get<double>() == y);
}

const Args kSquare90 = {"--fov", "90", "--size", "3x3"};

}  // namespace

// ---------------------------------------------------------------------------------------
// 1. The two worked example cameras, and the look-at formula on any basis.

TEST_CASE("rays: example camera 1, at the origin looking along -z") {
    // Basis: u = (1,0,0), v = (0,1,0), w = (0,0,-1) (left-handed, w along the gaze).
    // (The worked example says the left-handed w faces "away from the gaze" by mistake;
    // its own value w = (0,0,-1) points along the gaze (-z), which is what is tested here.)
    const Vector3d eye(0, 0, 0);
    for (const Args& look : {Args{"--gaze", "0,0,-1"}, Args{"--target", "0,0,-1"}}) {
        INFO("look " << look[0]);
        const json r = rays(kSquare90 + Args{"--eye", "0,0,0", "--up", "0,1,0"} + look, {"1,1", "0,0", "-0.5,-0.5"});
        // Pixel (1,1): alpha = tan45 (2*1 - 3 + 1)/3 = 0, beta = 0, d = w = (0,0,-1).
        check_pixel(r[0], 1, 1);
        check_ray(r[0], Vector3d(0, 0, -1), eye);
        // Pixel (0,0): alpha = beta = (2*0 - 3 + 1)/3 = -2/3, d = (-2/3, -2/3, -1).
        // (The worked example labels this second f(t) "at (1,1)" by mistake; it is the ray at (0,0).)
        check_pixel(r[1], 0, 0);
        check_ray(r[1], Vector3d(-2.0 / 3, -2.0 / 3, -1), eye);
        // The lower-left corner of the field of view is pixel (-0.5,-0.5) (the image
        // spans [-0.5, W-0.5]): alpha = (2(-0.5) - 3 + 1)/3 = -1, beta = -1, d = (-1,-1,-1).
        check_pixel(r[2], -0.5, -0.5);
        check_ray(r[2], Vector3d(-1, -1, -1), eye);
    }
}

TEST_CASE("rays: example camera 2, eye (0,5,5) looking at the origin") {
    // Basis: w = ((0,0,0) - (0,5,5))/|..| = (0,-1,-1)/sqrt2;
    //      u = w x up = (1,0,0)/sqrt2 -> (1,0,0);  v = u x w = (0,1,-1)/sqrt2.
    const Vector3d eye(0, 5, 5);
    const Vector3d u(1, 0, 0), v = Vector3d(0, 1, -1) / kSqrt2, w = Vector3d(0, -1, -1) / kSqrt2;
    const json r = rays(kSquare90 + Args{"--eye", "0,5,5", "--target", "0,0,0", "--up", "0,1,0"},
                        {"1,1", "0,0", "1,2.5"});
    // Pixel (1,1): alpha = beta = 0, d = w = (0,-1,-1)/sqrt2.
    check_ray(r[0], Vector3d(0, -1, -1) / kSqrt2, eye);
    check_ray(r[0], w, eye);
    // Pixel (0,0): alpha = beta = -2/3,
    //   d = -2/3 (1,0,0) - 2/3 (0,1,-1)/sqrt2 + (0,-1,-1)/sqrt2
    //     = (-2/3, -sqrt2/3 - 1/sqrt2, sqrt2/3 - 1/sqrt2)      (2/(3 sqrt2) = sqrt2/3).
    // (The worked example's f(t) at (0,0) prints x = 0 by mistake (it is -2t/3) and
    // y = 5 - 2t/3 - t/sqrt2 (it is 5 - sqrt2 t/3 - t/sqrt2); its d above is right.)
    const Vector3d d00(-2.0 / 3, -kSqrt2 / 3 - 1 / kSqrt2, kSqrt2 / 3 - 1 / kSqrt2);
    check_ray(r[1], d00, eye);
    check_ray(r[1], -2.0 / 3 * u - 2.0 / 3 * v + w, eye);
    {
        // f(t) = eye + t d with the look-at formula's unnormalised d, at t = 3: x = -2 (not 0),
        // y = 5 - sqrt2 - 3/sqrt2 (not 5 - 2 - 3/sqrt2), z = 5 + sqrt2 - 3/sqrt2.
        const double t = 3.0;
        const Vector3d point = vec3(r[1]["origin"]) + t * d00.norm() * vec3(r[1]["direction"]);
        CHECK_CLOSE(point, Vector3d(-2, 5 - kSqrt2 - 3 / kSqrt2, 5 + kSqrt2 - 3 / kSqrt2), 1e-12);
    }
    // The top centre of the field of view: alpha factor 0, beta factor 1, i.e. pixel
    // (1, 2.5): (2*1 - 3 + 1)/3 = 0, (2*2.5 - 3 + 1)/3 = 1;
    //   d = (0,1,-1)/sqrt2 + (0,-1,-1)/sqrt2 = (0, 0, -sqrt2).
    check_pixel(r[2], 1, 2.5);
    check_ray(r[2], Vector3d(0, 0, -kSqrt2), eye);
}

TEST_CASE("rays: the look-at formula on a general orthonormal basis") {
    // Pixel (1,1) -> w;  pixel (0,0) -> -2/3 u - 2/3 v + w.
    // The basis: w random (the gaze), v random orthogonal to w (given as --up), u = w x v,
    // so that v = u x w as in example camera 2 and {u, v, w} is orthonormal.
    for (int trial = 0; trial < 6; ++trial) {
        const Vector3d w = libcam::test::random_unit();
        Vector3d a;
        do a = libcam::test::random_unit();
        while (std::abs(a.dot(w)) > 0.9);
        const Vector3d v = (a - a.dot(w) * w).normalized();
        const Vector3d u = w.cross(v);
        const Vector3d eye = libcam::test::random_vector(50.0);
        INFO("trial " << trial << " u " << show(u.transpose()) << " v " << show(v.transpose()) << " w "
                      << show(w.transpose()) << " eye " << show(eye.transpose()));
        REQUIRE(std::abs(u.norm() - 1) < 1e-14);
        REQUIRE(std::abs(u.cross(w).dot(v) - 1) < 1e-14);
        const json r = rays(kSquare90 + Args{"--eye", vec_arg(eye), "--gaze", vec_arg(w), "--up", vec_arg(v)},
                            {"1,1", "0,0"});
        check_ray(r[0], w, eye);
        check_ray(r[1], -2.0 / 3 * u - 2.0 / 3 * v + w, eye);
        // The same camera given by a target one unit along the gaze.
        const json t = rays(kSquare90 + Args{"--eye", vec_arg(eye), "--target", vec_arg(eye + 7 * w), "--up",
                                             vec_arg(v)},
                            {"0,0"});
        check_ray(t[0], -2.0 / 3 * u - 2.0 / 3 * v + w, eye);
    }
}

// ---------------------------------------------------------------------------------------
// 2. convert: the JSON and its round trips.

namespace {

struct ConvertCase {
    const char* name;
    Args flags;
};

// Checks the structure every libcam JSON has, and P = K [R | t], rvec ~ R.
void check_json_structure(const json& j, long width, long height) {
    INFO(j.dump(2));
    for (const char* key : {"model", "image_size", "K", "dist", "R", "t", "rvec", "P", "fov_deg", "eye", "gaze", "up"}) {
        INFO("key " << key);
        CHECK(j.contains(key));
    }
    CHECK(j.at("model") == "PINHOLE");
    CHECK(j.at("image_size") == json::array({width, height}));
    REQUIRE(j.at("dist").is_array());
    CHECK(j.at("dist").empty());
    const MatrixXd K = mat(j.at("K"), 3, 3);
    const MatrixXd R = mat(j.at("R"), 3, 3);
    const Vector3d t = vec3(j.at("t"));
    Eigen::Matrix<double, 3, 4> Rt;
    Rt << R, t;
    CHECK_CLOSE(mat(j.at("P"), 3, 4), K * Rt, 1e-12);
    CHECK_CLOSE(rodrigues(vec3(j.at("rvec"))), R, 1e-12);
    CHECK_CLOSE(R * R.transpose(), Matrix3d::Identity(), 1e-12);
    CHECK(R.determinant() == Approx(1.0).epsilon(0).margin(1e-12));
    REQUIRE(j.at("fov_deg").is_object());
    for (const char* axis : {"horizontal", "vertical", "diagonal"}) {
        INFO("fov_deg." << axis);
        CHECK(j.at("fov_deg").contains(axis));
    }
}

}  // namespace

TEST_CASE("convert: JSON of example camera 1 (3x3, fov 90, at the origin looking along -z)") {
    const json j = run_json(Args{"convert"} + kSquare90 + Args{"--eye", "0,0,0", "--gaze", "0,0,-1", "--up", "0,1,0"});
    check_json_structure(j, 3, 3);
    // fx = fy = W/(2 tan 45) = 3/2 = 1.5, cx = cy = (W-1)/2 = 1.
    Matrix3d K;
    K << 1.5, 0, 1, 0, 1.5, 1, 0, 0, 1;
    CHECK_CLOSE(mat(j["K"], 3, 3), K, 1e-12);
    // R rows: u = (1,0,0), -v = (0,-1,0), gaze = (0,0,-1); t = -R eye = 0.
    Matrix3d R;
    R << 1, 0, 0, 0, -1, 0, 0, 0, -1;
    CHECK_CLOSE(mat(j["R"], 3, 3), R, 1e-12);
    CHECK_CLOSE(vec3(j["t"]), Vector3d::Zero(), 1e-12);
    // P = K [R | 0] = [[1.5, 0, -1, 0], [0, -1.5, -1, 0], [0, 0, -1, 0]].
    Eigen::Matrix<double, 3, 4> P;
    P << 1.5, 0, -1, 0, 0, -1.5, -1, 0, 0, 0, -1, 0;
    CHECK_CLOSE(mat(j["P"], 3, 4), P, 1e-12);
    // fov: tan of the half angle is 1 on each axis, so 90 and 90; on the diagonal the
    // half tangent is hypot(1, 1) = sqrt2, so 2 atan(sqrt2) = 109.4712206... degrees.
    CHECK(j["fov_deg"]["horizontal"].get<double>() == Approx(90.0).epsilon(1e-13));
    CHECK(j["fov_deg"]["vertical"].get<double>() == Approx(90.0).epsilon(1e-13));
    CHECK(j["fov_deg"]["diagonal"].get<double>() ==
          Approx(2.0 * std::atan(kSqrt2) * 180.0 / std::numbers::pi).epsilon(1e-13));
    CHECK_CLOSE(vec3(j["eye"]), Vector3d(0, 0, 0), 1e-12);
    CHECK_CLOSE(vec3(j["gaze"]), Vector3d(0, 0, -1), 1e-12);
    CHECK_CLOSE(vec3(j["up"]), Vector3d(0, 1, 0), 1e-12);
}

TEST_CASE("convert: JSON of example camera 2 (eye 0,5,5 looking at the origin)") {
    const json j = run_json(Args{"convert"} + kSquare90 + Args{"--eye", "0,5,5", "--target", "0,0,0", "--up", "0,1,0"});
    check_json_structure(j, 3, 3);
    Matrix3d K;
    K << 1.5, 0, 1, 0, 1.5, 1, 0, 0, 1;
    CHECK_CLOSE(mat(j["K"], 3, 3), K, 1e-12);
    // R rows: u = (1,0,0), -v = (0,-1,1)/sqrt2, w = (0,-1,-1)/sqrt2.
    Matrix3d R;
    R << 1, 0, 0, 0, -1 / kSqrt2, 1 / kSqrt2, 0, -1 / kSqrt2, -1 / kSqrt2;
    CHECK_CLOSE(mat(j["R"], 3, 3), R, 1e-12);
    // t = -R (0,5,5) = -(0, (-5+5)/sqrt2, (-5-5)/sqrt2) = (0, 0, 5 sqrt2): the eye is 5 sqrt2 behind.
    CHECK_CLOSE(vec3(j["t"]), Vector3d(0, 0, 5 * kSqrt2), 1e-12);
    CHECK_CLOSE(vec3(j["eye"]), Vector3d(0, 5, 5), 1e-12);
    CHECK_CLOSE(vec3(j["gaze"]), Vector3d(0, -1, -1) / kSqrt2, 1e-12);
    // up: the look-at camera's up as given, (0,1,0) (json_format.hpp), not its own v.
    CHECK_CLOSE(vec3(j["up"]), Vector3d(0, 1, 0), 1e-12);
}

namespace {

const std::vector<ConvertCase> kConvertCases = {
    {"example camera 2", kSquare90 + Args{"--eye", "0,5,5", "--target", "0,0,0", "--up", "0,1,0"}},
    // R = diag(1,-1,-1): a rotation by exactly pi about x (rvec's edge case).
    {"example camera 1", kSquare90 + Args{"--eye", "0,0,0", "--gaze", "0,0,-1", "--up", "0,1,0"}},
    // gaze +z, up -y: u = (0,0,1) x (0,-1,0) = (1,0,0), v = (0,-1,0), R rows (u, -v, gaze) = I.
    {"identity rotation", {"--fov", "50", "--size", "4x6", "--eye", "2,-1,0.5", "--gaze", "0,0,1", "--up", "0,-1,0"}},
    // gaze +z, up +y: u = (-1,0,0), v = (0,1,0), R = diag(-1,-1,1): a rotation by pi about z.
    {"pi about z", {"--fov", "120", "--size", "5x3", "--eye", "0,0,0", "--gaze", "0,0,1", "--up", "0,1,0"}},
    {"641x479 dfov 33.3, far eye",
     {"--fov", "33.3", "--fov-axis", "diagonal", "--size", "641x479", "--eye", "1e5,-3e4,7", "--gaze", "-0.3,0.9,0.1",
      "--up", "0,0,1"}},
    // Nearly pi: gaze +z, up tilted slightly.
    {"near pi about z", {"--fov", "120", "--size", "5x3", "--eye", "0,0,0", "--gaze", "1e-7,0,1", "--up", "1e-6,1,0"}},
    {"1920x1080 hfov 60, general pose",
     {"--fov", "60", "--fov-axis", "horizontal", "--size", "1920x1080", "--eye", "1.5,-2,3.25", "--target",
      "-4,0.5,7", "--up", "0.1,1,0.2"}},
    {"640x480 fov 75 on both axes (fx != fy)",
     {"--fov", "75", "--size", "640x480", "--eye", "-3,2,10", "--gaze", "0.3,-0.2,-1", "--up", "0,1,0"}},
};

// Every number in a libcam JSON that describes the camera.
void check_same_json_numbers(const json& a, const json& b, double tol) {
    CHECK(a.at("model") == b.at("model"));
    CHECK(a.at("image_size") == b.at("image_size"));
    CHECK(a.at("dist") == b.at("dist"));
    CHECK_CLOSE(mat(a.at("K"), 3, 3), mat(b.at("K"), 3, 3), tol);
    CHECK_CLOSE(mat(a.at("R"), 3, 3), mat(b.at("R"), 3, 3), tol);
    CHECK_CLOSE(mat(a.at("P"), 3, 4), mat(b.at("P"), 3, 4), tol);
    for (const char* key : {"t", "rvec", "eye", "gaze", "up"}) {
        INFO("key " << key);
        CHECK_CLOSE(vec3(a.at(key)), vec3(b.at(key)), tol);
    }
    for (const char* axis : {"horizontal", "vertical", "diagonal"}) {
        INFO("fov_deg." << axis);
        CHECK_CLOSE(MatrixXd::Constant(1, 1, a.at("fov_deg").at(axis).get<double>()),
                    MatrixXd::Constant(1, 1, b.at("fov_deg").at(axis).get<double>()), tol);
    }
}

}  // namespace

TEST_CASE("convert: JSON read back with --from gives the same numbers") {
    for (const ConvertCase& c : kConvertCases) {
        INFO(c.name);
        TempDir dir;
        const json original = run_json(Args{"convert"} + c.flags);
        const fs::path file = dir / "camera.json";
        // -o replaces an existing, longer file whole, and leaves no temporary beside it.
        write_whole_file(file, std::string(100000, '#'));
        run_to_file(Args{"convert"} + c.flags, file);
        CHECK(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()) == 1);
        // The file holds the same JSON as stdout.
        json in_file;
        REQUIRE_NOTHROW(in_file = json::parse(read_whole_file(file)));
        CHECK(in_file == original);
        const json again = run_json({"convert", "--from", file.string()});
        check_json_structure(again, original["image_size"][0].get<long>(), original["image_size"][1].get<long>());
        check_same_json_numbers(again, original, 1e-12);
        CHECK(again.value("fov_axis", "") == original.value("fov_axis", "?"));
    }
}

TEST_CASE("convert: opencv-yaml, opencv-xml, cameramodel and gl files read back to the same K, R, t") {
    struct Format {
        const char* to;
        const char* file;
        double tol;
        Args extra;
    };
    const Format formats[] = {
        {"opencv-yaml", "camera.yaml", 1e-12, {}},
        {"opencv-xml", "camera.xml", 1e-12, {}},
        {"cameramodel", "camera.cameramodel", 1e-12, {}},
        {"gl", "camera_gl.json", 1e-9, {}},
        {"gl", "camera_gl01.json", 1e-9, {"--depth-range", "zero-to-one", "--near", "0.5", "--far", "50"}},
    };
    for (const ConvertCase& c : kConvertCases) {
        const json original = run_json(Args{"convert"} + c.flags);
        for (const Format& f : formats) {
            INFO(c.name << ", --to " << f.to << " " << f.file);
            TempDir dir;
            const fs::path file = dir / f.file;
            run_to_file(Args{"convert"} + c.flags + Args{"--to", f.to} + f.extra, file);
            const json back = run_json({"convert", "--from", file.string()});
            CHECK(back.at("image_size") == original.at("image_size"));
            CHECK_CLOSE(mat(back.at("K"), 3, 3), mat(original.at("K"), 3, 3), f.tol);
            CHECK_CLOSE(mat(back.at("R"), 3, 3), mat(original.at("R"), 3, 3), f.tol);
            CHECK_CLOSE(vec3(back.at("t")), vec3(original.at("t")), f.tol);
            // And explicitly --to json.
            const json back2 = run_json({"convert", "--from", file.string(), "--to", "json"});
            CHECK_CLOSE(mat(back2.at("K"), 3, 3), mat(original.at("K"), 3, 3), f.tol);
        }
    }
}

// ---------------------------------------------------------------------------------------
// 3. --fov-axis on a non-square image.

TEST_CASE("convert: --fov-axis on 1920x1080, fov 60") {
    // tan(60/2) = tan 30deg = 1/sqrt3; the half sides are 960 and 540.
    const double tan30 = std::tan(std::numbers::pi / 6);
    struct AxisCase {
        const char* axis;
        double fx, fy;
    };
    const AxisCase cases[] = {
        {"horizontal", 960 / tan30, 960 / tan30},                                  // 1662.77 both
        {"vertical", 540 / tan30, 540 / tan30},                                    // 935.31 both
        {"diagonal", std::hypot(960.0, 540.0) / tan30, std::hypot(960.0, 540.0) / tan30},  // 1907.77 both
        {"both", 960 / tan30, 540 / tan30},                                        // the look-at formula's
    };
    for (const AxisCase& c : cases) {
        INFO("--fov-axis " << c.axis);
        const json j = run_json({"convert", "--fov", "60", "--size", "1920x1080", "--fov-axis", c.axis});
        Matrix3d K;
        // cx = (1920-1)/2 = 959.5, cy = (1080-1)/2 = 539.5.
        K << c.fx, 0, 959.5, 0, c.fy, 539.5, 0, 0, 1;
        CHECK_CLOSE(mat(j.at("K"), 3, 3), K, 1e-12);
        // The angle itself on its axis: 60 degrees.
        const std::string axis = std::string(c.axis) == "both" ? "horizontal" : c.axis;
        CHECK(j.at("fov_deg").at(axis).get<double>() == Approx(60.0).epsilon(1e-12));
        if (std::string(c.axis) == "both") CHECK(j.at("fov_deg").at("vertical").get<double>() == Approx(60.0).epsilon(1e-12));
    }
}

// ---------------------------------------------------------------------------------------
// 4. --pixel-origin.

TEST_CASE("rays: top-left pixel (x, y) is bottom-left pixel (x, H-1-y)") {
    // By hand first: in example camera 1, top-left (1, 0) is the top middle pixel,
    // bottom-left pixel (1, 2): alpha = 0, beta = (2*2 - 3 + 1)/3 = 2/3, d = (0, 2/3, -1).
    const Args camera1 = kSquare90 + Args{"--gaze", "0,0,-1"};
    const json top = rays(camera1, {"1,0"}, "top-left");
    check_ray(top[0], Vector3d(0, 2.0 / 3, -1), Vector3d::Zero());
    const json bottom = rays(camera1, {"1,2"}, "bottom-left");
    check_ray(bottom[0], Vector3d(0, 2.0 / 3, -1), Vector3d::Zero());

    // A 7x5 camera with a general pose: H - 1 = 4.
    const Args camera = {"--fov", "70", "--size", "7x5", "--eye", "1,2,3", "--target", "3,1,0", "--up", "0.2,1,0.1"};
    const std::vector<std::pair<double, double>> pixels = {{0, 0}, {6, 4}, {2, 1}, {3.25, 0.5}, {-0.5, -0.5}, {6.5, 4.5}, {1, 3}};
    Args top_args, bottom_args;
    for (const auto& [x, y] : pixels) {
        top_args.push_back(num(x) + "," + num(y));
        bottom_args.push_back(num(x) + "," + num(4 - y));
    }
    const json t = rays(camera, top_args, "top-left");
    const json b = rays(camera, bottom_args, "bottom-left");
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        INFO("top-left pixel " << top_args[i] << " vs bottom-left " << bottom_args[i]);
        check_ray(t[i], vec3(b[i]["direction"]), vec3(b[i]["origin"]));
        CHECK_CLOSE(vec3(t[i]["direction_look_at"]), vec3(b[i]["direction_look_at"]), 1e-12);
    }
    // And the flip is not a no-op: the same numbers (0, 0) are different pixels in the two origins.
    const json same_numbers = rays(camera, top_args, "bottom-left");
    CHECK((vec3(t[0]["direction"]) - vec3(same_numbers[0]["direction"])).norm() > 0.1);
}

// ---------------------------------------------------------------------------------------
// 5. Bad input.

namespace {

struct BadCase {
    const char* name;
    Args camera;         // the camera flags (or --from ...), used with both subcommands
    Args convert_extra;  // only for convert
    bool usage;          // a malformed command line: exit 2
    std::vector<std::string> names;  // stderr must contain each
};

void check_failure(const CliResult& r, const Args& args, const BadCase& c) {
    INFO(c.name << "\n" << joined(args) << "\n" << r.describe());
    CHECK(r.exit_code != 0);
    CHECK(r.exit_code > 0);  // exited, not killed by a signal
    if (c.usage) CHECK(r.exit_code == 2);
    CHECK(r.out.empty());
    // One line on stderr.
    REQUIRE(!r.err.empty());
    CHECK(r.err.back() == '\n');
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    for (const std::string& name : c.names) {
        INFO("stderr should name " << name);
        CHECK(r.err.find(name) != std::string::npos);
    }
}

}  // namespace

TEST_CASE("bad input: non-zero exit, nothing on stdout, one line on stderr, output file untouched") {
    TempDir files;
    const std::string missing = (files / "missing.json").string();
    const std::string empty = (files / "empty.json").string();
    const std::string truncated = (files / "truncated.json").string();
    const std::string bad_yaml = (files / "bad.yaml").string();
    write_whole_file(empty, "");
    {
        // A real camera file cut in half.
        const CliResult good = run_libcam(Args{"convert"} + kSquare90);
        REQUIRE(good.exit_code == 0);
        write_whole_file(truncated, good.out.substr(0, good.out.size() / 2));
    }
    write_whole_file(bad_yaml, "%YAML:1.0\n---\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: [3\n  : : : }\n");

    const Args size3 = {"--size", "3x3"};
    const Args fov90 = {"--fov", "90"};
    const std::vector<BadCase> cases = {
        {"fov 0", {"--fov", "0", "--size", "3x3"}, {}, false, {"fov"}},
        {"fov -5", {"--fov", "-5", "--size", "3x3"}, {}, false, {"fov"}},
        {"fov 180", {"--fov", "180", "--size", "3x3"}, {}, false, {"fov"}},
        {"fov 200", {"--fov", "200", "--size", "3x3"}, {}, false, {"fov"}},
        {"fov nan", {"--fov", "nan", "--size", "3x3"}, {}, false, {"fov"}},
        {"fov inf", {"--fov", "inf", "--size", "3x3"}, {}, false, {"fov"}},
        {"fov abc", {"--fov", "abc", "--size", "3x3"}, {}, true, {"fov", "abc"}},
        {"size 0x3", fov90 + Args{"--size", "0x3"}, {}, false, {"size"}},
        {"size -3x3", fov90 + Args{"--size", "-3x3"}, {}, false, {"size"}},
        {"size 3x", fov90 + Args{"--size", "3x"}, {}, true, {"size"}},
        {"size 3x3x3", fov90 + Args{"--size", "3x3x3"}, {}, true, {"size"}},
        {"size abc", fov90 + Args{"--size", "abc"}, {}, true, {"size"}},
        {"size 3.5x3", fov90 + Args{"--size", "3.5x3"}, {}, true, {"size"}},
        {"eye == target", kSquare90 + Args{"--eye", "1,2,3", "--target", "1,2,3"}, {}, false, {"target"}},
        {"up along the gaze", kSquare90 + Args{"--gaze", "0,0,-1", "--up", "0,0,-1"}, {}, false, {"up"}},
        {"up against the gaze", kSquare90 + Args{"--gaze", "0,0,-1", "--up", "0,0,5"}, {}, false, {"up"}},
        {"up along the target", kSquare90 + Args{"--target", "0,0,-4", "--up", "0,0,5"}, {}, false, {"up"}},
        {"eye nan", kSquare90 + Args{"--eye", "nan,0,0"}, {}, false, {"eye"}},
        {"eye inf", kSquare90 + Args{"--eye", "0,inf,0"}, {}, false, {"eye"}},
        {"up nan", kSquare90 + Args{"--up", "0,nan,0"}, {}, false, {"up"}},
        {"up -inf", kSquare90 + Args{"--up", "0,1,-inf"}, {}, false, {"up"}},
        {"target nan", kSquare90 + Args{"--target", "0,0,nan"}, {}, false, {"target"}},
        {"target inf", kSquare90 + Args{"--target", "inf,0,-1"}, {}, false, {"target"}},
        {"eye 1,2", kSquare90 + Args{"--eye", "1,2"}, {}, true, {"eye"}},
        {"eye 1,2,3,4", kSquare90 + Args{"--eye", "1,2,3,4"}, {}, true, {"eye"}},
        {"from a missing file", {"--from", missing}, {}, false, {missing}},
        {"from an empty file", {"--from", empty}, {}, false, {empty}},
        {"from a truncated JSON file", {"--from", truncated}, {}, false, {truncated}},
        {"from a malformed YAML file", {"--from", bad_yaml}, {}, false, {bad_yaml}},
        {"--from with --fov", {"--from", truncated, "--fov", "90"}, {}, true, {"--from", "--fov"}},
        {"unknown flag", kSquare90 + Args{"--bogus"}, {}, true, {"--bogus"}},
        {"unknown --to", kSquare90, {"--to", "bogus"}, true, {"--to", "bogus"}},
        {"unknown --fov-axis", kSquare90 + Args{"--fov-axis", "bogus"}, {}, true, {"fov-axis"}},
        {"gaze 0,0,0", kSquare90 + Args{"--gaze", "0,0,0"}, {}, false, {"gaze"}},
        {"up 0,0,0", kSquare90 + Args{"--up", "0,0,0"}, {}, false, {"up"}},
        {"--target with --gaze", kSquare90 + Args{"--target", "1,1,1", "--gaze", "0,0,1"}, {}, true, {"--target", "--gaze"}},
        {"gl near 0", kSquare90, {"--to", "gl", "--near", "0"}, false, {"near"}},
        {"gl far <= near", kSquare90, {"--to", "gl", "--near", "10", "--far", "10"}, false, {"far"}},
    };

    const std::string sentinel = "precious bytes\n\x01\x02 not a camera\n";
    for (const BadCase& c : cases) {
        // convert to stdout.
        const Args args = Args{"convert"} + c.camera + c.convert_extra;
        check_failure(run_libcam(args), args, c);

        // convert -o NEW: no file, and no temporary left beside it.
        TempDir out;
        const fs::path target = out / "out.json";
        const Args to_new = args + Args{"-o", target.string()};
        check_failure(run_libcam(to_new), to_new, c);
        {
            INFO(c.name << ": -o must not create the file");
            CHECK(!fs::exists(target));
            CHECK(fs::is_empty(out.path()));
        }

        // convert -o EXISTING: left byte for byte.
        write_whole_file(target, sentinel);
        const Args to_existing = args + Args{"-o", target.string()};
        check_failure(run_libcam(to_existing), to_existing, c);
        {
            INFO(c.name << ": -o must leave the existing file alone");
            CHECK(read_whole_file(target) == sentinel);
            CHECK(std::distance(fs::directory_iterator(out.path()), fs::directory_iterator()) == 1);
        }

        // rays with the same camera.
        if (c.convert_extra.empty()) {
            const Args rays_args = Args{"rays", "--json"} + c.camera + Args{"--pixels", "1,1"};
            check_failure(run_libcam(rays_args), rays_args, c);
        }
    }
}

TEST_CASE("bad input: rays-only flags, a missing output folder, no subcommand") {
    const std::vector<BadCase> rays_cases = {
        {"pixel with one number", {"--pixels", "1"}, {}, true, {"pixels"}},
        {"pixel with three numbers", {"--pixels", "1,1,1"}, {}, true, {"pixels"}},
        {"pixel nan", {"--pixels", "nan,1"}, {}, false, {"pixels"}},
        {"pixel abc", {"--pixels", "1,abc"}, {}, true, {"pixels"}},
        {"no pixels", {}, {}, true, {"pixels"}},
        {"unknown --pixel-origin", {"--pixel-origin", "bogus", "--pixels", "1,1"}, {}, true, {"pixel-origin"}},
    };
    for (const BadCase& c : rays_cases) {
        const Args args = Args{"rays", "--json"} + kSquare90 + c.camera;
        check_failure(run_libcam(args), args, c);
    }

    TempDir dir;
    const fs::path missing_folder = dir / "no-such-folder";
    const std::string target = (missing_folder / "out.json").string();
    const BadCase folder{"-o into a missing folder", {}, {}, false, {target}};
    const Args args = Args{"convert"} + kSquare90 + Args{"-o", target};
    check_failure(run_libcam(args), args, folder);
    CHECK(!fs::exists(missing_folder));
    CHECK(fs::is_empty(dir.path()));

    const BadCase none{"no subcommand", {}, {}, true, {}};
    check_failure(run_libcam({}), {}, none);
    // (CLI11 reports "A subcommand is required" here, without the word given.)
    const BadCase unknown{"unknown subcommand", {}, {}, true, {}};
    check_failure(run_libcam({"frobnicate"}), {"frobnicate"}, unknown);
}

// (A name that starts with "--" would be read by Catch as a flag, and the test never run.)
TEST_CASE("Each subcommand's --help exits 0 and prints its usage") {
    for (const char* command : {"convert", "rays", "project", "info", "remap", "rectify", "dataset", "derive", "render-plan", "verify", "fit",
                                "bench", "demo"}) {
        INFO(command);
        const CliResult r = run_libcam({command, "--help"});
        INFO(r.describe());
        CHECK(r.exit_code == 0);
        CHECK(r.out.find("Usage") != std::string::npos);
        CHECK(r.out.find(command) != std::string::npos);
        CHECK(r.out.find("--help") != std::string::npos);
        CHECK(r.err.empty());
    }
    const CliResult convert_help = run_libcam({"convert", "--help"});
    CHECK(convert_help.out.find("--to") != std::string::npos);
    const CliResult rays_help = run_libcam({"rays", "--help"});
    CHECK(rays_help.out.find("--pixels") != std::string::npos);
}

// ---------------------------------------------------------------------------------------
// 6. rays --from a camera file written by convert.

TEST_CASE("rays --from a file written by convert gives the rays of the flags") {
    const Args pixels = {"0,0", "1,1", "2,1", "-0.5,-0.5", "0.25,2.75"};
    for (const ConvertCase& c : kConvertCases) {
        for (const char* name : {"camera.json", "camera.yaml", "camera.cameramodel"}) {
            INFO(c.name << ", file " << name);
            TempDir dir;
            const fs::path file = dir / name;
            const std::string format = std::string(name) == "camera.json"   ? "json"
                                       : std::string(name) == "camera.yaml" ? "opencv-yaml"
                                                                            : "cameramodel";
            run_to_file(Args{"convert", "--to", format} + c.flags, file);
            for (const char* origin : {"bottom-left", "top-left"}) {
                INFO("--pixel-origin " << origin);
                const json from_flags = rays(c.flags, pixels, origin);
                const json from_file = rays({"--from", file.string()}, pixels, origin);
                for (std::size_t i = 0; i < pixels.size(); ++i) {
                    INFO("pixel " << pixels[i]);
                    check_ray(from_file[i], vec3(from_flags[i]["direction"]), vec3(from_flags[i]["origin"]));
                }
            }
        }
    }
    // And by hand for example camera 2 read from JSON: pixel (0,0) bottom-left is
    // (-2/3, -sqrt2/3 - 1/sqrt2, sqrt2/3 - 1/sqrt2) from (0,5,5) (as in "rays: example camera 2").
    TempDir dir;
    const fs::path file = dir / "camera2.json";
    run_to_file(Args{"convert"} + kConvertCases[0].flags, file);
    const json r = rays({"--from", file.string()}, {"0,0"});
    check_ray(r[0], Vector3d(-2.0 / 3, -kSqrt2 / 3 - 1 / kSqrt2, kSqrt2 / 3 - 1 / kSqrt2), Vector3d(0, 5, 5));
}

TEST_CASE("info lists every camera of a rig file, and --camera picks one for convert") {
    // A Kalibr camchain: cam0 an OPENCV4 camera, cam1 an equidistant fisheye (Kalibr's
    // pinhole-equi, zero coefficients) 0.1 to its right. The fisheye's horizontal field of
    // view through the lens, edge to edge: the edges -0.5 and 639.5 are 320 px from cx on
    // each side, so 2 x 320 / 200 radians = 183.35 degrees (r = f theta).
    TempDir dir;
    const std::string chain = (dir.path() / "camchain.yaml").string();
    std::ofstream(chain) << R"(cam0:
  camera_model: pinhole
  distortion_model: radtan
  intrinsics: [400, 400, 319.5, 239.5]
  distortion_coeffs: [-0.1, 0.01, 0.0, 0.0]
  resolution: [640, 480]
cam1:
  T_cn_cnm1:
  - [1, 0, 0, -0.1]
  - [0, 1, 0, 0]
  - [0, 0, 1, 0]
  - [0, 0, 0, 1]
  camera_model: pinhole
  distortion_model: equidistant
  intrinsics: [200, 200, 319.5, 239.5]
  distortion_coeffs: [0, 0, 0, 0]
  resolution: [640, 480]
)";
    const CliResult info = run_libcam({"info", chain, "--json"});
    INFO(info.describe());
    REQUIRE(info.exit_code == 0);
    const nlohmann::json out = nlohmann::json::parse(info.out);
    CHECK(out.at("format") == "kalibr");
    REQUIRE(out.at("cameras").size() == 2);
    CHECK(out.at("cameras")[1].at("name") == "cam1");
    CHECK(out.at("cameras")[1].at("model") == "FISHEYE");
    CHECK(out.at("cameras")[1].at("fov_deg").at("horizontal").get<double>() ==
          Approx(640.0 / 200 * 180 / std::numbers::pi).epsilon(1e-9));
    CHECK(out.at("cameras")[1].at("camera_center")[0].get<double>() == Approx(0.1).epsilon(1e-15));

    const CliResult table = run_libcam({"info", chain});
    CHECK_THAT(table.out, Catch::Contains("camchain.yaml: kalibr, 2 cameras"));
    CHECK_THAT(table.out, Catch::Contains("camera 1: cam1"));

    const CliResult picked = run_libcam({"convert", "--from", chain, "--camera", "cam1"});
    REQUIRE(picked.exit_code == 0);
    CHECK(nlohmann::json::parse(picked.out).at("model") == "FISHEYE");
    const CliResult missing = run_libcam({"convert", "--from", chain, "--camera", "2"});
    CHECK(missing.exit_code == 1);
    CHECK_THAT(missing.err, Catch::Contains("no camera '2'; it holds 2 cameras: 0 (cam0), 1 (cam1)"));
    const CliResult bad_format = run_libcam({"info", chain, "--from-format", "nerfstudio"});
    CHECK(bad_format.exit_code == 2);
    CHECK_THAT(bad_format.err, Catch::Contains("--from-format"));
}

namespace {

// The line of `libcam info`'s text that gives the field of view.
std::string fov_line(const std::string& info_text) {
    std::istringstream lines(info_text);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("  fov ", 0) == 0) return line;
    return "";
}

}  // namespace

TEST_CASE("info says of each axis whether its field of view spans the image or stops at the last pixel with a ray") {
    // r (1 + k1 r^2) with k1 = -0.2 folds at r = 1 / sqrt(0.6), whose image is 0.8607 f =
    // 258.2 px from the centre (f = 300): the horizontal edges, 320 px out, have no ray; the
    // vertical ones, 240 px out, have (test_field_of_view works the angles).
    TempDir dir;
    const std::string chain = (dir.path() / "camchain.yaml").string();
    std::ofstream(chain) << R"(cam0:
  camera_model: pinhole
  distortion_model: radtan
  intrinsics: [300, 300, 319.5, 239.5]
  distortion_coeffs: [-0.2, 0.0, 0.0, 0.0]
  resolution: [640, 480]
)";
    const CliResult folding = run_libcam({"info", chain});
    INFO(folding.describe());
    REQUIRE(folding.exit_code == 0);
    CHECK_THAT(fov_line(folding.out), Catch::Matches(R"(  fov +horizontal [0-9.]+ deg \(to the last pixel with a ray\), )"
                                                     R"(vertical [0-9.]+ deg \(edge to edge\), through the lens)"));

    std::ofstream(chain) << R"(cam0:
  camera_model: pinhole
  distortion_model: radtan
  intrinsics: [300, 300, 319.5, 239.5]
  distortion_coeffs: [-0.02, 0.0, 0.0, 0.0]
  resolution: [640, 480]
)";
    const CliResult mild = run_libcam({"info", chain});
    REQUIRE(mild.exit_code == 0);
    CHECK_THAT(fov_line(mild.out), Catch::Matches(R"(  fov +horizontal [0-9.]+ deg, vertical [0-9.]+ deg )"
                                                  R"(\(through the lens, edge to edge\))"));
}

TEST_CASE("A camera picked by its image's file name (--camera), and info says which views have no pose") {
    // A Metashape 1.5 document as Export Cameras writes it before alignment: one frame
    // sensor (f 1000, cx 12.5 from the centre of 640 x 480), two cameras without a
    // <transform>; and an OpenMVG-style name as a path, to find by its file name.
    TempDir dir;
    const std::string xml = (dir.path() / "cameras.xml").string();
    write_whole_file(xml, R"(<?xml version="1.0" encoding="UTF-8"?>
<document version="1.5.0">
  <chunk label="Chunk 1" enabled="true">
    <sensors next_id="1">
      <sensor id="0" label="body" type="frame">
        <resolution width="640" height="480"/>
        <calibration type="frame" class="initial">
          <resolution width="640" height="480"/>
          <f>1000</f>
          <cx>12.5</cx>
        </calibration>
      </sensor>
    </sensors>
    <cameras next_id="2" next_group_id="0">
      <camera id="0" sensor_id="0" label="DSC_0001"/>
      <camera id="1" sensor_id="0" label="DSC_0002"/>
    </cameras>
  </chunk>
</document>
)");
    const CliResult info = run_libcam({"info", xml, "--camera", "DSC_0002"});
    INFO(info.describe());
    REQUIRE(info.exit_code == 0);
    CHECK_THAT(info.out, Catch::Contains("camera 1: DSC_0002 (intrinsics body)"));
    // cx = 320 + 12.5 - 0.5 (Metashape's pixel (0, 0) is the top-left pixel's corner).
    CHECK_THAT(info.out, Catch::Contains("K         fx 1000, fy 1000, cx 332, cy 239.5"));
    CHECK_THAT(info.out, Catch::Contains("pose      none: the file lists this view without a pose"));
    const CliResult listed = run_libcam({"info", xml, "--json"});
    REQUIRE(listed.exit_code == 0);
    const json cameras = json::parse(listed.out).at("cameras");
    REQUIRE(cameras.size() == 2);
    CHECK(cameras[0].at("posed") == false);
    CHECK(cameras[1].at("name") == "DSC_0002");
    // A command that uses the pose says that the view has none.
    const CliResult unposed_rays = run_libcam({"rays", "--from", xml, "--camera", "DSC_0002", "--pixels", "332,239.5"});
    INFO(unposed_rays.describe());
    REQUIRE(unposed_rays.exit_code == 0);
    CHECK_THAT(unposed_rays.err, Catch::Contains("camera 'DSC_0002' has no pose in the file; the identity pose is used"));

    // A COLMAP model whose image names are paths: IMG_2.jpg alone finds day2/IMG_2.jpg.
    const fs::path model = dir.path() / "model";
    fs::create_directories(model);
    write_whole_file((model / "cameras.txt").string(), "1 PINHOLE 640 480 500 500 320 240\n");
    write_whole_file((model / "images.txt").string(),
                     "1 1 0 0 0 0 0 0 1 day1/IMG_1.jpg\n\n2 1 0 0 0 1 0 0 1 day2/IMG_2.jpg\n\n"
                     "3 1 0 0 0 2 0 0 1 day2/IMG_1.jpg\n\n");
    const CliResult by_file_name = run_libcam({"info", model.string(), "--camera", "IMG_2.jpg", "--json"});
    INFO(by_file_name.describe());
    REQUIRE(by_file_name.exit_code == 0);
    CHECK(json::parse(by_file_name.out).at("cameras")[0].at("name") == "day2/IMG_2.jpg");
    CHECK(json::parse(by_file_name.out).at("cameras")[0].at("posed") == true);
    const CliResult posed_rays = run_libcam({"rays", "--from", model.string(), "--camera", "IMG_2.jpg", "--pixels", "0,0"});
    REQUIRE(posed_rays.exit_code == 0);
    CHECK(posed_rays.err.empty());
    const CliResult ambiguous = run_libcam({"info", model.string(), "--camera", "IMG_1.jpg"});
    CHECK(ambiguous.exit_code == 1);
    CHECK_THAT(ambiguous.err, Catch::Contains("the image file name 'IMG_1.jpg' names 2 cameras: 0 (day1/IMG_1.jpg), "
                                              "2 (day2/IMG_1.jpg); give one's whole name or its position"));
}

TEST_CASE("libcam formats says which names --camera takes for each format it reads") {
    const CliResult result = run_libcam({"formats", "--json"});
    REQUIRE(result.exit_code == 0);
    for (const json& format : json::parse(result.out)) {
        CAPTURE(format.at("name"));
        if (format.at("reads") == true) CHECK_FALSE(format.at("camera_names").get<std::string>().empty());
    }
    const CliResult plain = run_libcam({"formats"});
    CHECK_THAT(plain.out, Catch::Contains("  --camera  each view's path, or its image's file name alone, posed or not"));
}

TEST_CASE("info gives each image of a model the field of view of its own calibration, shared or not") {
    // Five images over three calibrations: two pinholes with the same K on different image
    // widths, and a radial lens (COLMAP's SIMPLE_RADIAL, r (1 + k r^2)). info works each
    // calibration out once; every image must still get its own.
    TempDir dir;
    const fs::path model = dir.path() / "sparse";
    fs::create_directories(model);
    write_whole_file(model / "cameras.txt",
                     "1 PINHOLE 640 480 400 400 320 240\n"
                     "2 PINHOLE 800 480 400 400 400 240\n"
                     "3 SIMPLE_RADIAL 640 480 300 320 240 -0.05\n");
    const std::vector<std::pair<std::string, int>> images = {
        {"a.png", 1}, {"b.png", 3}, {"c.png", 1}, {"d.png", 2}, {"e.png", 3}};
    std::string lines;
    for (std::size_t i = 0; i < images.size(); ++i) {
        lines += std::to_string(i + 1) + " 1 0 0 0 " + std::to_string(i) + " 0 0 " + std::to_string(images[i].second) +
                 " " + images[i].first + "\n\n";
    }
    write_whole_file(model / "images.txt", lines);
    write_whole_file(model / "points3D.txt", "");
    const CliResult info = run_libcam({"info", model.string(), "--json"});
    INFO(info.describe());
    REQUIRE(info.exit_code == 0);
    const json cameras = json::parse(info.out).at("cameras");
    REQUIRE(cameras.size() == images.size());
    // The edge ray's angle, degrees, for an edge `pixels` from the centre (COLMAP's cx is
    // the image's half width: the outer side of the edge pixel) and the radial lens's
    // k: its undistorted radius solves r + k r^3 = pixels / f (bisection below the fold).
    const auto edge_degrees = [](double pixels, double f, double k) {
        double low = 0, high = k < 0 ? std::sqrt(-1 / (3 * k)) : pixels / f;
        for (int i = 0; i < 200; ++i) {
            const double r = (low + high) / 2;
            (r + k * r * r * r < pixels / f ? low : high) = r;
        }
        return std::atan((low + high) / 2) * 180 / std::numbers::pi;
    };
    for (std::size_t i = 0; i < images.size(); ++i) {
        const json& camera = cameras[i];
        INFO(images[i].first);
        CHECK(camera.at("name") == images[i].first);
        CHECK(camera.at("intrinsics_name") == "id:" + std::to_string(images[i].second));
        CHECK(camera.at("t")[0].get<double>() == static_cast<double>(i));
        const int width = images[i].second == 2 ? 800 : 640;
        const double f = images[i].second == 3 ? 300 : 400, k = images[i].second == 3 ? -0.05 : 0.0;
        CHECK(camera.at("image_size")[0].get<int>() == width);
        CHECK(camera.at("fov_deg").at("horizontal").get<double>() ==
              Approx(2 * edge_degrees(width / 2.0, f, k)).epsilon(1e-9));
        CHECK(camera.at("fov_deg").at("vertical").get<double>() == Approx(2 * edge_degrees(240, f, k)).epsilon(1e-9));
        CHECK(camera.at("rayless_fraction").get<double>() == 0.0);
    }
    // The same in the text: each image its own block, with its size.
    const CliResult text = run_libcam({"info", model.string()});
    CHECK_THAT(text.out, Catch::Contains("sparse: colmap, 5 cameras"));
    CHECK_THAT(text.out,
               Catch::Contains("camera 3: d.png (intrinsics id:2)\n  model     PINHOLE\n  size      800x480"));
}

TEST_CASE("convert writes a COLMAP model into a folder, info lists its image, and NeRF's sizes come from flags") {
    TempDir dir;
    const std::string model = (dir.path() / "sparse").string();
    // A 60-degree look-at camera: COLMAP's cx is libcam's 319.5 plus 0.5.
    const CliResult written = run_libcam({"convert", "--fov", "60", "--fov-axis", "horizontal", "--size", "640x480",
                                          "--to", "colmap", "-o", model, "--image-name", "frame_7.png"});
    INFO(written.describe());
    REQUIRE(written.exit_code == 0);
    CHECK(written.out.empty());
    CHECK_THAT(read_whole_file(dir.path() / "sparse" / "cameras.txt"), Catch::Contains("\n1 PINHOLE 640 480 "));
    CHECK_THAT(read_whole_file(dir.path() / "sparse" / "cameras.txt"), Catch::Contains(" 320 240\n"));
    const CliResult info = run_libcam({"info", model, "--json"});
    REQUIRE(info.exit_code == 0);
    const nlohmann::json out = nlohmann::json::parse(info.out);
    CHECK(out.at("format") == "colmap");
    CHECK(out.at("cameras").at(0).at("name") == "frame_7.png");
    CHECK(out.at("cameras").at(0).at("intrinsics_name") == "id:1");
    // Several files need a folder; a camera_info holds no pose unless told to drop it.
    const CliResult to_stdout = run_libcam({"convert", "--fov", "60", "--size", "640x480", "--to", "colmap"});
    CHECK(to_stdout.exit_code == 2);
    CHECK_THAT(to_stdout.err, Catch::Contains("give the folder"));
    const std::vector<std::string> posed = {"convert", "--fov", "60", "--size", "640x480", "--eye", "1,2,3", "--to", "ros"};
    const CliResult refused = run_libcam(posed);
    CHECK(refused.exit_code == 1);
    CHECK_THAT(refused.err, Catch::Contains("--no-pose"));
    std::vector<std::string> dropped = posed;
    dropped.push_back("--no-pose");
    CHECK(run_libcam(dropped).exit_code == 0);
    // NeRF's synthetic scenes record no size: --image-size gives it.
    const std::string nerf = (dir.path() / "transforms_train.json").string();
    std::ofstream(nerf) << R"({"camera_angle_x": 0.6911112070083618, "frames": []})";
    const CliResult unsized = run_libcam({"info", nerf});
    CHECK(unsized.exit_code == 1);
    CHECK_THAT(unsized.err, Catch::Contains("--image-size WxH"));
    const CliResult sized = run_libcam({"convert", "--from", nerf, "--image-size", "800x800"});
    INFO(sized.describe());
    REQUIRE(sized.exit_code == 0);
    CHECK(nlohmann::json::parse(sized.out).at("K").at(0).at(2) == 399.5);
}
