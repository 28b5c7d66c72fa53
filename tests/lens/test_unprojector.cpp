// The batch paths (libcam/camera/unprojector.hpp, projector.hpp): every unprojection
// method in float and double against an independent reference (the pixel OpenCV's or
// mrcal's projection gives for the ray), the validity flags against the full solver
// (Camera::unproject_pixels, itself checked against hand-worked folds in
// test_unproject), and the batch, threaded, one-pixel and whole-image paths bit for bit
// the same. No timing is asserted here: that is `libcam bench`.

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "lens_cases.hpp"
#include "libcam/camera/projector.hpp"
#include "libcam/camera/simd.hpp"
#include "libcam/camera/unprojector.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

constexpr double kExactTolerance = 1e-9;  // px, the bound for `exact`: the 1e-9 px target
constexpr double kFastTolerance = 0.01;   // px, the bound for `fast` and `lut` on the wide lens

// What an Unprojector returned, in double, with the pixels as it was given them (the
// grid rounded to Scalar): a float method is measured against the pixel it saw.
struct Unprojected {
    std::vector<Vec2> pixels;
    std::vector<Vec3> directions;
    std::vector<bool> valid;
};

template <class Scalar>
Unprojected unproject_all(const Unprojector<Scalar>& unprojector, const std::vector<Vec2>& grid, UnprojectMethod method,
                          int threads = 1) {
    const Points2<Scalar> pixels = as_points2<Scalar>(grid);
    Points3<Scalar> directions;
    ValidFlags valid;
    unprojector.unproject(pixels, method, directions, valid, threads);
    Unprojected out;
    for (std::size_t i = 0; i < grid.size(); ++i) {
        out.pixels.emplace_back(double(pixels.x[i]), double(pixels.y[i]));
        out.directions.emplace_back(double(directions.x[i]), double(directions.y[i]), double(directions.z[i]));
        out.valid.push_back(valid[i] != 0);
    }
    return out;
}

// The worst distance from a valid pixel to the reference library's projection of its ray.
double worst_reprojection(const Camera& camera, const Unprojected& result) {
    std::vector<Vec3> rays;
    for (std::size_t i = 0; i < result.directions.size(); ++i) rays.push_back(result.valid[i] ? result.directions[i] : Vec3(0, 0, 1));
    const std::vector<Vec2> reprojected = reference_project(camera, rays);
    double worst = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (result.valid[i]) worst = std::max(worst, (reprojected[i] - result.pixels[i]).norm());
    }
    return worst;
}

// The full solver's flags for the same pixels: each model's own unproject (the certified
// solver of lens/undistort.hpp, or the closed form), pixel by pixel, in double.
std::vector<bool> full_solver_flags(const Camera& camera, const std::vector<Vec2>& pixels) {
    std::vector<bool> flags;
    visit_lens_model<double>(camera.lens.type, [&]<class Model>() {
        const typename Model::Parameters lens = Model::parameters(camera.lens.coefficients);
        for (const Vec2& pixel : pixels) {
            Vec3 ray;
            flags.push_back(Model::unproject(lens, camera.intrinsics.normalized_from_pixel(pixel), ray) && ray.allFinite());
        }
    });
    return flags;
}

// A grid reaching 10 % past every edge of the image: pixels beyond the table too.
std::vector<Vec2> grid_past_edges(const ImageSize& size, int nx, int ny) {
    std::vector<Vec2> pixels;
    for (const Vec2& p : pixel_grid(size, nx, ny)) {
        pixels.emplace_back(1.2 * p.x() - 0.1 * static_cast<double>(size.width),
                            1.2 * p.y() - 0.1 * static_cast<double>(size.height));
    }
    return pixels;
}

std::vector<LensCase> all_lens_cases() {
    std::vector<LensCase> cases = sanitized_subset(lens_cases());
    for (const FoldCase& fold : fold_cases()) cases.push_back({fold.name, fold.camera});
    return cases;
}

const LensCase& lens_case(const std::string& name) {
    static const std::vector<LensCase> cases = lens_cases();
    for (const LensCase& c : cases) {
        if (c.name == name) return c;
    }
    throw std::invalid_argument("no lens case " + name);
}

