// The command-line program with lens distortion: `libcam convert` between every format
// that can hold the model, `libcam rays --from FILE` through the lens, and pixels with
// no ray reported as {"valid": false, "direction": null}.

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

using libcam::test::run_libcam;
using libcam::test::TempDir;
using libcam::test::write_whole_file;
using nlohmann::json;

namespace {

// OPENCV4 with k1 = -0.5 only, fx = fy = 500, cx = 499.5, cy = 374.5, 1000x750, at the
// origin looking down +z with OpenCV axes (R = I, t = 0).
// Radially, r_d(r) = r (1 - 0.5 r^2): increasing up to r = sqrt(2/3), where it reaches
// (2/3) sqrt(2/3) = 0.5443. Pixels farther than that (x 500) from the centre have no ray.
const char* kBarrelJson = R"({
  "model": "OPENCV4",
  "image_size": [1000, 750],
  "K": [[500, 0, 499.5], [0, 500, 374.5], [0, 0, 1]],
  "dist": [-0.5, 0, 0, 0],
  "R": [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
  "t": [0, 0, 0]
})";

// r with r (1 - 0.5 r^2) = target on [0, sqrt(2/3)], by bisection (independent of libcam).
double undistorted_radius(double target) {
    double low = 0.0, high = std::sqrt(2.0 / 3.0);
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (low + high);
        (mid * (1 - 0.5 * mid * mid) < target ? low : high) = mid;
    }
    return 0.5 * (low + high);
}

json rays_json(const std::vector<std::string>& args) {
    const auto result = run_libcam(args);
    INFO(result.describe());
    REQUIRE(result.exit_code == 0);
    return json::parse(result.out);
}

}  // namespace

TEST_CASE("rays through a distorted lens: inside the fold a ray, past it valid false and direction null") {
    TempDir dir;
    write_whole_file(dir / "barrel.json", kBarrelJson);
    // Pixel 250 px right of the centre: distorted radius 0.5; pixel 300 px right: 0.6 > 0.5443.
    const json out = rays_json({"rays", "--from", (dir / "barrel.json").string(), "--json", "--pixels", "749.5,374.5",
                                "799.5,374.5", "499.5,374.5"});
    const json& rays = out.at("rays");
    REQUIRE(rays.size() == 3);

    const double r = undistorted_radius(0.5);  // the ray is (r, 0, 1), normalised
    const double norm = std::hypot(r, 1.0);
    REQUIRE(rays[0].at("valid") == true);
    REQUIRE(std::abs(rays[0].at("direction")[0].get<double>() - r / norm) < 1e-12);
    REQUIRE(std::abs(rays[0].at("direction")[1].get<double>()) < 1e-12);
    REQUIRE(std::abs(rays[0].at("direction")[2].get<double>() - 1 / norm) < 1e-12);
    // Not a FOV camera: no look-at direction.
    REQUIRE(rays[0].at("direction_look_at").is_null());

    REQUIRE(rays[1].at("valid") == false);
    REQUIRE(rays[1].at("direction").is_null());

    REQUIRE(rays[2].at("valid") == true);  // the principal point looks straight ahead
    REQUIRE(std::abs(rays[2].at("direction")[2].get<double>() - 1.0) < 1e-15);
}

TEST_CASE("convert carries distortion through json, opencv-yaml, opencv-xml and cameramodel") {
    TempDir dir;
    write_whole_file(dir / "barrel.json", kBarrelJson);
    std::string previous = (dir / "barrel.json").string();
    for (const std::string format : {"opencv-yaml", "opencv-xml", "cameramodel", "json"}) {
        const std::string extension = format == "opencv-yaml" ? ".yaml"
                                      : format == "opencv-xml" ? ".xml"
                                      : format == "cameramodel" ? ".cameramodel"
                                                                : ".json";
        const std::string next = (dir / ("chain" + extension)).string();
        const auto result = run_libcam({"convert", "--from", previous, "--to", format, "-o", next});
        INFO(format << "\n" << result.describe());
        REQUIRE(result.exit_code == 0);
        previous = next;
    }
    // The end of the chain, as JSON, holds the same model and numbers as the start.
    const auto result = run_libcam({"convert", "--from", previous});
    REQUIRE(result.exit_code == 0);
    const json end = json::parse(result.out);
    REQUIRE(end.at("model") == "OPENCV4");
    REQUIRE(end.at("dist") == json::parse("[-0.5, 0, 0, 0]"));
    REQUIRE(end.at("K") == json::parse("[[500, 0, 499.5], [0, 500, 374.5], [0, 0, 1]]"));
    REQUIRE(end.at("fov_axes").empty());  // a lens with distortion is no FOV camera
}

TEST_CASE("a format that cannot hold the model is an error, and writes nothing") {
    TempDir dir;
    const std::string fisheye = R"({"model": "FISHEYE", "image_size": [800, 800],
      "K": [[300, 0, 399.5], [0, 300, 399.5], [0, 0, 1]], "dist": [0.1, 0.01, 0, 0],
      "R": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "t": [0, 0, 0]})";
    write_whole_file(dir / "fisheye.json", fisheye);
    for (const std::string format : {"cameramodel", "gl"}) {
        const std::string target = (dir / ("out." + format)).string();
        const auto result = run_libcam({"convert", "--from", (dir / "fisheye.json").string(), "--to", format, "-o", target});
        INFO(format << "\n" << result.describe());
        REQUIRE(result.exit_code == 1);
        REQUIRE(result.out.empty());
        REQUIRE_THAT(result.err, Catch::Matchers::Contains("FISHEYE"));
        REQUIRE_FALSE(std::filesystem::exists(target));
    }
}

TEST_CASE("a behind-the-camera fisheye ray comes back through rays") {
    // FISHEYE with zero coefficients is the equidistant lens: theta_d = theta, so a pixel
    // at distance f * theta from the centre looks theta from the optical axis. With
    // f = 100 and the pixel 200 px right of the centre, theta = 2 rad (past 90 degrees):
    // the ray is (sin 2, 0, cos 2), cos 2 < 0.
    TempDir dir;
    write_whole_file(dir / "equidistant.json", R"({"model": "FISHEYE", "image_size": [800, 800],
      "K": [[100, 0, 399.5], [0, 100, 399.5], [0, 0, 1]], "dist": [0, 0, 0, 0],
      "R": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "t": [0, 0, 0]})");
    const json out = rays_json({"rays", "--from", (dir / "equidistant.json").string(), "--json", "--pixels", "599.5,399.5"});
    const json& ray = out.at("rays")[0];
    REQUIRE(ray.at("valid") == true);
    REQUIRE(std::abs(ray.at("direction")[0].get<double>() - std::sin(2.0)) < 1e-12);
    REQUIRE(std::abs(ray.at("direction")[1].get<double>()) < 1e-12);
    REQUIRE(std::abs(ray.at("direction")[2].get<double>() - std::cos(2.0)) < 1e-12);
}
