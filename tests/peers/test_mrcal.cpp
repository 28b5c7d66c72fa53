// Cross-checks against mrcal: libcam's .cameramodel files are read by libmrcal's own
// parser, and projections are computed by libmrcal's C functions. Expected values
// come from mrcal (or from numbers written out here by hand), never from libcam.

#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "temp_dir.hpp"
#include "libcam/convert/look_at_convert.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/mrcal.hpp"
#include "libcam/interop/mrcal_diagnostic.hpp"
#include "libcam/interop/detail/mrcal_c.hpp"
#include "libcam/io/camera_file.hpp"
#include "support.hpp"

using namespace libcam;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

using libcam::test::TempDir;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct ModelDeleter {
    void operator()(mrcal_cameramodel_t* model) const { mrcal_free_cameramodel(&model); }
};
using ModelPtr = std::unique_ptr<mrcal_cameramodel_t, ModelDeleter>;

ModelPtr mrcal_read_file(const fs::path& path) { return ModelPtr(mrcal_read_cameramodel_file(path.c_str())); }

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void write_text(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

const ImageSize kSizes[] = {{1920, 1080}, {640, 4000}, {4000, 500}, {1000, 1000}, {3, 3}, {1, 1}};

std::vector<Camera> test_cameras() {
    std::vector<Camera> cameras;
    for (int i = 0; i < 24; ++i) {
        const ImageSize size = kSizes[i % std::size(kSizes)];
        const FovAxis axis = libcam::test::random_axis(i);
        if (i % 6 == 1) cameras.push_back(to_camera(libcam::test::random_look_at_camera(size, axis, 1.0, 1.0 + 1e-9)));
        else if (i % 6 == 4) cameras.push_back(to_camera(libcam::test::random_look_at_camera(size, axis, 179.0 - 1e-9, 179.0)));
        else cameras.push_back(to_camera(libcam::test::random_look_at_camera(size, axis)));
    }
    return cameras;
}

std::vector<Vec2> pixel_grid(const ImageSize& size) {
    const double W = static_cast<double>(size.width);
    const double H = static_cast<double>(size.height);
    std::vector<Vec2> pixels;
    for (double y : {-0.5, 0.0, H / 3.0, (H - 1.0) / 2.0, H - 1.0, H - 0.5})
        for (double x : {-0.5, 0.0, W / 3.0, (W - 1.0) / 2.0, W - 1.0, W - 0.5}) pixels.emplace_back(x, y);
    return pixels;
}

mrcal_lensmodel_t pinhole_model() {
    mrcal_lensmodel_t model{};
    model.type = MRCAL_LENSMODEL_PINHOLE;
    return model;
}

// mrcal's own pixel for camera-frame points, intrinsics given as mrcal stores them.
std::vector<Vec2> mrcal_pixels(const std::vector<Vec3>& points, const double* intrinsics) {
    std::vector<mrcal_point3_t> p(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) p[i] = {{points[i].x(), points[i].y(), points[i].z()}};
    std::vector<mrcal_point2_t> q(points.size());
    const mrcal_lensmodel_t model = pinhole_model();
    REQUIRE(mrcal_project(q.data(), nullptr, nullptr, p.data(), static_cast<int>(p.size()), &model, intrinsics));
    std::vector<Vec2> out;
    for (const mrcal_point2_t& pixel : q) out.emplace_back(pixel.x, pixel.y);
    return out;
}

}  // namespace

