// `libcam dataset` beside COLMAP's own image_undistorter on one radial dataset: the images
// of a smooth pattern known at every ray, undistorted by both, each pixel compared with
// the pattern at its ray (so each program's error is its own, and where both have a pixel
// their difference is at most the sum), and the cameras each chose, compared.
//
// The source image is drawn here: each pixel's ray comes from cv::undistortPoints (OpenCV,
// iterated to 1e-14), not from libcam.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "cli_runner.hpp"
#include "libcam/io/camera_file.hpp"
#include "temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using libcam::test::TempDir;

// An OPENCV lens with fx != fy and an off-centre principal point (OpenCV's pixels).
constexpr int kWidth = 320, kHeight = 240;
constexpr double kFx = 300, kFy = 290, kCx = 165.3, kCy = 114.7;
const double kDistortion[4] = {-0.25, 0.06, 0.001, -0.0015};

// The pattern at the ray (a, b, 1): smooth, with about 100 px periods, in [8, 248].
double pattern(double a, double b) { return 128 + 60 * std::sin(20 * a + 0.3) * std::cos(17 * b) + 60 * std::cos(9 * (a - b)); }

cv::Mat draw_source() {
    std::vector<cv::Point2d> pixels;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) pixels.emplace_back(x, y);
    }
    const cv::Matx33d K(kFx, 0, kCx, 0, kFy, kCy, 0, 0, 1);
    const cv::Vec4d dist(kDistortion[0], kDistortion[1], kDistortion[2], kDistortion[3]);
    std::vector<cv::Point2d> rays;
    cv::undistortPoints(pixels, rays, K, dist, cv::noArray(), cv::noArray(),
                        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-14));
    cv::Mat image(kHeight, kWidth, CV_8UC1);
    for (int i = 0; i < kHeight * kWidth; ++i) {
        image.at<unsigned char>(i / kWidth, i % kWidth) = cv::saturate_cast<unsigned char>(pattern(rays[i].x, rays[i].y));
    }
    return image;
}

void write_model(const fs::path& folder) {
    fs::create_directories(folder);
    std::ostringstream camera;
    camera.precision(17);
    camera << "1 OPENCV " << kWidth << " " << kHeight << " " << kFx << " " << kFy << " " << kCx + 0.5 << " " << kCy + 0.5;
    for (const double k : kDistortion) camera << " " << k;
    libcam::test::write_whole_file(folder / "cameras.txt", camera.str() + "\n");
    libcam::test::write_whole_file(folder / "images.txt", "1 1 0 0 0 0 0 0 1 view.png\n\n");
    libcam::test::write_whole_file(folder / "points3D.txt", "");
}

// Each pixel of an undistorted image against the pattern at its ray, over the pixels whose
// ray lands at least 3 px inside the source image (both programs blend a pixel's
// neighbours, and OpenCV's iteration is only checked inside).
struct PatternError {
    double mean = 0, max = 0;
    std::size_t pixels = 0;
};

bool well_inside(double a, double b) {
    const double r2 = a * a + b * b, radial = 1 + kDistortion[0] * r2 + kDistortion[1] * r2 * r2;
    const double x = a * radial + 2 * kDistortion[2] * a * b + kDistortion[3] * (r2 + 2 * a * a);
    const double y = b * radial + kDistortion[2] * (r2 + 2 * b * b) + 2 * kDistortion[3] * a * b;
    const double u = kFx * x + kCx, v = kFy * y + kCy;
    return u >= 3 && v >= 3 && u <= kWidth - 4 && v <= kHeight - 4 && r2 < 0.6;
}

PatternError against_pattern(const cv::Mat& image, const libcam::Camera& camera) {
    const auto& k = camera.intrinsics;
    PatternError error;
    double sum = 0;
    for (int y = 0; y < image.rows; ++y) {
        for (int x = 0; x < image.cols; ++x) {
            const double a = (x - k.cx) / k.fx, b = (y - k.cy) / k.fy;
            if (!well_inside(a, b)) continue;
            const double difference = std::abs(image.at<unsigned char>(y, x) - pattern(a, b));
            sum += difference;
            error.max = std::max(error.max, difference);
            ++error.pixels;
        }
    }
    error.mean = error.pixels ? sum / error.pixels : 0;
    return error;
}

libcam::Camera pinhole_of(const fs::path& model) {
    const libcam::CameraFile file = libcam::read_camera_file(model);
    REQUIRE(file.camera.lens.type == libcam::LensType::Pinhole);
    return file.camera;
}

}  // namespace