// The same lens on a smaller sensor: the image rescaled (pixel centres at integers).
Camera scaled_to_width(Camera camera, long width) {
    const double s = static_cast<double>(width) / static_cast<double>(camera.size.width);
    camera.size = {width, std::lround(s * static_cast<double>(camera.size.height))};
    Intrinsics& k = camera.intrinsics;
    k = {s * k.fx, s * k.fy, s * (k.cx + 0.5) - 0.5, s * (k.cy + 0.5) - 0.5, s * k.skew};
    return camera;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

template <class Scalar>
bool same_bits(const Points3<Scalar>& a, const Points3<Scalar>& b) {
    return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

template <class Scalar>
bool same_bits(const Points2<Scalar>& a, const Points2<Scalar>& b) {
    return same_bits(a.x, b.x) && same_bits(a.y, b.y);
}

template <class Scalar>
const char* scalar_name() {
    return sizeof(Scalar) == sizeof(float) ? "float" : "double";
}

}  // namespace

TEST_CASE("exact in double: every valid pixel of dense grids within 1e-9 px through OpenCV or mrcal, every model", "[sweep][engine]") {
    for (const LensCase& c : all_lens_cases()) {
        INFO(c.name);
        const Unprojector<double> unprojector(c.camera);
        const std::vector<Vec2> grid = pixel_grid(c.camera.size, sweep_side(161), sweep_side(121));
        const Unprojected result = unproject_all(unprojector, grid, UnprojectMethod::Exact);
        CHECK(worst_reprojection(c.camera, result) <= kExactTolerance);
        CHECK(result.valid == full_solver_flags(c.camera, grid));
    }
}

TEST_CASE("The real wide lens (6016x4016, OPENCV8), 601x401 pixels: exact within 1e-9 px, fast and lut within 0.01 px, float too", "[engine]") {
    const Camera camera = wide_reference_camera();
    const std::vector<Vec2> grid = pixel_grid(camera.size, 601, 401);
    const Unprojector<double> in_double(camera);
    const Unprojector<float> in_float(camera);
    for (UnprojectMethod method : kUnprojectMethods) {
        INFO(method_name(method));
        const Unprojected d = unproject_all(in_double, grid, method);
        const Unprojected f = unproject_all(in_float, grid, method);
        const double worst_double = worst_reprojection(camera, d), worst_float = worst_reprojection(camera, f);
        WARN("wide lens, " << method_name(method) << ": worst through cv::projectPoints " << worst_double
                           << " px (double), " << worst_float << " px (float)");
        CHECK(std::count(d.valid.begin(), d.valid.end(), true) == static_cast<long>(grid.size()));
        CHECK(f.valid == d.valid);
        CHECK(worst_double <= (method == UnprojectMethod::Exact ? kExactTolerance : kFastTolerance));
        // float: the pixel itself is only good to 2^-24 relative (4e-4 px at x = 6000).
        CHECK(worst_float <= kFastTolerance);
    }
}

TEST_CASE("Every method, in float and double, flags exactly the pixels the full solver flags, in and past the image", "[sweep]") {
    for (const LensCase& c : all_lens_cases()) {
        INFO(c.name);
        const std::vector<Vec2> grid = grid_past_edges(c.camera.size, sweep_side(121), sweep_side(91));
        const Unprojector<double> in_double(c.camera);
        const Unprojector<float> in_float(c.camera);
        const std::vector<bool> expected = full_solver_flags(c.camera, grid);
        const std::vector<Vec2> float_grid = unproject_all(in_float, grid, UnprojectMethod::Exact).pixels;
        const std::vector<bool> expected_float = full_solver_flags(c.camera, float_grid);
        for (UnprojectMethod method : kUnprojectMethods) {
            INFO(method_name(method));
            CHECK(unproject_all(in_double, grid, method).valid == expected);
            CHECK(unproject_all(in_float, grid, method).valid == expected_float);
        }
    }
}

TEST_CASE("Past a fold worked by hand, no method in either scalar type returns a ray", "[engine]") {
    for (const FoldCase& fold : fold_cases()) {
        INFO(fold.name);
        const std::vector<Vec2> grid = pixel_grid(fold.camera.size, 161, 121);
        const Unprojector<double> in_double(fold.camera);
        const Unprojector<float> in_float(fold.camera);
        for (UnprojectMethod method : kUnprojectMethods) {
            INFO(method_name(method));
            for (const Unprojected& result : {unproject_all(in_double, grid, method), unproject_all(in_float, grid, method)}) {
                std::size_t past_fold = 0;
                for (std::size_t i = 0; i < grid.size(); ++i) {
                    const double radius = fold.camera.intrinsics.normalized_from_pixel(result.pixels[i]).norm();
                    if (radius > fold.d_max * (1 + 1e-9)) {
                        ++past_fold;
                        CHECK_FALSE(result.valid[i]);
                    }
                    if (radius < fold.d_max * (1 - 1e-9)) CHECK(result.valid[i]);
                }
                CHECK(past_fold > grid.size() / 10);
            }
        }
    }
}

TEST_CASE("fast and lut on every lens of the test set, folds inside the image included: within 0.01 px", "[sweep][engine]") {
    // They answer only in the table cells checked to be within the budget (0.005 px at
    // five checkpoints); next to a fold, where the inverse steepens, the full solver does.
    for (const LensCase& c : all_lens_cases()) {
        INFO(c.name);
        const std::vector<Vec2> grid = pixel_grid(c.camera.size, sweep_side(121), sweep_side(91));
        const Unprojector<double> unprojector(c.camera);
        for (UnprojectMethod method : {UnprojectMethod::Fast, UnprojectMethod::Lut}) {
            INFO(method_name(method));
            const double worst = worst_reprojection(c.camera, unproject_all(unprojector, grid, method));
            WARN(c.name << ", " << method_name(method) << ": worst " << worst << " px");
            CHECK(worst <= kFastTolerance);
        }
    }
}

TEMPLATE_TEST_CASE("Batch paths: the same bits on 1, 2 and 3 threads, one pixel at a time, and for the whole image", "[engine]",
                   float, double) {
    using Scalar = TestType;
    for (const char* name : {"PINHOLE", "OPENCV8 wide", "FISHEYE strong", "LONLAT"}) {
        const Camera camera = scaled_to_width(lens_case(name).camera, 320);  // the whole image in milliseconds
        INFO(name << " " << scalar_name<Scalar>());
        const Unprojector<Scalar> unprojector(camera);
        const std::vector<Vec2> grid = grid_past_edges(camera.size, 97, 61);
        const Points2<Scalar> pixels = as_points2<Scalar>(grid);
        for (UnprojectMethod method : kUnprojectMethods) {
            INFO(method_name(method));
            Points3<Scalar> one, two, three;
            ValidFlags valid_one, valid_two, valid_three;
            unprojector.unproject(pixels, method, one, valid_one, 1);
            unprojector.unproject(pixels, method, two, valid_two, 2);
            unprojector.unproject(pixels, method, three, valid_three, 3);
            CHECK((same_bits(one, two) && same_bits(one, three)));
            CHECK((same_bits(valid_one, valid_two) && same_bits(valid_one, valid_three)));

            // Interleaved, as numpy's (N, 2) pixels and (N, 3) directions.
            const std::size_t n = grid.size();
            std::vector<Scalar> pairs(2 * n);
            for (std::size_t i = 0; i < n; ++i) pairs[2 * i] = pixels.x[i], pairs[2 * i + 1] = pixels.y[i];
            for (int threads : {1, 2}) {
                std::vector<Scalar> triples(3 * n, Scalar(-7));
                ValidFlags triples_valid(n, 7);
                unprojector.unproject_interleaved(pairs, method, triples, triples_valid, threads);
                Points3<Scalar> unpacked;
                for (std::size_t i = 0; i < n; ++i) {
                    unpacked.x.push_back(triples[3 * i]);
                    unpacked.y.push_back(triples[3 * i + 1]);
                    unpacked.z.push_back(triples[3 * i + 2]);
                }
                CHECK(same_bits(unpacked, one));
                CHECK(same_bits(triples_valid, valid_one));
            }

            // Lists of points (PreparedCamera::unproject's form), written over entries that
            // hold other values.
            for (int threads : {1, 2}) {
                std::vector<Unprojection> entries(n, Unprojection{Vec3::Constant(-7), true});
                unprojector.unproject(grid, method, entries, threads);
                Points3<Scalar> unpacked;
                ValidFlags entries_valid;
                for (const Unprojection& entry : entries) {
                    unpacked.x.push_back(Scalar(entry.direction.x()));
                    unpacked.y.push_back(Scalar(entry.direction.y()));
                    unpacked.z.push_back(Scalar(entry.direction.z()));
                    entries_valid.push_back(entry.valid ? 1 : 0);
                }
                CHECK(same_bits(unpacked, one));
                CHECK(same_bits(entries_valid, valid_one));
            }

            bool singles_agree = true;
            for (std::size_t i = 0; i < grid.size(); i += 7) {
                Eigen::Matrix<Scalar, 3, 1> direction = Eigen::Matrix<Scalar, 3, 1>::Zero();
                const bool valid = unprojector.unproject(Eigen::Matrix<Scalar, 2, 1>(pixels.x[i], pixels.y[i]), method, direction);
                const Eigen::Matrix<Scalar, 3, 1> batch(one.x[i], one.y[i], one.z[i]);
                singles_agree = singles_agree && valid == (valid_one[i] != 0) && (!valid || direction == batch);
            }
            CHECK(singles_agree);

            Points3<Scalar> image_one, image_two;
            ValidFlags image_valid_one, image_valid_two;
            unprojector.unproject_image(method, image_one, image_valid_one, 1);
            unprojector.unproject_image(method, image_two, image_valid_two, 2);
            Points2<Scalar> every_pixel;
            for (long y = 0; y < camera.size.height; ++y) {
                for (long x = 0; x < camera.size.width; ++x) {
                    every_pixel.x.push_back(Scalar(x));
                    every_pixel.y.push_back(Scalar(y));
                }
            }
            Points3<Scalar> listed;
            ValidFlags listed_valid;
            unprojector.unproject(every_pixel, method, listed, listed_valid);
            CHECK((same_bits(image_one, image_two) && same_bits(image_one, listed)));
            CHECK((same_bits(image_valid_one, image_valid_two) && same_bits(image_valid_one, listed_valid)));
        }
    }
}

namespace {

// Camera points for the projection tests: the rays of a grid of pixels at several
// depths, and the same points behind the camera and on its plane.
std::vector<Vec3> projection_points(const Camera& camera) {
    std::vector<Vec3> points;
    const std::vector<Unprojection> rays = PreparedCamera(camera).unproject(grid_past_edges(camera.size, sweep_side(41), sweep_side(31)));
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (!rays[i].valid) continue;
        const double depth = 0.5 + static_cast<double>(i % 7);
        points.push_back(rays[i].direction * depth);
        points.push_back(Vec3(rays[i].direction.x(), rays[i].direction.y(), -rays[i].direction.z()) * depth);
        points.push_back(Vec3(rays[i].direction.x(), rays[i].direction.y(), 0.0));
    }
    return points;
}

}  // namespace