TEST_CASE("A .cameramodel written by libcam loads in libmrcal with the same numbers, bit for bit", "[mrcal]") {
    TempDir dir;
    int index = 0;
    for (const Camera& camera : test_cameras()) {
        const fs::path path = dir.path() / ("camera" + std::to_string(index++) + ".cameramodel");
        write_camera_file(path, camera, CameraFormat::Cameramodel);
        const ModelPtr model = mrcal_read_file(path);
        REQUIRE(model != nullptr);
        CHECK(model->lensmodel.type == MRCAL_LENSMODEL_PINHOLE);
        CHECK(model->imagersize[0] == static_cast<unsigned>(camera.size.width));
        CHECK(model->imagersize[1] == static_cast<unsigned>(camera.size.height));
        CHECK(model->intrinsics[0] == camera.intrinsics.fx);
        CHECK(model->intrinsics[1] == camera.intrinsics.fy);
        CHECK(model->intrinsics[2] == camera.intrinsics.cx);
        CHECK(model->intrinsics[3] == camera.intrinsics.cy);
        const Vec3 rvec = camera.pose.rvec();
        for (int i = 0; i < 3; ++i) {
            CHECK(model->rt_cam_ref[i] == rvec(i));
            CHECK(model->rt_cam_ref[3 + i] == camera.pose.t(i));
        }
        // The r in rt_cam_ref is, by mrcal's own Rodrigues, the camera's R.
        double R[9];
        mrcal_R_from_r(R, nullptr, model->rt_cam_ref);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) CHECK(std::abs(R[3 * r + c] - camera.pose.R(r, c)) <= 1e-14);

        // The in-memory text says the same to libmrcal's string parser.
        const std::string text = format_camera(camera, CameraFormat::Cameramodel);
        CHECK(text == slurp(path));
        const ModelPtr from_string(mrcal_read_cameramodel_string(text.data(), static_cast<int>(text.size())));
        REQUIRE(from_string != nullptr);
        CHECK(from_string->intrinsics[0] == camera.intrinsics.fx);
        CHECK(from_string->rt_cam_ref[5] == camera.pose.t.z());

        // And libcam reads the file back to the same camera.
        const CameraFile back = read_camera_file(path);
        CHECK(back.camera.intrinsics.fx == camera.intrinsics.fx);
        CHECK(back.camera.intrinsics.fy == camera.intrinsics.fy);
        CHECK(back.camera.intrinsics.cx == camera.intrinsics.cx);
        CHECK(back.camera.intrinsics.cy == camera.intrinsics.cy);
        CHECK(back.camera.size == camera.size);
        CHECK(back.camera.pose.t == camera.pose.t);
        CHECK((back.camera.pose.R - camera.pose.R).cwiseAbs().maxCoeff() <= 1e-14);
    }
}

TEST_CASE("A hand-written .cameramodel reads into libcam with mrcal's meaning", "[mrcal]") {
    // rt_cam_ref = (0, 0, pi/2, 1, 2, 3): R turns x into y; a world point X maps to
    // R X + t. Worked by hand: X = (1, 0, 5) -> (0, 1, 5) + (1, 2, 3) = (1, 3, 8).
    TempDir dir;
    const fs::path path = dir.path() / "hand.cameramodel";
    write_text(path,
               "# written by hand\n"
               "{\n"
               "    'lensmodel':  'LENSMODEL_PINHOLE',\n"
               "    'intrinsics': [ 1234.5, 1100.25, 639.5, 359.5 ],\n"
               "    'imagersize': [ 1280, 720 ],\n"
               "    'extrinsics': [ 0, 0, 1.5707963267948966, 1, 2, 3 ]\n"
               "}\n");
    const Camera camera = read_camera_file(path).camera;
    CHECK(camera.size == ImageSize{1280, 720});
    CHECK(camera.intrinsics.fx == 1234.5);
    CHECK(camera.intrinsics.fy == 1100.25);
    CHECK(camera.intrinsics.cx == 639.5);
    CHECK(camera.intrinsics.cy == 359.5);
    CHECK(camera.intrinsics.skew == 0.0);
    const Vec3 p = camera.pose.camera_from_world(Vec3(1, 0, 5));
    CHECK((p - Vec3(1, 3, 8)).norm() <= 1e-15);
    // Pixel by hand: (1234.5 * 1/8 + 639.5, 1100.25 * 3/8 + 359.5).
    const Projection q = PreparedCamera(camera).project(Vec3(1, 0, 5));
    REQUIRE(q.valid);
    CHECK(std::abs(q.pixel.x() - (1234.5 / 8 + 639.5)) <= 1e-12);
    CHECK(std::abs(q.pixel.y() - (1100.25 * 3 / 8 + 359.5)) <= 1e-12);
}

