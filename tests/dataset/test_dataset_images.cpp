// `libcam dataset`'s images in the formats people have: a JPEG's quality asked for and
// kept across a resumed run, and a float EXR image remapped as floats.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "cli_runner.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using libcam::test::run_libcam;
using libcam::test::TempDir;
using Json = nlohmann::json;

// A one-image COLMAP model of an OPENCV lens, its image named `name`.
void write_model(const fs::path& folder, const std::string& name) {
    fs::create_directories(folder);
    libcam::test::write_whole_file(folder / "cameras.txt", "1 OPENCV 160 120 150 148 80.5 60.2 -0.2 0.04 0 0\n");
    libcam::test::write_whole_file(folder / "images.txt", "1 1 0 0 0 0 0 0 1 " + name + "\n\n");
    libcam::test::write_whole_file(folder / "points3D.txt", "");
}

cv::Mat texture(int type) {
    cv::Mat image(120, 160, CV_32FC3);
    for (int y = 0; y < image.rows; ++y) {
        for (int x = 0; x < image.cols; ++x) {
            const float value = 0.5f + 0.4f * std::sin(x * 0.7f) * std::cos(y * 0.55f);
            image.at<cv::Vec3f>(y, x) = cv::Vec3f(value, 1.0f - value, 0.25f + 0.01f * (x % 7));
        }
    }
    cv::Mat converted;
    image.convertTo(converted, type, type == CV_8UC3 ? 255.0 : 1.0);
    return converted;
}

Json run_json(const std::vector<std::string>& args) {
    const libcam::test::CliResult result = run_libcam(args);
    INFO(result.describe());
    REQUIRE(result.exit_code == 0);
    return Json::parse(result.out);
}

}  // namespace

TEST_CASE("dataset: --jpeg-quality sets the JPEG's quality, and a new quality writes the images again", "[dataset]") {
    TempDir dir;
    write_model(dir / "model", "photo.jpg");
    fs::create_directories(dir / "images");
    REQUIRE(cv::imwrite((dir / "images" / "photo.jpg").string(), texture(CV_8UC3), {cv::IMWRITE_JPEG_QUALITY, 100}));
    auto run = [&](const std::string& out, int quality) {
        return run_json({"dataset", (dir / "model").string(), "--images", (dir / "images").string(), "-o",
                         (dir / out).string(), "--json", "--jpeg-quality", std::to_string(quality)});
    };
    run("low", 30);
    run("high", 100);
    const auto low_bytes = fs::file_size(dir / "low" / "images" / "photo.jpg");
    const auto high_bytes = fs::file_size(dir / "high" / "images" / "photo.jpg");
    // The same image encoded by OpenCV at each quality: the sizes libcam's files must have.
    const cv::Mat written = cv::imread((dir / "high" / "images" / "photo.jpg").string());
    std::vector<unsigned char> at30;
    REQUIRE(cv::imencode(".jpg", written, at30, {cv::IMWRITE_JPEG_QUALITY, 30}));
    CHECK(low_bytes < high_bytes / 2);
    CHECK(static_cast<double>(low_bytes) == Approx(static_cast<double>(at30.size())).epsilon(0.15));

    // Run again with the same quality: kept; with another: written again.
    CHECK(run("low", 30)["images_kept"] == 1);
    const Json again = run("low", 90);
    CHECK(again["images_written"] == 1);
    CHECK(fs::file_size(dir / "low" / "images" / "photo.jpg") > low_bytes);

    const libcam::test::CliResult wrong = run_libcam({"dataset", (dir / "model").string(), "-o", (dir / "x").string(),
                                                      "--no-images", "--jpeg-quality", "0"});
    CHECK(wrong.exit_code != 0);
    CHECK(wrong.err.find("--jpeg-quality: expected 1 to 100, got 0") != std::string::npos);
}

TEST_CASE("dataset: a float EXR image is remapped as floats, its values kept in range and not rounded to 8 bits", "[dataset]") {
    TempDir dir;
    write_model(dir / "model", "radiance.exr");
    fs::create_directories(dir / "images");
    const cv::Mat source = texture(CV_32FC3);
    REQUIRE(cv::imwrite((dir / "images" / "radiance.exr").string(), source));
    run_json({"dataset", (dir / "model").string(), "--images", (dir / "images").string(), "-o", (dir / "out").string(),
              "--json", "--interpolation", "linear"});
    const cv::Mat result = cv::imread((dir / "out" / "images" / "radiance.exr").string(), cv::IMREAD_UNCHANGED);
    REQUIRE(result.type() == CV_32FC3);
    // Values stay those of a blend of the source's: in its range, not rounded to 8 bits.
    double low, high;
    cv::minMaxLoc(result.reshape(1), &low, &high);
    CHECK(low >= 0.0);
    CHECK(high <= 1.0 + 1e-6);
    std::size_t fractional = 0;
    for (int y = 0; y < result.rows; ++y) {
        for (int x = 0; x < result.cols; ++x) {
            const float value = result.at<cv::Vec3f>(y, x)[0];
            fractional += std::abs(value * 255 - std::round(value * 255)) > 0.01;
        }
    }
    CHECK(fractional > static_cast<std::size_t>(result.total() / 2));
}