TEST_CASE("Projection batches: OpenCV's or mrcal's pixel within 1e-9 px, Camera's flags, the same bits on any threads", "[engine]") {
    for (const LensCase& c : all_lens_cases()) {
        INFO(c.name);
        const std::vector<Vec3> points = projection_points(c.camera);
        const std::vector<Projection> expected = PreparedCamera(c.camera).project_camera_points(points);
        const std::vector<Vec2> reference = reference_project(c.camera, points);

        const Projector<double> projector(c.camera);
        Points2<double> pixels, pixels_two;
        ValidFlags valid, valid_two;
        const Points3<double> input = as_points3<double>(points);
        projector.project(input, pixels, valid, 1);
        projector.project(input, pixels_two, valid_two, 2);
        CHECK((same_bits(pixels.x, pixels_two.x) && same_bits(pixels.y, pixels_two.y) && same_bits(valid, valid_two)));

        double worst = 0;
        bool flags_agree = true;
        for (std::size_t i = 0; i < points.size(); ++i) {
            flags_agree = flags_agree && (valid[i] != 0) == expected[i].valid;
            // The reference libraries mirror points behind the camera instead of flagging them.
            if (valid[i] && points[i].z() > 0) worst = std::max(worst, (Vec2(pixels.x[i], pixels.y[i]) - reference[i]).norm());
        }
        CHECK(flags_agree);
        CHECK(worst <= kExactTolerance);

        // float: the pixel to float's rounding of the point and the result (a few 1e-4 px
        // at these image sizes); flags as in double except where the rounding crosses the
        // domain's edge, which these points do not approach.
        const Projector<float> in_float(c.camera);
        Points2<float> float_pixels;
        ValidFlags float_valid;
        in_float.project(as_points3<float>(points), float_pixels, float_valid, 1);
        double worst_float = 0;
        for (std::size_t i = 0; i < points.size(); ++i) {
            if (float_valid[i] && valid[i] && points[i].z() > 0) {
                worst_float = std::max(worst_float, (Vec2(float_pixels.x[i], float_pixels.y[i]) - reference[i]).norm());
            }
        }
        CHECK(same_bits(float_valid, valid));
        CHECK(worst_float <= 0.01);
    }
}