TEST_CASE("A CAHVOR .cameramodel reads with mrcal's meaning and writes back as libmrcal reads it", "[mrcal]") {
    const fs::path source = fs::path(LIBCAM_FUZZ_CORPUS) / "cameramodel" / "cahvor.cameramodel";
    const Camera camera = read_camera_file(source).camera;
    REQUIRE(camera.lens.type == LensType::Cahvor);
    CHECK(camera.lens.coefficients == std::vector<double>{-0.001, 0.002, -0.637, -0.002, 0.016});
    // The pixel mrcal's projection tests record for their point (-1.1, 0.3, 1) with these
    // intrinsics (test-projections.py).
    const Projection q = PreparedCamera(camera).project(Vec3(-1.1, 0.3, 1.0));
    REQUIRE(q.valid);
    CHECK((q.pixel - Vec2(-92.63813066, 1653.09646897)).norm() < 1e-7);

    TempDir dir;
    const fs::path path = dir.path() / "cahvor.cameramodel";
    write_camera_file(path, camera, CameraFormat::Cameramodel);
    const ModelPtr model = mrcal_read_file(path);
    REQUIRE(model != nullptr);
    CHECK(model->lensmodel.type == MRCAL_LENSMODEL_CAHVOR);
    const double expected[] = {4842.918, 4842.771, 1970.528, 1085.302, -0.001, 0.002, -0.637, -0.002, 0.016};
    for (int i = 0; i < 9; ++i) CHECK(model->intrinsics[i] == expected[i]);
}

TEST_CASE("mrcal_project of camera-frame points along each ray returns the pixel", "[mrcal]") {
    TempDir dir;
    int checked = 0;
    for (const Camera& camera : test_cameras()) {
        // Intrinsics and extrinsics as libmrcal read them from libcam's file.
        const fs::path path = dir.path() / "camera.cameramodel";
        write_camera_file(path, camera, CameraFormat::Cameramodel);
        const ModelPtr model = mrcal_read_file(path);
        REQUIRE(model != nullptr);
        CAPTURE(camera.size.width, camera.size.height, camera.intrinsics.fx, camera.intrinsics.fy);

        const PreparedCamera prepared(camera);
        for (const Vec2& pixel : pixel_grid(camera.size)) {
            const Ray ray = prepared.ray(pixel);
            REQUIRE(ray.valid);
            const Vec3 direction = camera.pose.R * ray.direction;  // camera frame, unit
            std::vector<Vec3> points;
            for (double depth : {0.5, 3.0, 100.0, 1e4}) points.push_back(depth * direction);
            const std::vector<Vec2> by_mrcal = mrcal_pixels(points, model->intrinsics);
            const std::vector<Vec2> by_wrapper = mrcal_project_points(camera, points);
            for (std::size_t i = 0; i < points.size(); ++i) {
                CAPTURE(pixel.x(), pixel.y(), by_mrcal[i].x(), by_mrcal[i].y());
                CHECK((by_mrcal[i] - pixel).cwiseAbs().maxCoeff() <= 1e-9);
                CHECK(by_wrapper[i] == by_mrcal[i]);
                // libcam's own projection agrees too.
                const Projection own = prepared.project_camera_point(points[i]);
                REQUIRE(own.valid);
                CHECK((own.pixel - by_mrcal[i]).cwiseAbs().maxCoeff() <= 1e-9);
                ++checked;
            }

            // World points through mrcal's rt_cam_ref transform, then mrcal_project. The
            // world point's own rounding (|eye| up to ~170) limits this at short range
            // (see test_opencv): allow that conditioning, never less than 1e-9 px.
            for (double depth : {3.0, 100.0, 1e4}) {
                const Vec3 world = ray.origin + depth * ray.direction;
                double camera_point[3];
                mrcal_transform_point_rt(camera_point, nullptr, nullptr, model->rt_cam_ref, world.data());
                const Vec2 q = mrcal_pixels({Vec3(camera_point[0], camera_point[1], camera_point[2])}, model->intrinsics)[0];
                const Vec2 m = camera.intrinsics.normalized_from_pixel(pixel);
                const double f = std::max(camera.intrinsics.fx, camera.intrinsics.fy);
                const double tolerance =
                    std::max(1e-9, 16.0 * kEps * f * (1.0 + m.squaredNorm()) * (ray.origin.norm() + depth) / depth);
                CAPTURE(pixel.x(), pixel.y(), depth, q.x(), q.y());
                CHECK((q - pixel).cwiseAbs().maxCoeff() <= tolerance);
            }
        }
    }
    CHECK(checked >= 24 * 36 * 4);
}

