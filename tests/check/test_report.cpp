// libcam::report, called as a library: the pictures come back as libcam's Image (no
// cv::Mat in its API), their PNG bytes decode to the same pixels, and the errors a fit
// heatmap draws are computed by libcam::fit (fit_error_map).

#include <catch2/catch.hpp>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/fit/error_map.hpp"
#include "libcam/report/bench_plot.hpp"
#include "libcam/report/fit_heatmap.hpp"
#include "libcam/report/verify_heatmap.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using Catch::Matchers::Contains;

namespace {

Camera lens_camera(LensType type, std::vector<double> coefficients, ImageSize size) {
    Camera camera;
    camera.size = size;
    camera.intrinsics = {0.56 * static_cast<double>(size.width), 0.57 * static_cast<double>(size.width),
                         0.5 * static_cast<double>(size.width - 1) + 3.0, 0.5 * static_cast<double>(size.height - 1) - 2.0,
                         0.0};
    camera.lens = {type, std::move(coefficients)};
    return camera;
}

void check_well_formed(const Image& image) {
    REQUIRE(image.width > 0);
    REQUIRE(image.height > 0);
    CHECK(image.bgr.size() == static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3);
}

// The PNG decodes (with OpenCV, independently of report) to exactly the image's pixels.
void check_png_round_trip(const Image& image) {
    const std::string png = encode_png(image);
    REQUIRE(png.size() > 8);
    CHECK(png.substr(1, 3) == "PNG");
    const std::vector<std::uint8_t> bytes(png.begin(), png.end());
    const cv::Mat decoded = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
    REQUIRE(decoded.type() == CV_8UC3);
    REQUIRE(decoded.cols == image.width);
    REQUIRE(decoded.rows == image.height);
    CHECK(std::equal(image.bgr.begin(), image.bgr.end(), decoded.data));
}

}  // namespace

TEST_CASE("verify_heatmap: an Image of the map, title, scale and legend, and PNG bytes of the same pixels") {
    // d = r (1 - 0.5 r^2) folds inside the image: part of it has no ray (hatched).
    const Camera camera = lens_camera(LensType::OpenCv4, {-0.5, 0, 0, 0}, {1600, 1200});
    VerifyOptions options;
    options.grid_columns = 32;
    options.grid_rows = 24;
    const VerifyReport report = verify_camera(camera, options);
    const Image image = verify_heatmap(report, verify_check::round_trip);
    check_well_formed(image);
    // The map is the 1600x1200 image at 720x540, with a title, scale bar and legend around it.
    CHECK(image.width > kHeatmapMapSide);
    CHECK(image.width < 1400);
    CHECK(image.height > 540);
    CHECK(image.height < 1000);
    check_png_round_trip(image);

    const test::TempDir dir;
    write_png(dir / "map.png", image);
    const cv::Mat read = cv::imread((dir / "map.png").string(), cv::IMREAD_UNCHANGED);
    CHECK(read.cols == image.width);

    CHECK_THROWS_AS(verify_heatmap(report, "nonsense"), InvalidArgument);
}

TEST_CASE("verify_heatmap refuses a skipped check") {
    Camera camera = lens_camera(LensType::Fisheye, {0.01, -0.002, 0.0005, -0.0001}, {160, 120});
    VerifyOptions options;
    options.grid_columns = 8;
    options.grid_rows = 6;
    const VerifyReport report = verify_camera(camera, options);
    REQUIRE(report.find(verify_check::project_mrcal)->skipped());  // mrcal has no FISHEYE
    CHECK_THROWS_AS(verify_heatmap(report, verify_check::project_mrcal), Error);
}

TEST_CASE("fit_error_map: the fitted model's worst error at each tile centre, NaN where the source has no ray") {
    const Camera source = lens_camera(LensType::OpenCv4, {-0.5, 0, 0, 0}, {160, 120});
    FittedModel same;
    same.candidate = {"OPENCV4", LensType::OpenCv4};
    same.camera = source;
    same.camera.pose = Pose{};
    const FitErrorMap map = fit_error_map(source, same, {1.0, 10.0}, 40, 30);
    REQUIRE(map.error_px.size() == 40u * 30u);
    std::size_t no_ray = 0;
    for (const double e : map.error_px) {
        if (std::isnan(e)) {
            ++no_ray;
            continue;
        }
        CHECK(e < 1e-9);  // the source against itself
    }
    CHECK(std::isnan(map.error_px.front()));  // the corners are past the fold
    CHECK(no_ray < map.error_px.size());
    CHECK(map.error_px[15 * 40 + 20] < 1e-9);  // the centre has a ray

    Camera wider = same.camera;
    wider.intrinsics.fx *= 1.01;
    FittedModel off = same;
    off.camera = wider;
    const FitErrorMap off_map = fit_error_map(source, off, {}, 40, 30);
    // The centre tile is near the principal point: a 1% longer fx moves it little there.
    CHECK(off_map.error_px[15 * 40 + 20] < off_map.error_px[15 * 40 + 30]);

    CHECK_THROWS_AS(fit_error_map(source, same, {}, 0, 3), InvalidArgument);
}

TEST_CASE("fit_heatmap: one picture pixel per tile, the scale bar beside it, a caption below") {
    const Camera source = lens_camera(LensType::OpenCv4, {-0.05, 0.01, 2e-4, -3e-4}, {320, 240});
    CandidateReport chosen;
    chosen.fit.candidate = {"OPENCV4", LensType::OpenCv4};
    chosen.fit.camera = source;
    chosen.fit.camera.pose = Pose{};
    chosen.max_px = 0.0;
    FitOptions options;
    options.tolerance_px = 0.5;
    const Image image = fit_heatmap(source, Scene::circle(100, {159.5, 119.5}), options, chosen);
    check_well_formed(image);
    CHECK(image.width == 320 + 150);
    CHECK(image.height == 240 + 40);
    check_png_round_trip(image);
}

TEST_CASE("plot_speed_accuracy: a panel per camera, and rows without a measured error are not drawn") {
    BenchRow row;
    row.camera = "test";
    row.op = "unproject";
    row.library = "libcam";
    row.method = "exact";
    row.scalar = "double";
    row.model = "OPENCV4";
    row.ns_per_point = 50;
    row.error = error_stats({1e-12, 2e-12});
    BenchRow unmeasured = row;
    unmeasured.method = "nothing";
    unmeasured.error = error_stats({});
    const Image image = plot_speed_accuracy({row, unmeasured});
    check_well_formed(image);
    CHECK(image.width == 1000);
    CHECK(image.height == 700);

    CHECK_THROWS_WITH(plot_speed_accuracy({unmeasured}), Contains("no unprojection rows"));
}
