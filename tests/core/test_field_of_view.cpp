// The field of view through the lens (camera/field_of_view.hpp), against the angles worked
// by hand: a pinhole's 2 atan(W / 2 fx), an equidistant fisheye's W / f, and a barrel lens
// r (1 + k1 r^2) whose domain ends inside the image, its edge ray and its pixels without a
// ray found from the cubic directly.

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "libcam/camera/field_of_view.hpp"

using namespace libcam;

namespace {

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

Camera camera_640x480(LensType type, double f, std::vector<double> coefficients) {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = Intrinsics{f, f, 319.5, 239.5, 0.0};
    camera.lens.type = type;
    camera.lens.coefficients = std::move(coefficients);
    return camera;
}

// The undistorted radius r of r + k1 r^3 = m on the branch before the fold, by bisection.
double undistorted_radius(double k1, double m) {
    double low = 0, high = std::sqrt(-1 / (3 * k1));
    for (int i = 0; i < 200; ++i) {
        const double middle = (low + high) / 2;
        (middle + k1 * middle * middle * middle < m ? low : high) = middle;
    }
    return (low + high) / 2;
}

}  // namespace

TEST_CASE("field of view: a pinhole's is 2 atan(W / 2 fx), every pixel with a ray") {
    const FieldOfView fov = field_of_view(PreparedCamera(camera_640x480(LensType::Pinhole, 400, {})));
    // The edges -0.5 and 639.5 are 320 px from cx = 319.5.
    CHECK(fov.horizontal.degrees == Approx(degrees(2 * std::atan(320.0 / 400))).epsilon(1e-12));
    CHECK(fov.vertical.degrees == Approx(degrees(2 * std::atan(240.0 / 400))).epsilon(1e-12));
    CHECK(fov.horizontal.edge_to_edge);
    CHECK(fov.vertical.edge_to_edge);
    CHECK(fov.valid_angle_deg == Approx(90.0).epsilon(1e-12));
    CHECK(fov.rayless_fraction == 0.0);
}

TEST_CASE("field of view: an equidistant fisheye's is W / f radians, past 180 degrees") {
    const FieldOfView fov = field_of_view(PreparedCamera(camera_640x480(LensType::Fisheye, 200, {0, 0, 0, 0})));
    CHECK(fov.horizontal.degrees == Approx(degrees(640.0 / 200)).epsilon(1e-9));
    CHECK(fov.vertical.degrees == Approx(degrees(480.0 / 200)).epsilon(1e-9));
    CHECK(fov.horizontal.edge_to_edge);
    CHECK(fov.rayless_fraction == 0.0);
}

TEST_CASE("field of view: a barrel lens folding inside the image, to the last pixel with a ray") {
    // r (1 + k1 r^2) with k1 = -0.2 rises to its fold at r = 1 / sqrt(0.6) (1.291, an angle
    // of 52.24 degrees from the axis), where m = 2/3 r = 0.8607: pixels farther than
    // 0.8607 f = 258.2 px from the centre have no ray. The horizontal edges (320 px) are
    // past it; the vertical ones (240 px) inside.
    const double k1 = -0.2, f = 300;
    const double fold = std::sqrt(-1 / (3 * k1)), m_fold = fold * (1 + k1 * fold * fold);
    const FieldOfView fov = field_of_view(PreparedCamera(camera_640x480(LensType::OpenCv4, f, {k1, 0, 0, 0})));
    CHECK(fov.valid_angle_deg == Approx(degrees(std::atan(fold))).epsilon(1e-9));
    CHECK(fov.vertical.edge_to_edge);
    CHECK(fov.vertical.degrees == Approx(2 * degrees(std::atan(undistorted_radius(k1, 240 / f)))).epsilon(1e-9));
    // From each horizontal edge, steps of 640 / 1024 px inwards to the first pixel with a
    // ray: step i is 320 - 0.625 i px from the centre, the first within the fold at i = 99
    // (258.125 px; the fold is at 258.20).
    CHECK_FALSE(fov.horizontal.edge_to_edge);
    const double first = 320 - 0.625 * std::ceil((320 - m_fold * f) / 0.625);
    REQUIRE(first == 258.125);
    CHECK(fov.horizontal.degrees == Approx(2 * degrees(std::atan(undistorted_radius(k1, first / f)))).epsilon(1e-9));
    // The share of the 64 x 64 lattice of pixels (0 to 639 by 639/63, 0 to 479 by 479/63)
    // farther from the centre than the fold's image.
    int rayless = 0;
    for (int row = 0; row < 64; ++row) {
        for (int column = 0; column < 64; ++column) {
            const double x = 639.0 * column / 63 - 319.5, y = 479.0 * row / 63 - 239.5;
            const double m = std::hypot(x, y) / f;
            REQUIRE(std::abs(m - m_fold) > 1e-6);  // none on the fold itself, where rounding would decide
            rayless += m > m_fold ? 1 : 0;
        }
    }
    CHECK(rayless > 0);
    CHECK(fov.rayless_fraction == Approx(rayless / 4096.0).epsilon(1e-15));
}
