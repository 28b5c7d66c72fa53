// What libcam's layers share, in libcam::core: the error statistics and their one
// quantile rule, the pixel grid, the number formats, and the pixel origin.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/geometry/pixel_grid.hpp"
#include "libcam/geometry/pixel_origin.hpp"
#include "libcam/stats/error_stats.hpp"
#include "libcam/text/number_format.hpp"

using namespace libcam;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<double> one_to(int n) {
    std::vector<double> values(static_cast<std::size_t>(n));
    std::iota(values.begin(), values.end(), 1.0);
    return values;
}

}  // namespace

TEST_CASE("error_stats: nearest-rank quantiles, always a measured value") {
    const ErrorStats four = error_stats({4, 1, 3, 2});
    CHECK(four.count == 4);
    CHECK(four.median_px == 2);  // rank ceil(0.5 * 4) = 2
    CHECK(four.p99_px == 4);
    CHECK(four.max_px == 4);
    CHECK(four.rms_px == Approx(std::sqrt(7.5)));
    CHECK(error_stats({3, 1, 2}).median_px == 2);
    CHECK(error_stats(one_to(100)).p99_px == 99);
    CHECK(error_stats(one_to(1000)).p99_px == 990);
    CHECK(error_stats(one_to(1000)).median_px == 500);

    const std::vector<double> sorted = one_to(10);
    CHECK(nearest_rank_quantile(sorted, 0.0) == 1);  // rank clamped to 1
    CHECK(nearest_rank_quantile(sorted, 1.0) == 10);
    CHECK(nearest_rank_quantile(sorted, 0.31) == 4);
}

TEST_CASE("error_stats: no errors give count 0, a NaN error counts as infinitely wrong") {
    const ErrorStats none = error_stats({});
    CHECK(none.count == 0);
    CHECK(none.median_px == 0);
    CHECK(none.max_px == 0);

    const ErrorStats with_nan = error_stats({1.0, std::nan(""), 2.0});
    CHECK(with_nan.count == 3);
    CHECK(with_nan.median_px == 2);
    CHECK(with_nan.max_px == kInf);
    CHECK(with_nan.rms_px == kInf);
}

TEST_CASE("PixelGrid: both ends of each side, exactly, row by row") {
    const ImageSize size{1600, 1200};
    const PixelGrid grid{200, 150};
    const std::vector<Vec2> pixels = grid.pixels(size);
    REQUIRE(pixels.size() == 200u * 150u);
    CHECK(pixels.front() == Vec2(0, 0));
    CHECK(pixels[199] == Vec2(1599, 0));
    CHECK(pixels.back() == Vec2(1599, 1199));
    CHECK(pixels[200] == Vec2(0, grid.y(1, size)));
    CHECK(grid.step_x(size) == 1599.0 / 199.0);

    // One rounding per coordinate: the last lands on W-1 where step * index would not
    // (1/49 * 49 is 0.9999999999999999 in double).
    const PixelGrid fine{50, 2};
    CHECK(fine.x(49, {2, 2}) == 1.0);
    CHECK(fine.x(7, {2, 2}) == 7.0 / 49.0);

    // A side of one pixel: every coordinate is 0.
    CHECK(PixelGrid{3, 3}.pixels({1, 5}).back() == Vec2(0, 4));

    CHECK_THROWS_AS(PixelGrid({1, 5}).validate(), InvalidArgument);
    CHECK_THROWS_WITH(PixelGrid({4, 1}).validate("--grid"), Catch::Contains("--grid") && Catch::Contains("4x1"));
    CHECK_NOTHROW(PixelGrid({2, 2}).validate());
}

TEST_CASE("PixelGrid::pixels_in: the points of a box, its edges included") {
    const ImageSize size{101, 51};
    const PixelGrid grid{11, 6};  // steps of 10 px both ways
    const std::vector<Vec2> inside = grid.pixels_in(size, {20, 10}, {40, 30}, 1e-9);
    REQUIRE(inside.size() == 3u * 3u);
    CHECK(inside.front() == Vec2(20, 10));
    CHECK(inside.back() == Vec2(40, 30));
    CHECK(grid.pixels_in(size, {0, 0}, {100, 50}, 1e-9) == grid.pixels(size));
    CHECK(grid.pixels_in(size, {21, 11}, {29, 19}, 1e-9).empty());
}

TEST_CASE("tile_centres: the centres of equal tiles covering the image to its edges") {
    const std::vector<Vec2> centres = tile_centres({4, 2}, 2, 1);
    REQUIRE(centres.size() == 2);
    CHECK(centres[0] == Vec2(0.5, 0.5));  // the tile spans [-0.5, 1.5] x [-0.5, 1.5]
    CHECK(centres[1] == Vec2(2.5, 0.5));
    CHECK(tile_centres({640, 480}, 640, 480).back() == Vec2(639, 479));
}

TEST_CASE("format_number round-trips, and format_short is printf's %.3g, or as many digits as asked") {
    for (const double value : {0.1, 1.0 / 3.0, 1e-300, 6016.0, -2.5e17, 5e-324}) {
        CHECK(std::strtod(format_number(value).c_str(), nullptr) == value);  // (std::stod refuses subnormals)
    }
    CHECK(format_number(0.1) == "0.1");
    CHECK(format_number(kInf) == "inf");

    CHECK(format_short(1234.5678) == "1.23e+03");
    CHECK(format_short(0.000123456) == "0.000123");
    CHECK(format_short(1e-9) == "1e-09");
    CHECK(format_short(100.0) == "100");
    CHECK(format_short(kInf) == "inf");
    CHECK(format_short(1.0 / 3.0, 10) == "0.3333333333");
    CHECK(format_short(0.5, 6) == "0.5");
    CHECK(format_short(1.0 / 3.0, 40) == format_short(1.0 / 3.0, 17));  // no digits past double's
}

TEST_CASE("PixelOrigin: the row flip is its own inverse, and names read back") {
    const ImageSize size{3, 5};
    CHECK(flip_row(0.0, size) == 4.0);
    CHECK(opencv_pixel({1, 1}, PixelOrigin::BottomLeft, size) == Vec2(1, 3));
    CHECK(opencv_pixel({1, 1}, PixelOrigin::TopLeft, size) == Vec2(1, 1));
    CHECK(user_pixel(opencv_pixel({2, 0.5}, PixelOrigin::BottomLeft, size), PixelOrigin::BottomLeft, size) == Vec2(2, 0.5));
    for (const PixelOrigin origin : {PixelOrigin::BottomLeft, PixelOrigin::TopLeft}) {
        CHECK(pixel_origin_from_string(to_string(origin)) == origin);
    }
    CHECK_THROWS_AS(pixel_origin_from_string("middle"), InvalidArgument);
}