TEST_CASE("mrcal_unproject gives libcam's ray direction", "[mrcal]") {
    for (const Camera& camera : test_cameras()) {
        const std::vector<Vec2> pixels = pixel_grid(camera.size);
        std::vector<mrcal_point2_t> q;
        for (const Vec2& p : pixels) q.push_back({{p.x(), p.y()}});
        std::vector<mrcal_point3_t> v(q.size());
        const mrcal_lensmodel_t model = pinhole_model();
        const double intrinsics[4] = {camera.intrinsics.fx, camera.intrinsics.fy, camera.intrinsics.cx, camera.intrinsics.cy};
        REQUIRE(mrcal_unproject(v.data(), q.data(), static_cast<int>(q.size()), &model, intrinsics));
        const PreparedCamera prepared(camera);
        for (std::size_t i = 0; i < pixels.size(); ++i) {
            const Vec3 expected = Vec3(v[i].x, v[i].y, v[i].z).normalized();
            const Unprojection unprojection = prepared.unproject(pixels[i]);
            REQUIRE(unprojection.valid);
            CAPTURE(pixels[i].x(), pixels[i].y());
            CHECK((unprojection.direction.normalized() - expected).norm() <= 1e-13);
            const Ray ray = prepared.ray(pixels[i]);
            CHECK((camera.pose.R * ray.direction - expected).norm() <= 1e-13);
            CHECK((ray.origin - camera.pose.centre()).norm() == 0.0);
        }
    }
}

TEST_CASE("A .cameramodel with the legacy key 'lens_model' is rejected, naming the key", "[mrcal][errors]") {
    TempDir dir;
    const std::string legacy =
        "{\n"
        "    'lens_model': 'LENSMODEL_PINHOLE',\n"
        "    'intrinsics': [ 1000.0, 1000.0, 319.5, 239.5 ],\n"
        "    'imagersize': [ 640, 480 ],\n"
        "    'extrinsics': [ 0, 0, 0, 0, 0, 0 ]\n"
        "}\n";
    // libmrcal itself refuses it (the reference for "this file is not valid").
    const ModelPtr by_mrcal(mrcal_read_cameramodel_string(legacy.data(), static_cast<int>(legacy.size())));
    CHECK(by_mrcal == nullptr);

    const fs::path path = dir.path() / "legacy.cameramodel";
    write_text(path, legacy);
    REQUIRE_THROWS_AS(read_camera_file(path), FileError);
    REQUIRE_THROWS_WITH(read_camera_file(path), Contains("lens_model") && Contains(path.string()));
    REQUIRE_THROWS_AS(parse_camera(legacy, CameraFormat::Cameramodel, "legacy"), FileError);
    REQUIRE_THROWS_WITH(parse_camera(legacy, CameraFormat::Cameramodel, "legacy"), Contains("lens_model"));

    // With the key renamed, the same file reads.
    std::string fixed = legacy;
    fixed.replace(fixed.find("lens_model"), 10, "lensmodel");
    const Camera camera = parse_camera(fixed, CameraFormat::Cameramodel, "fixed").camera;
    CHECK(camera.intrinsics.fx == 1000.0);
    CHECK(camera.size == ImageSize{640, 480});
}