TEST_CASE("dataset: libcam's and COLMAP image_undistorter's images agree where both have pixels", "[dataset][colmap]") {
    const std::string colmap = COLMAP_PROGRAM;
    if (colmap.empty() || !fs::exists(colmap)) {
        WARN("skipped: no colmap program");
        return;
    }
    TempDir dir;
    write_model(dir / "model");
    fs::create_directories(dir / "images");
    REQUIRE(cv::imwrite((dir / "images" / "view.png").string(), draw_source()));

    const libcam::test::CliResult ours =
        libcam::test::run_libcam({"dataset", (dir / "model").string(), "--images", (dir / "images").string(), "-o",
                                  (dir / "libcam").string(), "--interpolation", "linear", "--threads", "1"});
    INFO(ours.describe());
    REQUIRE(ours.exit_code == 0);
    const libcam::test::CliResult theirs = libcam::test::run_program(
        colmap, {"image_undistorter", "--image_path", (dir / "images").string(), "--input_path", (dir / "model").string(),
                 "--output_path", (dir / "colmap").string(), "--output_type", "COLMAP"});
    INFO(theirs.describe());
    REQUIRE(theirs.exit_code == 0);

    const libcam::Camera ours_camera = pinhole_of(dir / "libcam" / "sparse" / "0");
    const libcam::Camera theirs_camera = pinhole_of(dir / "colmap" / "sparse");
    const cv::Mat ours_image = cv::imread((dir / "libcam" / "images" / "view.png").string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat theirs_image = cv::imread((dir / "colmap" / "images" / "view.png").string(), cv::IMREAD_GRAYSCALE);
    REQUIRE(ours_image.cols == ours_camera.size.width);
    REQUIRE(theirs_image.cols == theirs_camera.size.width);

    // The cameras: COLMAP keeps the source's fx, fy and principal point and shrinks the
    // image to its undistorted border; libcam chooses square pixels about the centre.
    const auto& them = theirs_camera.intrinsics;
    CHECK(them.fx == Approx(kFx).epsilon(1e-9));
    CHECK(them.fy == Approx(kFy).epsilon(1e-9));
    // Its principal point scaled with the image, in COLMAP's pixels (centre of the first at 0.5).
    CHECK(them.cx + 0.5 == Approx((kCx + 0.5) * theirs_camera.size.width / kWidth).epsilon(1e-9));
    CHECK(them.cy + 0.5 == Approx((kCy + 0.5) * theirs_camera.size.height / kHeight).epsilon(1e-9));
    CHECK(ours_camera.intrinsics.fx == ours_camera.intrinsics.fy);

    // Each image against the pattern: both are bilinear blends of the same source pixels,
    // so each is within the 8-bit rounding plus the blend's error of a smooth pattern.
    const PatternError ours_error = against_pattern(ours_image, ours_camera);
    const PatternError theirs_error = against_pattern(theirs_image, theirs_camera);
    CHECK(ours_error.pixels > 40000);
    CHECK(theirs_error.pixels > 40000);
    CHECK(ours_error.mean < 0.6);
    CHECK(theirs_error.mean < 0.6);
    CHECK(ours_error.max < 2.5);
    CHECK(theirs_error.max < 2.5);

    // Directly: each of COLMAP's pixels against libcam's image at the same ray (bilinear).
    double sum = 0, largest = 0;
    std::size_t both = 0;
    const auto& us = ours_camera.intrinsics;
    for (int y = 0; y < theirs_image.rows; ++y) {
        for (int x = 0; x < theirs_image.cols; ++x) {
            const double a = (x - them.cx) / them.fx, b = (y - them.cy) / them.fy;
            const double u = us.fx * a + us.cx, v = us.fy * b + us.cy;
            if (!well_inside(a, b) || u < 0 || v < 0 || u > ours_image.cols - 1.001 || v > ours_image.rows - 1.001) continue;
            const int u0 = static_cast<int>(u), v0 = static_cast<int>(v);
            const double fu = u - u0, fv = v - v0;
            auto at = [&](int yy, int xx) { return static_cast<double>(ours_image.at<unsigned char>(yy, xx)); };
            const double ours_value = (1 - fv) * ((1 - fu) * at(v0, u0) + fu * at(v0, u0 + 1)) +
                                      fv * ((1 - fu) * at(v0 + 1, u0) + fu * at(v0 + 1, u0 + 1));
            const double difference = std::abs(ours_value - theirs_image.at<unsigned char>(y, x));
            sum += difference;
            largest = std::max(largest, difference);
            ++both;
        }
    }
    REQUIRE(both > 40000);
    CHECK(sum / both < 0.6);
    WARN("COLMAP's camera " << theirs_camera.size.width << "x" << theirs_camera.size.height << " fx " << them.fx << " fy "
                            << them.fy << " cx " << them.cx << " cy " << them.cy << "; libcam's "
                            << ours_camera.size.width << "x" << ours_camera.size.height << " f " << us.fx << " cx " << us.cx
                            << " cy " << us.cy << "\nagainst the pattern: libcam mean " << ours_error.mean << " max "
                            << ours_error.max << " over " << ours_error.pixels << " pixels, COLMAP mean "
                            << theirs_error.mean << " max " << theirs_error.max << " over " << theirs_error.pixels
                            << "\nCOLMAP's pixels against libcam's image at the same ray: mean " << sum / both << " max "
                            << largest << " over " << both << " pixels");
}