TEST_CASE("A pixel that is not a number has no ray, for every method", "[engine]") {
    const Camera camera = wide_reference_camera();
    const Unprojector<double> unprojector(camera);
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    for (UnprojectMethod method : kUnprojectMethods) {
        for (const Vec2& pixel : {Vec2(nan, 10), Vec2(10, nan), Vec2(inf, 10), Vec2(-inf, -inf)}) {
            Vec3 direction = Vec3::Zero();
            CHECK_FALSE(unprojector.unproject(pixel, method, direction));
        }
    }
}

// Such pixels, and pixels far outside the image, are located in the table by clamping
// to its border cells: in a batch of both scalars, among pixels that have rays, they
// get none and leave their neighbours' rays as the one-pixel call gives them.
TEMPLATE_TEST_CASE("Pixels that are not numbers or lie far outside the image have no ray in a batch", "[engine]",
                   double, float) {
    using Scalar = TestType;
    const Camera camera = wide_reference_camera();
    const Unprojector<Scalar> unprojector(camera);
    const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN(), inf = std::numeric_limits<Scalar>::infinity();
    const Scalar far = Scalar(1e30);
    const std::vector<std::pair<Scalar, Scalar>> rayless = {{nan, 10}, {10, nan}, {inf, 10}, {-inf, -inf},
                                                            {far, 10}, {-far, far}, {10, -far}};
    Points2<Scalar> pixels;
    for (std::size_t i = 0; i < 400; ++i) {  // across several of the batch engine's blocks of 128
        const bool odd = i % 2 == 1;
        const auto [x, y] = odd ? rayless[i / 2 % rayless.size()]
                                : std::pair<Scalar, Scalar>(Scalar(17 * i % camera.size.width), Scalar(11 * i % camera.size.height));
        pixels.x.push_back(x);
        pixels.y.push_back(y);
    }
    for (UnprojectMethod method : kUnprojectMethods) {
        INFO(method_name(method));
        Points3<Scalar> directions;
        ValidFlags valid;
        unprojector.unproject(pixels, method, directions, valid);
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            INFO("pixel " << i << ": " << pixels.x[i] << ", " << pixels.y[i]);
            Eigen::Matrix<Scalar, 3, 1> alone = Eigen::Matrix<Scalar, 3, 1>::Zero();
            const bool has_ray = unprojector.unproject(Eigen::Matrix<Scalar, 2, 1>(pixels.x[i], pixels.y[i]), method, alone);
            CHECK(bool(valid[i]) == (i % 2 == 0));
            CHECK(has_ray == (i % 2 == 0));
            if (has_ray) CHECK((directions.x[i] == alone.x() && directions.y[i] == alone.y() && directions.z[i] == alone.z()));
        }
    }
}