TEST_CASE("A .cameramodel libmrcal refuses is told in libcam's words, with the line, the key and the value",
          "[mrcal][errors]") {
    // A valid file, then each change to it and what libcam says of it; that libmrcal
    // itself refuses each one is checked first (the reference for "not valid").
    const std::string lines[] = {"{", "    'lensmodel': 'LENSMODEL_PINHOLE',", "    'intrinsics': [ 1000, 1000, 319.5, 239.5 ],",
                                 "    'extrinsics': [ 0, 0, 0, 0, 0, 0 ],", "    'imagersize': [ 640, 480 ]", "}"};
    const auto file_with = [&](std::size_t line, const std::string& instead) {
        std::string text;
        for (std::size_t i = 0; i < std::size(lines); ++i) {
            if (i != line || !instead.empty()) text += (i == line ? instead : lines[i]) + "\n";
        }
        return text;
    };
    struct Case {
        std::size_t line;
        std::string instead;  // empty: the line removed
        std::string said;
    };
    const Case cases[] = {
        {3, "", "missing \"extrinsics\" (a .cameramodel needs lensmodel, intrinsics, extrinsics and imagersize)"},
        {2, "    'intrinsics': [ 1000, 1000, 319.5 239.5 ],", "line 3: \"intrinsics\": expected ',' between its values"},
        {2, "    'intrinsics': [ 1000, 1000, 319.5, 239.5, 7 ],",
         "line 3: \"intrinsics\": more values than the 4 of its lensmodel 'LENSMODEL_PINHOLE'"},
        {2, "    'intrinsics': [ 1000, 1000, 319.5, x ],", "line 3: \"intrinsics\": expected a finite number, got 'x'"},
        {2, "    'intrinsics': [ 1000, 1000, 319.5, 1e999 ],",
         "line 3: \"intrinsics\": expected a finite number, got '1e999'"},
        {4, "    'imagersize': [ 640, -480 ]", "line 5: \"imagersize\": expected whole numbers >= 0, got '-480'"},
        {1, "    'lensmodel': 'LENSMODEL_FOO',", "\"lensmodel\": 'LENSMODEL_FOO' is not a lens model mrcal knows (LENSMODEL_...)"},
        {1, "    'lensmodel': 'LENSMODEL_PINHOLE' 'x': 1,", "line 2: expected ',' after the value"},
        {0, "(", "expected '{' first: a .cameramodel is a Python dict"},
        {3, "    'lensmodel': 'LENSMODEL_PINHOLE',", "\"lensmodel\" given twice"},
        {1, "    'extra': 1,\n    'intrinsics': [ 1, 1, 1, 1 ],\n    'lensmodel': 'LENSMODEL_PINHOLE',",
         "\"intrinsics\" comes before any \"lensmodel\": libmrcal needs \"lensmodel\" first"},
        // A spline of 100000 x 100000 knots: 4 + 2 x 10^10 intrinsics, which libmrcal cannot allocate.
        {1, "    'lensmodel': 'LENSMODEL_SPLINED_STEREOGRAPHIC_order=3_Nx=100000_Ny=100000_fov_x_deg=100',",
         "\"lensmodel\": its spline of Nx=100000 by Ny=100000 asks for 4 + 2 Nx Ny = 20000000004 intrinsics, more than "
         "libmrcal could allocate"},
    };
    for (const Case& c : cases) {
        const std::string text = file_with(c.line, c.instead);
        INFO(text);
        const ModelPtr by_mrcal(mrcal_read_cameramodel_string(text.data(), static_cast<int>(text.size())));
        CHECK(by_mrcal == nullptr);
        try {
            (void)parse_camera(text, CameraFormat::Cameramodel, "f.cameramodel");
            FAIL("no error");
        } catch (const FileError& error) {
            CHECK(std::string(error.what()) == "f.cameramodel: " + c.said);
        }
    }
}

