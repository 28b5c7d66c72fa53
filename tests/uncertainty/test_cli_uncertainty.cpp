// libcam uncertainty as a user runs it: its JSON keys and summary on a small solve mrcal
// makes (mrcal_uncertainty.py), sigma_px against mrcal's own; and its refusals.

#include <catch2/catch.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.hpp"
#include "temp_dir.hpp"
#include "shell_output.hpp"

namespace {

using namespace libcam::test;
namespace fs = std::filesystem;

const fs::path kScript = fs::path(LIBCAM_DOCS_DIR).parent_path() / "tests/uncertainty/mrcal_uncertainty.py";

std::string python(const std::string& arguments) {
    return shell_output("/usr/bin/python3 '" + kScript.string() + "' " + arguments);
}

// One line on stderr, nothing on stdout, the exit code given.
void check_refusal(const CliResult& run, int exit_code, const std::string& says) {
    INFO(run.describe());
    CHECK(run.exit_code == exit_code);
    CHECK(run.out.empty());
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK(run.err.find(says) != std::string::npos);
}

}  // namespace

TEST_CASE("libcam uncertainty: JSON keys, the summary and a heatmap, sigma as mrcal's", "[uncertainty][cli]") {
    TempDir dir;
    const fs::path model = dir / "small.cameramodel";
    python("write '" + model.string() + "'");
    const CliResult run = run_libcam({"uncertainty", model.string(), "--at", "319.5,239.5", "--at", "20,30", "--json",
                                      "--heatmap", (dir / "sigma.png").string()});
    INFO(run.describe());
    REQUIRE(run.exit_code == 0);
    const nlohmann::json report = nlohmann::json::parse(run.out);
    const nlohmann::json mrcal = nlohmann::json::parse(python("sigma '" + model.string() + "' inf 319.5,239.5 20,30"));
    CHECK(report["observed_pixel_uncertainty_px"].get<double>() == Approx(mrcal["noise_px"].get<double>()).epsilon(1e-6));
    REQUIRE(report["at"].size() == 2);
    CHECK(report["at"][0]["pixel"] == nlohmann::json::array({319.5, 239.5}));
    for (int i = 0; i < 2; ++i) {
        CHECK(report["at"][i]["sigma_px"].get<double>() == Approx(mrcal["sigma_px"][i].get<double>()).epsilon(0.10));
    }
    // The share of the image under 1 px includes the share under 0.1 px; the worst sigma
    // where the corners were is at least the centre's.
    CHECK(report["share_below_1_px"].get<double>() >= report["share_below_0_1_px"].get<double>());
    CHECK(report["worst_observed_sigma_px"].get<double>() >= report["at"][0]["sigma_px"].get<double>());
    CHECK(report["parameters"].size() == 8);
    CHECK(fs::file_size(dir / "sigma.png") > 1000);

    const CliResult text = run_libcam({"uncertainty", model.string()});
    INFO(text.describe());
    REQUIRE(text.exit_code == 0);
    CHECK(text.out.find("worst inside the region the corners covered") != std::string::npos);
    CHECK(text.out.find("the image under 0.1 px") != std::string::npos);
}

TEST_CASE("libcam uncertainty refuses in one line: no observations, a pixel off the image", "[uncertainty][cli]") {
    TempDir dir;
    const fs::path camera = write_file(dir, "camera.yaml",
                                       "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\ncamera_matrix: !!opencv-matrix\n"
                                       "   rows: 3\n   cols: 3\n   dt: d\n   data: [ 500., 0., 320., 0., 500., 240., 0., 0., 1. ]\n"
                                       "distortion_coefficients: !!opencv-matrix\n   rows: 5\n   cols: 1\n   dt: d\n"
                                       "   data: [ 0., 0., 0., 0., 0. ]\n");
    check_refusal(run_libcam({"uncertainty", camera.string()}), 1, "no observations");
    const fs::path model = dir / "small.cameramodel";
    python("write '" + model.string() + "'");
    check_refusal(run_libcam({"uncertainty", model.string(), "--at", "700,20"}), 2, "--at: pixel (700, 20) is off");
    check_refusal(run_libcam({"uncertainty", model.string(), "--at", "7;20"}), 2, "--at");
}

TEST_CASE("libcam uncertainty on each camera's model of an mrcal solve of two: the file's camera, the whole solve",
          "[uncertainty][cli]") {
    TempDir dir;
    const fs::path first = dir / "rig-0.cameramodel", second = dir / "rig-1.cameramodel";
    python("write-rig '" + first.string() + "' '" + second.string() + "'");
    // Without --camera: the camera the model is (its icam_intrinsics), not a refusal.
    const CliResult run = run_libcam({"uncertainty", second.string(), "--at", "319.5,239.5", "--at", "20,30", "--json"});
    INFO(run.describe());
    REQUIRE(run.exit_code == 0);
    const nlohmann::json report = nlohmann::json::parse(run.out);
    const nlohmann::json mrcal = nlohmann::json::parse(python("sigma '" + second.string() + "' inf 319.5,239.5 20,30"));
    for (int i = 0; i < 2; ++i) {
        CHECK(report["at"][i]["sigma_px"].get<double>() == Approx(mrcal["sigma_px"][i].get<double>()).epsilon(1e-6));
    }
    // --camera picks the other one out of the same file.
    const CliResult other = run_libcam({"uncertainty", second.string(), "--camera", "0", "--at", "20,30", "--json"});
    REQUIRE(other.exit_code == 0);
    const nlohmann::json theirs = nlohmann::json::parse(python("sigma '" + first.string() + "' inf 20,30"));
    CHECK(nlohmann::json::parse(other.out)["at"][0]["sigma_px"].get<double>() ==
          Approx(theirs["sigma_px"][0].get<double>()).epsilon(1e-6));
    const CliResult text = run_libcam({"uncertainty", first.string()});
    REQUIRE(text.exit_code == 0);
    CHECK(text.out.find("in a solve of 2 cameras sharing 12 board poses") != std::string::npos);
}