TEST_CASE("The table: the nodes' exact solutions and the checked cells, the same bits built on 1, 2 and 3 threads",
          "[engine]") {
    // The strong lens folds over inside the image: its outer nodes have no ray.
    for (const auto& [name, every_node_has_ray] :
         {std::pair{"OPENCV8 wide", true}, std::pair{"OPENCV8 mild", true}, std::pair{"OPENCV4 strong", false}}) {
        INFO(name);
        const Camera camera = lens_case(name).camera;
        const auto table = [&](int threads) {
            return Unprojector<double>(camera, UnprojectorOptions{.threads = threads}).table();
        };
        const UnprojectionTable<double> one = table(1), two = table(2), three = table(3);
        for (const UnprojectionTable<double>* other : {&two, &three}) {
            CHECK(same_bits(one.u_pairs, other->u_pairs));
            CHECK(same_bits(one.fast_ok, other->fast_ok));
            CHECK(same_bits(one.lut_ok, other->lut_ok));
        }
        if (!every_node_has_ray) continue;
        // Each node's u projects back to the node's pixel (OpenCV's models: the ray is
        // (u, 1)), and every row of cells was checked: on these lenses every cell passes.
        const PreparedCamera prepared(camera);
        double worst_px = 0;
        for (int j = 0; j < one.nodes_y; ++j) {
            for (int i = 0; i < one.nodes_x; ++i) {
                const std::size_t k = static_cast<std::size_t>(j * one.nodes_x + i);
                const Projection back = prepared.project_camera_point(Vec3(one.u_pairs[2 * k], one.u_pairs[2 * k + 1], 1));
                const Vec2 node(one.origin_x + i * one.step, one.origin_y + j * one.step);
                worst_px = std::max(worst_px, back.valid ? (back.pixel - node).norm() : HUGE_VAL);
            }
        }
        CHECK(worst_px < 1e-9);
        int unchecked = 0;
        for (int j = 1; j + 2 < one.nodes_y; ++j) {
            for (int i = 1; i + 2 < one.nodes_x; ++i) {
                const std::size_t k = static_cast<std::size_t>(j * one.nodes_x + i);
                unchecked += one.fast_ok[k] > 0 && one.lut_ok[k] > 0 ? 0 : 1;
            }
        }
        CHECK(unchecked == 0);
    }
}