TEST_CASE("libmrcal's own line is found among other lines written to stderr meanwhile", "[mrcal][errors]") {
    // A checked build's allocator warns before libmrcal says "malloc() failed"; the
    // message is libmrcal's line, translated, not the warning.
    const std::string text =
        "{\n    'lensmodel': 'LENSMODEL_SPLINED_STEREOGRAPHIC_order=3_Nx=100000_Ny=100000_fov_x_deg=100',\n}\n";
    CHECK(libcam::mrcal_parse_failure("==7==WARNING: AddressSanitizer failed to allocate 0x10 bytes\n"
                                      "cameramodel-parser.re(458): malloc() failed\n",
                                      text) ==
          "\"lensmodel\": its spline of Nx=100000 by Ny=100000 asks for 4 + 2 Nx Ny = 20000000004 intrinsics, more "
          "than libmrcal could allocate");
    CHECK(libcam::mrcal_parse_failure("no place here\n", text) == "libmrcal could not read it: no place here");
}

TEST_CASE("A camera with skew cannot be written as .cameramodel", "[mrcal][errors]") {
    TempDir dir;
    Camera camera = to_camera(libcam::test::random_look_at_camera({640, 480}, FovAxis::Horizontal));
    camera.intrinsics.skew = 0.25;
    REQUIRE_THROWS_AS(format_camera(camera, CameraFormat::Cameramodel), NotRepresentable);
    REQUIRE_THROWS_WITH(format_camera(camera, CameraFormat::Cameramodel), Contains("skew"));
    const fs::path path = dir.path() / "skewed.cameramodel";
    REQUIRE_THROWS_AS(write_camera_file(path, camera, CameraFormat::Cameramodel), NotRepresentable);
    CHECK_FALSE(fs::exists(path));
    CHECK(fs::is_empty(dir.path()));  // no temporary left behind either
    REQUIRE_THROWS_AS(mrcal_project_points(camera, {Vec3(0, 0, 1)}), NotRepresentable);
    // The same camera without skew is fine.
    camera.intrinsics.skew = 0.0;
    CHECK_NOTHROW(write_camera_file(path, camera, CameraFormat::Cameramodel));
    CHECK(fs::exists(path));
}

TEST_CASE("libcam's .cameramodel keeps every digit where libmrcal's own writer rounds", "[mrcal]") {
    TempDir dir;
    const double fx = 1234.56789012345;
    const double r0 = 0.123456789012345;
    const double t0 = -98.7654321098765;

    // libmrcal's writer: "%f", six decimals.
    const std::size_t bytes = sizeof(mrcal_cameramodel_t) + 4 * sizeof(double);
    std::unique_ptr<mrcal_cameramodel_t, decltype(&std::free)> model(
        static_cast<mrcal_cameramodel_t*>(std::calloc(1, bytes)), &std::free);
    REQUIRE(model != nullptr);
    model->lensmodel.type = MRCAL_LENSMODEL_PINHOLE;
    model->imagersize[0] = 640;
    model->imagersize[1] = 480;
    model->intrinsics[0] = fx;
    model->intrinsics[1] = 1000.0;
    model->intrinsics[2] = 319.5;
    model->intrinsics[3] = 239.5;
    model->rt_cam_ref[0] = r0;
    model->rt_cam_ref[3] = t0;
    const fs::path by_mrcal = dir.path() / "by_mrcal.cameramodel";
    REQUIRE(mrcal_write_cameramodel_file(by_mrcal.c_str(), model.get()));
    const ModelPtr mrcal_back = mrcal_read_file(by_mrcal);
    REQUIRE(mrcal_back != nullptr);
    CHECK(std::abs(mrcal_back->intrinsics[0] - fx) > 1e-7);  // 1234.567890: rounded
    CHECK(std::abs(mrcal_back->intrinsics[0] - fx) < 1e-6);
    CHECK(mrcal_back->rt_cam_ref[0] != r0);
    CHECK(mrcal_back->rt_cam_ref[3] != t0);

    // libcam's writer: the same camera reads back exactly through libmrcal.
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = Intrinsics{fx, 1000.0, 319.5, 239.5, 0.0};
    camera.pose = Pose::from_rvec(Vec3(r0, 0, 0), Vec3(t0, 0, 0));
    const fs::path by_libcam = dir.path() / "by_libcam.cameramodel";
    write_camera_file(by_libcam, camera, CameraFormat::Cameramodel);
    const ModelPtr libcam_back = mrcal_read_file(by_libcam);
    REQUIRE(libcam_back != nullptr);
    CHECK(libcam_back->intrinsics[0] == fx);
    CHECK(libcam_back->rt_cam_ref[3] == t0);
    CHECK(std::abs(libcam_back->rt_cam_ref[0] - r0) <= 1e-16);  // rvec of R(r0): r0 to an ulp
    CHECK(libcam_back->rt_cam_ref[0] == camera.pose.rvec().x());
}

