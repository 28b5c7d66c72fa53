// `libcam verify`, as a library call and as the program (tests/cli_runner.hpp): cameras
// that must pass, the real wide lens (6016x4016, OPENCV8) and OpenCV's default
// undistortPoints on it, models one library lacks, the heatmap, and bad input.
//
// Expected values come from the targets libcam is held to (1e-9 px for libcam, 1e-6 px
// against mrcal_unproject), from OpenCV's default measured at 384 px on the wide lens's
// corner, from OpenCV called here, or from formulas worked by hand, never from the
// program's own output.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "lens_cases.hpp"
#include "libcam/error.hpp"
#include "libcam/check/verify.hpp"
#include "libcam/io/camera_file.hpp"

using namespace libcam;
using namespace libcam::test;
using nlohmann::json;
using Args = std::vector<std::string>;
namespace fs = std::filesystem;

namespace {

constexpr double kLibcamTolerancePx = 1e-9;
constexpr double kMrcalAgreementPx = 1e-6;

// The checks that measure libcam itself, held to 1e-9 px.
const std::vector<std::string> kLibcamChecks = {"project-opencv",          "project-mrcal",
                                                "unproject-libcam",        "unproject-libcam-opencv",
                                                "unproject-libcam-mrcal",  "round-trip"};

Args operator+(Args a, const Args& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

Camera lens_case(const std::string& name) {
    for (const LensCase& c : lens_cases()) {
        if (c.name == name) return c.camera;
    }
    throw std::logic_error("no lens case " + name);
}

std::string joined(const Args& args) {
    std::string text = "libcam";
    for (const std::string& a : args) text += " '" + a + "'";
    return text;
}

fs::path write_json_camera(const TempDir& dir, const std::string& name, const Camera& camera) {
    const fs::path path = dir / (name + ".json");
    write_camera_file(path, camera, CameraFormat::Json);
    return path;
}

// The wide lens as OpenCV's calibration sample writes it, by cv::FileStorage itself.
fs::path write_opencv_yaml(const TempDir& dir, const Camera& camera) {
    const fs::path path = dir / "wide.yaml";
    cv::FileStorage out(path.string(), cv::FileStorage::WRITE);
    out << "image_width" << static_cast<int>(camera.size.width) << "image_height" << static_cast<int>(camera.size.height);
    out << "camera_matrix" << opencv_camera_matrix(camera.intrinsics);
    out << "distortion_coefficients" << cv::Mat(camera.lens.coefficients, true).reshape(1, 1);
    out.release();
    return path;
}

json run_verify_json(const Args& args, int expected_exit = 0) {
    const CliResult r = run_libcam(Args{"verify", "--json"} + args);
    INFO(joined(args) << "\n" << r.describe());
    REQUIRE(r.exit_code == expected_exit);
    REQUIRE(r.err.empty());
    json report;
    REQUIRE_NOTHROW(report = json::parse(r.out));
    return report;
}

const json& check_named(const json& report, const std::string& name) {
    for (const json& check : report.at("checks")) {
        if (check.at("name") == name) return check;
    }
    FAIL("no check named " << name);
    throw std::logic_error("unreachable");
}

// Every check that measures libcam ran and is within its tolerance (1e-9 px); so is the
// agreement with mrcal_unproject where mrcal has the model.
void require_libcam_within_tolerance(const json& report) {
    for (const std::string& name : kLibcamChecks) {
        const json& check = check_named(report, name);
        INFO(check.dump());
        CHECK(check.at("pass") == true);
        if (check.at("status") == "skipped") continue;
        CHECK(check.at("max_px").get<double>() <= kLibcamTolerancePx);
        CHECK(check.at("tolerance_px").get<double>() == kLibcamTolerancePx);
    }
    const json& mrcal = check_named(report, "unproject-mrcal-vs-libcam");
    INFO(mrcal.dump());
    if (mrcal.at("status") != "skipped") CHECK(mrcal.at("max_px").get<double>() <= kMrcalAgreementPx);
}

// The worst reprojection error of cv::undistortPoints at its default over the four
// corner pixels, reprojected by cv::projectPoints: measured here, on OpenCV alone.
double opencv_default_corner_error(const Camera& camera) {
    const double right = static_cast<double>(camera.size.width - 1), bottom = static_cast<double>(camera.size.height - 1);
    const std::vector<cv::Point2d> corners{{0, 0}, {right, 0}, {0, bottom}, {right, bottom}};
    const cv::Mat K = opencv_camera_matrix(camera.intrinsics), dist = opencv_distortion(camera.lens);
    std::vector<cv::Point2d> normalised, back;
    cv::undistortPoints(corners, normalised, K, dist);
    std::vector<cv::Point3d> rays;
    for (const cv::Point2d& m : normalised) rays.emplace_back(m.x, m.y, 1.0);
    const cv::Mat zero = cv::Mat::zeros(3, 1, CV_64F);
    cv::projectPoints(rays, zero, zero, K, dist, back);
    double worst = 0;
    for (std::size_t i = 0; i < corners.size(); ++i) worst = std::max(worst, cv::norm(back[i] - corners[i]));
    return worst;
}

}  // namespace

TEST_CASE("The grid runs over the whole image, corners included, and every check is reported once") {
    VerifyOptions options;
    options.grid_columns = 5;
    options.grid_rows = 4;
    const Camera camera = lens_camera(LensType::Pinhole, {}, {640, 480});
    const VerifyReport report = verify_camera(camera, options);
    REQUIRE(report.pixels.size() == 20);
    CHECK(report.pixels.front() == Vec2(0, 0));
    CHECK(report.pixels[4] == Vec2(639, 0));
    CHECK(report.pixels[15] == Vec2(0, 479));
    CHECK(report.pixels.back() == Vec2(639, 479));
    CHECK(report.invalid_fraction == 0.0);
    REQUIRE(report.checks.size() == verify_check_names().size());
    for (std::size_t i = 0; i < report.checks.size(); ++i) CHECK(report.checks[i].name == verify_check_names()[i]);
    CHECK(report.pass());

    options.grid_columns = 1;
    CHECK_THROWS_AS(verify_camera(camera, options), InvalidArgument);
}

TEST_CASE("Informational rows never fail, and a measured row fails past its tolerance") {
    VerifyCheck check;
    check.stats.count = 1;
    check.stats.max_px = 384.0;
    CHECK(check.pass());  // no tolerance: informational
    check.tolerance_px = 1e-9;
    CHECK_FALSE(check.pass());
    check.stats.max_px = 1e-10;
    CHECK(check.pass());
}

TEST_CASE("libcam verify: a pinhole and a mild OPENCV8 camera pass") {
    const TempDir dir;
    for (const std::string name : {"PINHOLE", "OPENCV8 mild"}) {
        INFO(name);
        const Camera camera = lens_case(name);
        const fs::path file = write_json_camera(dir, "camera", camera);
        const json report = run_verify_json({file.string(), "--grid", "40x30"});
        CHECK(report.at("pass") == true);
        CHECK(report.at("invalid_fraction") == 0.0);
        require_libcam_within_tolerance(report);
        if (camera.lens.type == LensType::Pinhole) {
            // Without distortion cv::undistortPoints is K^-1 [x, y, 1], exact at its default.
            CHECK(check_named(report, "undistort-opencv-default").at("max_px").get<double>() <= kLibcamTolerancePx);
        }

        const CliResult table = run_libcam({"verify", file.string(), "--grid", "40x30"});
        INFO(table.describe());
        CHECK(table.exit_code == 0);
        CHECK(table.err.empty());
        for (std::string_view name : verify_check_names()) CHECK(table.out.find(std::string(name)) != std::string::npos);
    }
}

TEST_CASE("libcam verify: the real wide lens passes, and OpenCV's default undistortPoints is off by pixels") {
    const TempDir dir;
    const Camera camera = wide_reference_camera();
    const json report = run_verify_json({write_opencv_yaml(dir, camera).string()});  // default grid, 200x150
    CHECK(report.at("pass") == true);
    CHECK(report.at("invalid_fraction") == 0.0);  // every pixel of this lens has a ray
    require_libcam_within_tolerance(report);

    // The grid holds the corners, so the worst it reports is at least what OpenCV does
    // there, measured here: 384 px, at the top-right corner (6015, 0).
    const double corner_error = opencv_default_corner_error(camera);
    CHECK(corner_error > 100.0);
    const json& summary = report.at("opencv_default_summary");
    INFO(summary.dump());
    CHECK(summary.at("max_px").get<double>() > 1.0);
    CHECK(summary.at("max_px").get<double>() >= corner_error * (1 - 1e-9));
    CHECK(summary.at("fraction_over_1px").get<double>() > 0.0);
    CHECK(summary.at("fraction_over_0_1px").get<double>() >= summary.at("fraction_over_1px").get<double>());
    // At 100 iterations OpenCV gets within 0.016 px on this lens: the row runs that rule.
    CHECK(check_named(report, "undistort-opencv-100").at("max_px").get<double>() < 0.1);
    // mrcal_unproject's own residual is 1.9e-8 px at worst on this lens.
    CHECK(check_named(report, "unproject-mrcal").at("max_px").get<double>() < 1e-6);
}

TEST_CASE("libcam verify: FISHEYE and LONLAT run, the library that lacks the model is skipped") {
    const TempDir dir;
    for (const std::string name : {"FISHEYE mild", "LONLAT"}) {
        INFO(name);
        const LensType type = lens_case(name).lens.type;
        const json report = run_verify_json({write_json_camera(dir, "camera", lens_case(name)).string(), "--grid", "41x31"});
        CHECK(report.at("pass") == true);
        require_libcam_within_tolerance(report);
        for (const json& check : report.at("checks")) {
            const std::string name = check.at("name");
            const bool needs_mrcal = name.find("mrcal") != std::string::npos;
            const bool needs_opencv = name.find("opencv") != std::string::npos;
            const bool lacking = (needs_mrcal && !in_mrcal(type)) || (needs_opencv && !in_opencv(type));
            INFO(check.dump());
            CHECK((check.at("status") == "skipped") == lacking);
            CHECK(check.at("pass") == true);
        }
        CHECK(report.at("opencv_default_summary").is_null() == !in_opencv(type));
    }
}

TEST_CASE("libcam verify: the fraction of pixels without a ray, LONLAT worked by hand") {
    // LONLAT: lon = (x - cx) / fx, lat = (y - cy) / fy; a pixel has a ray exactly when
    // |lon| <= pi and |lat| <= pi/2. This camera sees a little more than the sphere.
    const Camera camera = lens_camera(LensType::Lonlat, {}, {2000, 1000}, 310, 300);
    const int columns = 51, rows = 37;
    std::size_t outside = 0;
    for (int j = 0; j < rows; ++j) {
        for (int i = 0; i < columns; ++i) {
            const double x = 1999.0 * i / (columns - 1), y = 999.0 * j / (rows - 1);
            const double lon = (x - camera.intrinsics.cx) / 310, lat = (y - camera.intrinsics.cy) / 300;
            outside += std::abs(lon) <= std::numbers::pi && std::abs(lat) <= std::numbers::pi / 2 ? 0 : 1;
        }
    }
    REQUIRE(outside > 0);
    const TempDir dir;
    const json report = run_verify_json({write_json_camera(dir, "lonlat", camera).string(), "--grid", "51x37"});
    CHECK(report.at("invalid_fraction").get<double>() == Approx(double(outside) / (columns * rows)).epsilon(1e-12));
}

TEST_CASE("libcam verify --heatmap writes a PNG of the chosen check") {
    const TempDir dir;
    // d = r (1 - 0.5 r^2) folds at |m| = 0.544, inside the image: part of it has no ray.
    const fs::path file = write_json_camera(dir, "fold", lens_camera(LensType::OpenCv4, {-0.5, 0, 0, 0}, {1600, 1200}));
    for (const std::string check : {"", "undistort-opencv-default", "round-trip"}) {
        INFO("--check '" << check << "'");
        const fs::path png = dir / ("map" + check + ".png");
        Args args{"verify", file.string(), "--grid", "64x48", "--heatmap", png.string()};
        if (!check.empty()) args = args + Args{"--check", check};
        const CliResult r = run_libcam(args);
        INFO(r.describe());
        REQUIRE(r.exit_code == 0);
        const cv::Mat image = cv::imread(png.string(), cv::IMREAD_UNCHANGED);
        REQUIRE_FALSE(image.empty());
        CHECK(image.type() == CV_8UC3);
        // The map is the 1600x1200 image at 720x540, with a title, scale bar and legend around it.
        CHECK(image.cols > 720);
        CHECK(image.cols < 1400);
        CHECK(image.rows > 540);
        CHECK(image.rows < 1000);
    }
}

TEST_CASE("libcam verify --heatmap refuses what it cannot draw, and writes nothing") {
    const TempDir dir;
    const fs::path pinhole = write_json_camera(dir, "pinhole", lens_camera(LensType::Pinhole, {}));
    const fs::path fisheye = write_json_camera(dir, "fisheye", lens_case("FISHEYE mild"));
    const fs::path png = dir / "map.png";

    const CliResult bad_name = run_libcam({"verify", pinhole.string(), "--heatmap", png.string(), "--check", "nonsense"});
    INFO(bad_name.describe());
    CHECK(bad_name.exit_code == 2);
    CHECK(bad_name.out.empty());
    CHECK_FALSE(fs::exists(png));

    // mrcal has no FISHEYE: that check was skipped, so there is nothing to draw.
    const CliResult skipped =
        run_libcam({"verify", fisheye.string(), "--grid", "8x6", "--heatmap", png.string(), "--check", "project-mrcal"});
    INFO(skipped.describe());
    CHECK(skipped.exit_code == 1);
    CHECK(skipped.out.empty());
    CHECK(std::count(skipped.err.begin(), skipped.err.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(png));

    const CliResult check_alone = run_libcam({"verify", pinhole.string(), "--check", "round-trip"});
    CHECK(check_alone.exit_code == 2);
    CHECK(check_alone.out.empty());
}

TEST_CASE("libcam verify: a malformed file fails with one line, a malformed grid is a usage error") {
    const TempDir dir;
    const fs::path truncated = dir / "truncated.json";
    write_whole_file(truncated, "{\"model\": \"OPENCV8\", \"image_size\": [6016, 40");
    for (const fs::path& file : {truncated, dir / "missing.json"}) {
        const CliResult r = run_libcam({"verify", file.string()});
        INFO(r.describe());
        CHECK(r.exit_code == 1);
        CHECK(r.out.empty());
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
        CHECK(r.err.find(file.filename().string()) != std::string::npos);
    }

    const fs::path pinhole = write_json_camera(dir, "pinhole", lens_camera(LensType::Pinhole, {}));
    for (const std::string grid : {"1x1", "abc", "2x1", "0x5", "10x", "2001x10", "3.5x4"}) {
        const CliResult r = run_libcam({"verify", pinhole.string(), "--grid", grid});
        INFO("--grid " << grid << "\n" << r.describe());
        CHECK(r.exit_code == 2);
        CHECK(r.out.empty());
        CHECK(r.err.find("--grid") != std::string::npos);
    }
}

TEST_CASE("libcam verify: MEI and UCM are checked by cv::omnidir, behind the camera too") {
    const TempDir dir;
    for (const std::string name : {"MEI xi 1.45", "MEI xi 1", "UCM xi 0.8"}) {
        INFO(name);
        const json report = run_verify_json({write_json_camera(dir, "camera", lens_case(name)).string(), "--grid", "41x31"});
        CHECK(report.at("pass") == true);
        require_libcam_within_tolerance(report);
        const json project = check_named(report, "project-opencv");
        CHECK(project.at("library") == "cv::omnidir::projectPoints");
        CHECK(project.at("status") != "skipped");
        CHECK(project.at("max_px").get<double>() <= 1e-9);
        CHECK(check_named(report, "unproject-libcam-opencv").at("max_px").get<double>() <= 1e-9);
        const json undistort = check_named(report, "undistort-opencv-default");
        CHECK(undistort.at("library").get<std::string>().find("cv::omnidir::undistortPoints") != std::string::npos);
        CHECK(undistort.at("status") != "skipped");
        // cv::omnidir::undistortPoints has one fixed rule: the second rule's row says so.
        CHECK(check_named(report, "undistort-opencv-100").at("status") == "skipped");
        CHECK(check_named(report, "project-mrcal").at("status") == "skipped");
    }
}