TEST_CASE("Options out of range are refused, naming the option and the value") {
    const Camera camera = wide_reference_camera();
    CHECK_THROWS_WITH(Unprojector<double>(camera, UnprojectorOptions{.table_nodes = 3}),
                      "table_nodes: must be in [4, 100000], got 3");
    CHECK_THROWS_WITH(Unprojector<double>(camera, UnprojectorOptions{.approximation_budget_px = 0}),
                      "approximation_budget_px: must be > 0, got 0");
    CHECK_THROWS_WITH(Unprojector<double>(camera, UnprojectorOptions{.threads = -1}), "threads: must be >= 0, got -1");
}

TEST_CASE("Batches with coordinate arrays of different lengths are refused") {
    const Unprojector<double> unprojector(wide_reference_camera());
    Points2<double> pixels;
    pixels.x = {1, 2, 3};
    pixels.y = {1, 2};
    Points3<double> directions;
    ValidFlags valid;
    CHECK_THROWS_AS(unprojector.unproject(pixels, UnprojectMethod::Exact, directions, valid), InvalidArgument);
    Points3<double> points;
    points.x = {1};
    Points2<double> out;
    CHECK_THROWS_AS(Projector<double>(wide_reference_camera()).project(points, out, valid), InvalidArgument);
}

namespace {

// Every result of the batch paths on one camera, in Scalar, with the current instruction set.
template <class Scalar>
struct BatchResults {
    Points2<Scalar> pixels;
    ValidFlags projected;
    std::vector<Points3<Scalar>> rays, image;
    std::vector<ValidFlags> ray_valid, image_valid;
};

template <class Scalar>
BatchResults<Scalar> batch_results(const Projector<Scalar>& projector, const Unprojector<Scalar>& unprojector,
                                   const Points3<Scalar>& points, const Points2<Scalar>& grid) {
    BatchResults<Scalar> out;
    projector.project(points, out.pixels, out.projected);
    for (UnprojectMethod method : kUnprojectMethods) {
        out.rays.emplace_back();
        out.ray_valid.emplace_back();
        unprojector.unproject(grid, method, out.rays.back(), out.ray_valid.back(), 2);
        out.image.emplace_back();
        out.image_valid.emplace_back();
        unprojector.unproject_image(method, out.image.back(), out.image_valid.back());
    }
    return out;
}

template <class Scalar>
bool same_results(const BatchResults<Scalar>& a, const BatchResults<Scalar>& b) {
    bool same = same_bits(a.pixels, b.pixels) && same_bits(a.projected, b.projected);
    for (std::size_t m = 0; m < a.rays.size(); ++m) {
        same = same && same_bits(a.rays[m], b.rays[m]) && same_bits(a.ray_valid[m], b.ray_valid[m]) &&
               same_bits(a.image[m], b.image[m]) && same_bits(a.image_valid[m], b.image_valid[m]);
    }
    return same;
}

// Restores the default instruction set when a test ends, however it ends.
struct DefaultSimdTargetAfter {
    ~DefaultSimdTargetAfter() { set_simd_target(std::nullopt); }
};

}  // namespace