TEST_CASE("The packed mrcal calls refuse partial points, mismatched outputs and invalid cameras, naming them") {
    const Camera camera = to_camera(LookAtCamera{});
    std::vector<double> points{0.1, 0.2, 1.0, 0.3};  // one point and a stray number
    std::vector<double> pixels(2);
    const std::string partial = test::error_of([&] { mrcal_project_packed(camera, points, pixels); });
    CHECK_THAT(partial, Contains("InvalidArgument") && Contains("mrcal_project_packed") && Contains("got 4 and 2"));
    points.pop_back();
    std::vector<double> short_output(1);
    CHECK_THAT(test::error_of([&] { mrcal_project_packed(camera, points, short_output); }), Contains("got 3 and 1"));
    std::vector<double> directions(3);
    CHECK_THAT(test::error_of([&] { mrcal_unproject_packed(camera, std::vector<double>{1, 2, 3}, directions); }),
               Contains("mrcal_unproject_packed") && Contains("got 3 and 3"));
    Camera zero_fx = camera;
    zero_fx.intrinsics.fx = 0;
    CHECK_THAT(test::error_of([&] { mrcal_project_packed(zero_fx, points, pixels); }), Contains("K.fx"));
    CHECK_THAT(test::error_of([&] { (void)mrcal_project_points(zero_fx, {Vec3(0, 0, 1)}); }), Contains("K.fx"));
}

TEST_CASE("mrcal_project_points: a point mrcal refuses gets a NaN pixel, the others mrcal's own") {
    // CAHVORE with a linearity of 1.5: mrcal projects only where 1.5 theta < 90 degrees.
    Camera camera = to_camera(LookAtCamera{});
    camera.lens = Lens{LensType::Cahvore, {0, 0, 0, 0, 0, 0, 0, 0, 1.5}};
    const double inside = radians_from_degrees(30), outside = radians_from_degrees(70);
    const std::vector<Vec3> points{Vec3(std::sin(inside), 0, std::cos(inside)), Vec3(0, std::sin(outside), std::cos(outside))};
    std::vector<double> alone(2);
    mrcal_project_packed(camera, std::vector<double>{points[0].x(), points[0].y(), points[0].z()}, alone);
    std::vector<double> both(4);
    CHECK_THROWS_AS(mrcal_project_packed(camera, std::vector<double>{points[0].x(), points[0].y(), points[0].z(),
                                                                      points[1].x(), points[1].y(), points[1].z()},
                                         both),
                    Error);
    const std::vector<Vec2> pixels = mrcal_project_points(camera, points);
    REQUIRE(pixels.size() == 2);
    CHECK(pixels[0] == Vec2(alone[0], alone[1]));
    // By hand: chi = tan(1.5 theta) / 1.5, the pixel fx chi from the centre along x.
    CHECK(std::abs(pixels[0].x() - (camera.intrinsics.cx + camera.intrinsics.fx * std::tan(1.5 * inside) / 1.5)) < 1e-9);
    CHECK(std::isnan(pixels[1].x()));
    CHECK(std::isnan(pixels[1].y()));
}