// The kernels are compiled once per instruction set from one source, without fused
// multiply-adds: every set must compute each point with the same operations, so the
// baseline's bits (checked against OpenCV and mrcal by the tests above) are every set's.
TEMPLATE_TEST_CASE("Every instruction set this CPU runs gives the baseline's bits, on every lens of the test set", "",
                   float, double) {
    using Scalar = TestType;
    const DefaultSimdTargetAfter restore;
    const std::vector<SimdTarget> targets = supported_simd_targets();
    REQUIRE(targets.front() == SimdTarget::Sse2);
    if (targets.size() == 1) {
        WARN("only the baseline set is compiled or run here: nothing to compare it with");
        return;
    }
    for (const LensCase& lens : lens_cases()) {
        const Camera camera = scaled_to_width(lens.camera, 160);
        INFO(lens.name << " " << scalar_name<Scalar>());
        const std::vector<Vec2> grid = grid_past_edges(camera.size, 53, 37);
        const Points3<Scalar> points = as_points3<Scalar>(projection_points(camera));
        const Projector<Scalar> projector(camera);
        const Unprojector<Scalar> unprojector(camera, UnprojectorOptions{.table_nodes = 40});  // small: built quickly
        set_simd_target(SimdTarget::Sse2);
        const BatchResults<Scalar> baseline = batch_results(projector, unprojector, points, as_points2<Scalar>(grid));
        for (SimdTarget target : targets) {
            INFO(simd_target_name(target));
            set_simd_target(target);
            CHECK(simd_target() == target);
            CHECK(same_results(baseline, batch_results(projector, unprojector, points, as_points2<Scalar>(grid))));
        }
    }
}

TEST_CASE("The instruction sets: names, the default, and a forced set this build lacks is refused") {
    const DefaultSimdTargetAfter restore;
    for (SimdTarget target : kSimdTargets) CHECK(simd_target_from_name(simd_target_name(target)) == target);
    CHECK_FALSE(simd_target_from_name("avx3").has_value());
    const std::vector<SimdTarget> targets = supported_simd_targets();
    if (std::getenv("LIBCAM_SIMD") == nullptr) CHECK(simd_target() == targets.back());  // the best by default
    for (SimdTarget target : kSimdTargets) {
        if (simd_target_supported(target)) {
            CHECK_NOTHROW(set_simd_target(target));
        } else {
            CHECK_THROWS_WITH(set_simd_target(target), Catch::Contains(std::string(simd_target_name(target))));
        }
    }
}

TEMPLATE_TEST_CASE("Interleaved projection (numpy's (N, 3) to (N, 2)) and projection on the caller's (3, N) rows give "
                   "the arrays' bits, on every lens of the test set",
                   "[sweep][engine]", float, double) {
    using Scalar = TestType;
    for (const LensCase& lens : all_lens_cases()) {
        const Camera camera = scaled_to_width(lens.camera, 160);
        INFO(lens.name << " " << scalar_name<Scalar>());
        // With points far outside the comfortable range, which the kernel's second pass
        // projects (scaled first), writing its pixels into the pairs too.
        std::vector<Vec3> camera_points = projection_points(camera);
        const double huge = std::numeric_limits<Scalar>::max() / 8, tiny = std::numeric_limits<Scalar>::min() * 8;
        for (std::size_t i = 0; i < camera_points.size(); i += 5) {
            camera_points.push_back(camera_points[i] * huge);
            camera_points.push_back(camera_points[i] * tiny);
        }
        const Points3<Scalar> points = as_points3<Scalar>(camera_points);
        const Projector<Scalar> projector(camera);
        Points2<Scalar> pixels;
        ValidFlags valid;
        projector.project(points, pixels, valid);
        const std::size_t n = points.size();
        std::vector<Scalar> interleaved_points(3 * n), interleaved_pixels(2 * n, Scalar(-7));
        for (std::size_t i = 0; i < n; ++i) {
            interleaved_points[3 * i] = points.x[i];
            interleaved_points[3 * i + 1] = points.y[i];
            interleaved_points[3 * i + 2] = points.z[i];
        }
        for (int threads : {1, 2}) {
            ValidFlags interleaved_valid(n, 7);
            projector.project_interleaved(interleaved_points, interleaved_pixels, interleaved_valid, threads);
            Points2<Scalar> unpacked;
            for (std::size_t i = 0; i < n; ++i) {
                unpacked.x.push_back(interleaved_pixels[2 * i]);
                unpacked.y.push_back(interleaved_pixels[2 * i + 1]);
            }
            CHECK(same_bits(unpacked, pixels));
            CHECK(same_bits(interleaved_valid, valid));
        }
        // One buffer holding x, y, z as the rows of a (3, N) array; the pixels into the rows
        // of a (2, N) one.
        std::vector<Scalar> rows(points.x);
        rows.insert(rows.end(), points.y.begin(), points.y.end());
        rows.insert(rows.end(), points.z.begin(), points.z.end());
        std::vector<Scalar> pixel_rows(2 * n, Scalar(-7));
        const std::span<const Scalar> in(rows);
        const std::span<Scalar> out(pixel_rows);
        ValidFlags row_valid(n, 7);
        projector.project(in.subspan(0, n), in.subspan(n, n), in.subspan(2 * n, n), out.subspan(0, n), out.subspan(n, n),
                          row_valid, 2);
        Points2<Scalar> from_rows;
        from_rows.x.assign(pixel_rows.begin(), pixel_rows.begin() + static_cast<std::ptrdiff_t>(n));
        from_rows.y.assign(pixel_rows.begin() + static_cast<std::ptrdiff_t>(n), pixel_rows.end());
        CHECK(same_bits(from_rows, pixels));
        CHECK(same_bits(row_valid, valid));
    }
    const Projector<Scalar> projector(wide_reference_camera());
    std::vector<Scalar> five(5);
    std::vector<std::uint8_t> flags(5);
    const std::span<const Scalar> coordinates(five);
    CHECK_THROWS_WITH(projector.project(coordinates, coordinates, coordinates.first(4), five, five, flags),
                      Catch::Contains("different lengths (5 and 4)"));
    // Pixels written over the points they come from, or over each other: refused.
    std::vector<Scalar> shared(10);
    const std::span<Scalar> first(shared.data(), 5), second(shared.data() + 5, 5);
    CHECK_THROWS_WITH(projector.project(first, coordinates, coordinates, first, second, flags),
                      Catch::Contains("must not overlap"));
    CHECK_THROWS_WITH(projector.project(coordinates, coordinates, coordinates, first, first, flags),
                      Catch::Contains("must not overlap"));
    CHECK_NOTHROW(projector.project(coordinates, coordinates, coordinates, first, second, flags));
    std::vector<Scalar> three(3), two(2), four(4);
    ValidFlags one(1);
    CHECK_THROWS_WITH(projector.project_interleaved(three, four, one),
                      Catch::Contains("project_interleaved: 1 flags need 3 point coordinates and 2 pixel coordinates, got 3 and 4"));
    CHECK_THROWS_AS(projector.project_interleaved(four, two, one), InvalidArgument);
    ValidFlags none;
    CHECK_NOTHROW(projector.project_interleaved(std::span<const Scalar>(), std::span<Scalar>(), none));
    // Pixels written over the points of a later block would change them: refused.
    std::vector<Scalar> buffer(5);
    CHECK_THROWS_WITH(projector.project_interleaved(std::span<const Scalar>(buffer.data(), 3), std::span<Scalar>(buffer.data() + 2, 2), one),
                      Catch::Contains("must not overlap"));
}

TEMPLATE_TEST_CASE("Interleaved unprojection refuses arrays of the wrong lengths and outputs over the pixels", "", float,
                   double) {
    using Scalar = TestType;
    const Unprojector<Scalar> unprojector(wide_reference_camera());
    std::vector<Scalar> two(2), three(3), four(4), six(6);
    ValidFlags one(1), two_flags(2);
    CHECK_THROWS_WITH(unprojector.unproject_interleaved(two, UnprojectMethod::Exact, four, one),
                      Catch::Contains("1 flags need 2 pixel coordinates and 3 direction coordinates, got 2 and 4"));
    CHECK_THROWS_AS(unprojector.unproject_interleaved(four, UnprojectMethod::Exact, three, one), InvalidArgument);
    CHECK_THROWS_AS(unprojector.unproject_interleaved(four, UnprojectMethod::Exact, six, one), InvalidArgument);
    CHECK_NOTHROW(unprojector.unproject_interleaved(four, UnprojectMethod::Exact, six, two_flags));
    ValidFlags none;
    CHECK_NOTHROW(unprojector.unproject_interleaved(std::span<const Scalar>(), UnprojectMethod::Fast, std::span<Scalar>(), none));
    std::vector<Scalar> buffer(8);
    CHECK_THROWS_WITH(unprojector.unproject_interleaved(std::span<const Scalar>(buffer.data(), 4), UnprojectMethod::Exact,
                                                        std::span<Scalar>(buffer.data() + 2, 6), two_flags),
                      Catch::Contains("must not overlap"));
}
