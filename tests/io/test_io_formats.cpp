// COLMAP models, NeRF's transforms.json and JPL's .cahvor with libcam::io alone: every
// expected number is worked by hand from the text of the fixture (COLMAP's and NeRF's
// pixel (0, 0) is the image's corner, so libcam's cx is theirs minus 0.5; a quaternion
// of a quarter turn about z; OpenGL's camera axes flipped to OpenCV's).

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "error_message.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using libcam::test::file_error_of;
namespace fs = std::filesystem;

namespace {

void check_intrinsics(const Camera& camera, double fx, double fy, double cx, double cy) {
    CHECK(camera.intrinsics.fx == fx);
    CHECK(camera.intrinsics.fy == fy);
    CHECK(camera.intrinsics.cx == cx);
    CHECK(camera.intrinsics.cy == cy);
}

// A quarter turn about z: x -> y, y -> -x.
const Mat3 kQuarterTurnZ = (Mat3() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished();

}  // namespace

TEST_CASE("COLMAP cameras.txt: every model as the libcam model that holds it, pixel centres moved by 0.5") {
    const std::string text = R"(# Camera list with one line of data per camera:
#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]
1 SIMPLE_PINHOLE 640 480 500 320 240
2 PINHOLE 640 480 500 510 320 240
3 SIMPLE_RADIAL 640 480 500 320 240 0.1
4 RADIAL 640 480 500 320 240 0.1 -0.02
5 OPENCV 640 480 500 510 320 240 0.1 -0.02 0.001 0.002
6 OPENCV_FISHEYE 640 480 300 301 320 240 0.01 0.02 0.03 0.04
7 FULL_OPENCV 640 480 500 510 320 240 1 2 3 4 5 6 7 8
8 FOV 640 480 500 510 320 240 0.9
9 SIMPLE_RADIAL_FISHEYE 640 480 300 320 240 0.05
10 RADIAL_FISHEYE 640 480 300 320 240 0.05 0.06
11 THIN_PRISM_FISHEYE 640 480 300 301 320 240 1 2 3 4 5 6 7 8
12 RAD_TAN_THIN_PRISM_FISHEYE 640 480 300 301 320 240 1 2 3 4 5 6 7 8 9 10 11 12
)";
    const CameraSet set = parse_camera_set(text, CameraFormat::Colmap, "cameras.txt");
    REQUIRE(set.cameras.size() == 12);
    struct Expected {
        LensType type;
        double fx, fy;
        std::vector<double> coefficients;
    };
    const std::vector<Expected> expected = {
        {LensType::Pinhole, 500, 500, {}},
        {LensType::Pinhole, 500, 510, {}},
        {LensType::OpenCv4, 500, 500, {0.1, 0, 0, 0}},
        {LensType::OpenCv4, 500, 500, {0.1, -0.02, 0, 0}},
        {LensType::OpenCv4, 500, 510, {0.1, -0.02, 0.001, 0.002}},
        {LensType::Fisheye, 300, 301, {0.01, 0.02, 0.03, 0.04}},
        {LensType::OpenCv8, 500, 510, {1, 2, 3, 4, 5, 6, 7, 8}},
        {LensType::Fov, 500, 510, {0.9}},
        {LensType::Fisheye, 300, 300, {0.05, 0, 0, 0}},
        {LensType::Fisheye, 300, 300, {0.05, 0.06, 0, 0}},
        {LensType::ThinPrismFisheye, 300, 301, {1, 2, 3, 4, 5, 6, 7, 8}},
        {LensType::RadTanThinPrismFisheye, 300, 301, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}},
    };
    for (std::size_t i = 0; i < expected.size(); ++i) {
        const NamedCamera& named = set.cameras[i];
        CAPTURE(i);
        CHECK(named.name == "id:" + std::to_string(i + 1));
        CHECK(named.file.camera.lens.type == expected[i].type);
        check_intrinsics(named.file.camera, expected[i].fx, expected[i].fy, 319.5, 239.5);
        CHECK(named.file.camera.lens.coefficients == expected[i].coefficients);
        CHECK(named.file.camera.size == ImageSize{640, 480});
    }
    CHECK(select_camera(set, "id:7", "cameras.txt").file.camera.lens.type == LensType::OpenCv8);
}

TEST_CASE("COLMAP model folder: each image with its camera's intrinsics and its world-to-camera pose") {
    test::TempDir dir;
    write_file_atomically(dir.path() / "cameras.txt", "1 PINHOLE 640 480 500 510 320 240\n"
                                                      "2 SIMPLE_RADIAL 800 600 700 400 300 -0.1\n"
                                                      "3 PINHOLE 100 100 50 50 50 50\n");
    // A quarter turn about z: q = (cos 45, 0, 0, sin 45). Image 7 has an empty points line,
    // image 9 a line of points; COLMAP writes the header comments first.
    const double h = std::sqrt(0.5);
    write_file_atomically(dir.path() / "images.txt",
                          "# Image list with two lines of data per image:\n"
                          "7 " + std::to_string(h) + " 0 0 " + std::to_string(h) + " 1 2 3 2 left.png\n"
                          "\n"
                          "9 1 0 0 0 -1 0 0.5 1 right.png\n"
                          "10.5 20.5 -1 30 40 7\n");
    const CameraSet set = read_camera_set(dir.path());
    CHECK(set.format == CameraFormat::Colmap);
    REQUIRE(set.cameras.size() == 3);
    // Image order, then the camera no image uses.
    CHECK(set.cameras[0].name == "left.png");
    CHECK(set.cameras[0].intrinsics_name == "id:2");
    CHECK(set.cameras[1].name == "right.png");
    CHECK(set.cameras[2].name == "id:3");
    const Camera& left = set.cameras[0].file.camera;
    CHECK(left.lens.type == LensType::OpenCv4);
    check_intrinsics(left, 700, 700, 399.5, 299.5);
    CHECK((left.pose.R - kQuarterTurnZ).cwiseAbs().maxCoeff() < 1e-6);  // the text printed 6 decimals
    CHECK(left.pose.t == Vec3(1, 2, 3));
    const Camera& right = set.cameras[1].file.camera;
    CHECK(right.pose.R == Mat3::Identity());
    CHECK(right.pose.centre() == Vec3(1, 0, -0.5));
    // --camera by image name, by COLMAP camera id (its first image), by position.
    CHECK(select_camera(set, "right.png", "m").file.camera.pose.t == Vec3(-1, 0, 0.5));
    CHECK(select_camera(set, "id:1", "m").name == "right.png");
    CHECK(select_camera(set, "2", "m").name == "id:3");
    // The cameras file named directly reads the images beside it too; so does another file
    // of the model named instead (not read as if it were the cameras).
    CHECK(read_camera_set(dir.path() / "cameras.txt").cameras.size() == 3);
    write_file_atomically(dir.path() / "points3D.txt", "# 3D point list\n7 0 0 1 0 0 0 0.5 9 1\n");
    for (const char* part : {"images.txt", "points3D.txt"}) {
        INFO(part);
        const CameraSet from_part = read_camera_set(dir.path() / part);
        CHECK(from_part.format == CameraFormat::Colmap);
        REQUIRE(from_part.cameras.size() == 3);
        CHECK(from_part.cameras[1].file.camera.pose.centre() == Vec3(1, 0, -0.5));
    }
    // Without a cameras file beside it, images.txt is read as the file it is, and refused.
    test::TempDir lone;
    write_file_atomically(lone.path() / "images.txt", "9 1 0 0 0 -1 0 0.5 1 right.png\n\n");
    CHECK_THROWS_AS(read_camera_set(lone.path() / "images.txt"), FileError);
}

TEST_CASE("COLMAP cameras.bin and images.bin, as COLMAP lays out the bytes") {
    // cameras.bin: count (u64), then id (u32), model id (i32), width, height (u64), params (f64).
    std::string cameras;
    const auto put = [](std::string& out, const auto& value) {
        out.append(reinterpret_cast<const char*>(&value), sizeof(value));
    };
    put(cameras, std::uint64_t{1});
    put(cameras, std::uint32_t{4});
    put(cameras, std::int32_t{5});  // OPENCV_FISHEYE
    put(cameras, std::uint64_t{1280});
    put(cameras, std::uint64_t{720});
    for (const double p : {400.0, 401.0, 640.0, 360.0, 0.1, 0.2, 0.3, 0.4}) put(cameras, p);
    // images.bin: count, then id (u32), qw qx qy qz tx ty tz (f64), camera id (u32), the
    // name ending in NUL, the number of points (u64) and 24 bytes per point.
    std::string images;
    put(images, std::uint64_t{1});
    put(images, std::uint32_t{3});
    for (const double v : {1.0, 0.0, 0.0, 0.0, 5.0, 6.0, 7.0}) put(images, v);
    put(images, std::uint32_t{4});
    images += std::string("frame.jpg") + '\0';
    put(images, std::uint64_t{1});
    for (const double v : {1.0, 2.0}) put(images, v);
    put(images, std::uint64_t{99});

    test::TempDir dir;
    write_file_atomically(dir.path() / "cameras.bin", cameras);
    write_file_atomically(dir.path() / "images.bin", images);
    const CameraSet set = read_camera_set(dir.path());
    REQUIRE(set.cameras.size() == 1);
    CHECK(set.cameras[0].name == "frame.jpg");
    const Camera& camera = set.cameras[0].file.camera;
    CHECK(camera.lens.type == LensType::Fisheye);
    CHECK(camera.size == ImageSize{1280, 720});
    check_intrinsics(camera, 400, 401, 639.5, 359.5);
    CHECK(camera.lens.coefficients == std::vector<double>{0.1, 0.2, 0.3, 0.4});
    CHECK(camera.pose.t == Vec3(5, 6, 7));

    // Cut short anywhere: refused, naming the byte.
    for (const std::size_t cut : {std::size_t{4}, std::size_t{20}, cameras.size() - 1}) {
        const std::string message =
            file_error_of([&] { (void)parse_camera_set(cameras.substr(0, cut), CameraFormat::Colmap, "cameras.bin"); });
        CHECK(message.starts_with("cameras.bin: byte "));
    }
    // A count larger than the file could hold is refused before anything is allocated.
    std::string huge;
    put(huge, std::uint64_t{1} << 60);
    CHECK_THAT(file_error_of([&] { (void)parse_camera_set(huge, CameraFormat::Colmap, "cameras.bin"); }),
               Catch::EndsWith("the number of cameras is 1152921504606846976, more than the 0 bytes left of the file's 8 "
                               "can hold (at least 40 bytes each)"));
}

TEST_CASE("COLMAP's SIMPLE_FISHEYE, FISHEYE and EUCM read from cameras.txt and cameras.bin") {
    // COLMAP's models.h: SIMPLE_FISHEYE (id 14) is "f, cx, cy", FISHEYE (15) "fx, fy, cx, cy"
    // (the equidistant fisheye: OpenCV's fisheye with k1..k4 = 0), EUCM (16) "fx, fy, cx,
    // cy, alpha, beta". COLMAP's cx is libcam's plus 0.5.
    const std::string text = "1 SIMPLE_FISHEYE 640 480 300 320.5 240.5\n"
                             "2 FISHEYE 800 600 310 311 400.5 300.25\n"
                             "3 EUCM 1024 768 400 401 512.5 384.5 0.6 1.1\n";
    std::string bytes;
    const auto put = [](std::string& out, const auto& value) {
        out.append(reinterpret_cast<const char*>(&value), sizeof(value));
    };
    put(bytes, std::uint64_t{3});
    const auto put_camera = [&](std::uint32_t id, std::int32_t model, std::uint64_t w, std::uint64_t h,
                                std::initializer_list<double> params) {
        put(bytes, id);
        put(bytes, model);
        put(bytes, w);
        put(bytes, h);
        for (const double p : params) put(bytes, p);
    };
    put_camera(1, 14, 640, 480, {300, 320.5, 240.5});
    put_camera(2, 15, 800, 600, {310, 311, 400.5, 300.25});
    put_camera(3, 16, 1024, 768, {400, 401, 512.5, 384.5, 0.6, 1.1});
    for (const auto& [file, source] : {std::pair{text, "cameras.txt"}, std::pair{bytes, "cameras.bin"}}) {
        INFO(source);
        const CameraSet set = parse_camera_set(file, CameraFormat::Colmap, source);
        REQUIRE(set.cameras.size() == 3);
        const Camera& simple = set.cameras[0].file.camera;
        CHECK(simple.lens.type == LensType::Fisheye);
        CHECK(simple.lens.coefficients == std::vector<double>{0, 0, 0, 0});
        CHECK(simple.size == ImageSize{640, 480});
        check_intrinsics(simple, 300, 300, 320, 240);
        const Camera& fisheye = set.cameras[1].file.camera;
        CHECK(fisheye.lens.type == LensType::Fisheye);
        CHECK(fisheye.lens.coefficients == std::vector<double>{0, 0, 0, 0});
        check_intrinsics(fisheye, 310, 311, 400, 299.75);
        const Camera& eucm = set.cameras[2].file.camera;
        CHECK(eucm.lens.type == LensType::Eucm);
        CHECK(eucm.lens.coefficients == std::vector<double>{0.6, 1.1});
        CHECK(eucm.size == ImageSize{1024, 768});
        check_intrinsics(eucm, 400, 401, 512, 384);
    }
    // Written back: EUCM as COLMAP's EUCM, the parameters as they were read.
    Camera eucm = parse_camera_set(text, CameraFormat::Colmap, "cameras.txt").cameras[2].file.camera;
    CHECK_THAT(format_camera_files(eucm, CameraFormat::Colmap)[0].text,
               Catch::EndsWith("\n1 EUCM 1024 768 400 401 512.5 384.5 0.6 1.1\n"));
    // COLMAP's id 12, SIMPLE_DIVISION (f, cx, cy, k): DIVISION with fx = fy, the
    // principal point moved by COLMAP's half pixel.
    std::string division;
    put(division, std::uint64_t{1});
    put(division, std::uint32_t{1});
    put(division, std::int32_t{12});
    put(division, std::uint64_t{640});
    put(division, std::uint64_t{480});
    for (const double p : {300.0, 320.0, 240.0, 0.1}) put(division, p);
    const Camera simple_division = parse_camera_set(division, CameraFormat::Colmap, "cameras.bin").cameras[0].file.camera;
    CHECK(simple_division.lens == Lens{LensType::Division, {0.1}});
    check_intrinsics(simple_division, 300, 300, 319.5, 239.5);
    CHECK_THAT(format_camera_files(simple_division, CameraFormat::Colmap)[0].text,
               Catch::EndsWith("\n1 DIVISION 640 480 300 300 320 240 0.1\n"));
}

TEST_CASE("COLMAP files that are wrong are refused, naming the file, line and field") {
    const auto error_of = [](const std::string& text) {
        return file_error_of([&] { (void)parse_camera_set(text, CameraFormat::Colmap, "cameras.txt"); });
    };
    CHECK(error_of("1 PINHOLE 640 480 500 510 320\n") ==
          "cameras.txt: line 1: PARAMS: PINHOLE has 4 parameters, got 3");
    CHECK_THAT(error_of("1 FISH 640 480 1 2 3\n"), Catch::StartsWith("cameras.txt: line 1: MODEL: must be one of"));
    CHECK(error_of("# c\n1 PINHOLE 640 480 500 nan 320 240\n") ==
          "cameras.txt: line 2: PARAMS[1]: expected a finite number, got 'nan'");
    CHECK(error_of("1 PINHOLE 0 480 500 510 320 240\n") ==
          "cameras.txt: line 1: WIDTH: expected an integer in [1, 1000000], got '0'");
    CHECK_THAT(error_of("1 PINHOLE 640 480 -5 510 320 240\n"), Catch::StartsWith("cameras.txt: line 1: camera 1: "));
    CHECK(error_of("1 PINHOLE 640 480 500 510 320 240\n1 PINHOLE 640 480 500 510 320 240\n") ==
          "cameras.txt: CAMERA_ID 1 appears more than once");
    CHECK(error_of("# only comments\n") == "cameras.txt: no camera");

    test::TempDir dir;
    write_file_atomically(dir.path() / "cameras.txt", "1 PINHOLE 640 480 500 510 320 240\n");
    write_file_atomically(dir.path() / "images.txt", "1 1 0 0 0 0 0 0 2 a.png\n\n");
    CHECK(file_error_of([&] { (void)read_camera_set(dir.path()); }) ==
          (dir.path() / "images.txt").string() + ": line 1: image 1 (a.png): CAMERA_ID 2 is not in cameras.txt");
    write_file_atomically(dir.path() / "images.txt", "1 2 0 0 0 0 0 0 1 a.png\n\n");
    CHECK(file_error_of([&] { (void)read_camera_set(dir.path()); }) ==
          (dir.path() / "images.txt").string() + ": line 1: image 1: the quaternion's norm is 2, not 1");
    CHECK_THAT(file_error_of([&] { (void)read_camera_set(dir.path() / "missing"); }), Catch::Contains("missing"));
}

TEST_CASE("COLMAP is written as cameras.txt and images.txt, and refuses what it cannot hold") {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {500.0, 510.0, 319.5, 239.5, 0.0};
    camera.lens = {LensType::OpenCv5, {0.1, -0.02, 0.001, 0.002, 0.003}};
    camera.pose = {kQuarterTurnZ, Vec3(1, 2, 3)};
    const std::vector<CameraFileText> files = format_camera_files(camera, CameraFormat::Colmap);
    REQUIRE(files.size() == 3);
    CHECK(files[2].name == "points3D.txt");
    CHECK(files[0].name == "cameras.txt");
    // OPENCV5 is FULL_OPENCV with k4 = k5 = k6 = 0; COLMAP's cx is libcam's plus 0.5.
    CHECK_THAT(files[0].text, Catch::EndsWith("\n1 FULL_OPENCV 640 480 500 510 320 240 0.1 -0.02 0.001 0.002 0.003 0 0 0\n"));
    // q = (cos 45, 0, 0, sin 45) for the quarter turn.
    CHECK_THAT(files[1].text, Catch::Contains("\n1 0.7071067811865476 0 0 0.7071067811865475 1 2 3 1 image.png\n"));
    CHECK_THROWS_AS(format_camera(camera, CameraFormat::Colmap), NotRepresentable);

    test::TempDir dir;
    write_camera_file(dir.path() / "model", camera, CameraFormat::Colmap);
    const Camera back = read_camera_file(dir.path() / "model").camera;
    CHECK(back.lens.type == LensType::OpenCv8);
    CHECK(back.intrinsics.cx == camera.intrinsics.cx);
    CHECK((back.pose.R - camera.pose.R).cwiseAbs().maxCoeff() < 1e-15);

    Camera skewed = camera;
    skewed.intrinsics.skew = 0.5;
    CHECK_THROWS_WITH(format_camera_files(skewed, CameraFormat::Colmap), "COLMAP's models have no skew; this camera's is 0.5");
    Camera mei = camera;
    mei.lens = {LensType::Mei, {1.2, 0, 0, 0, 0}};
    CHECK_THROWS_WITH(format_camera_files(mei, CameraFormat::Colmap), Catch::StartsWith("COLMAP has no model for a MEI lens"));
    Camera prism = camera;
    prism.lens = {LensType::OpenCv12, {0, 0, 0, 0, 0, 0, 0, 0, 0.01, 0, 0, 0}};
    CHECK_THROWS_AS(format_camera_files(prism, CameraFormat::Colmap), NotRepresentable);
    CHECK_FALSE(fs::exists(dir.path() / "prism"));
}

TEST_CASE("transforms.json: a NeRF synthetic scene's camera_angle_x, its centre, and Blender's camera-to-world") {
    // NeRF's lego scene writes only the horizontal angle and camera-to-world matrices in
    // OpenGL's axes. This camera sits at (0, -4, 0) looking along +y (its -z), z up.
    const std::string text = R"({
  "camera_angle_x": 0.5,
  "frames": [
    {"file_path": "./train/r_0", "transform_matrix": [[1, 0, 0, 0], [0, 0, -1, -4], [0, 1, 0, 0], [0, 0, 0, 1]]}
  ]
})";
    CHECK_THAT(file_error_of([&] { (void)parse_camera_set(text, CameraFormat::Nerf, "t.json"); }),
               Catch::Contains("give the size (--image-size WxH)"));
    ReadOptions options;
    options.size = ImageSize{800, 600};
    const CameraSet set = parse_camera_set(text, CameraFormat::Nerf, "t.json", options);
    REQUIRE(set.cameras.size() == 1);
    CHECK(set.cameras[0].name == "./train/r_0");
    const Camera& camera = set.cameras[0].file.camera;
    const double f = 400.0 / std::tan(0.25);
    check_intrinsics(camera, f, f, 399.5, 299.5);
    CHECK(camera.lens.type == LensType::Pinhole);
    // OpenCV axes in the world: x (1,0,0), y down (0,0,-1), z forward (0,1,0).
    const Mat3 expected = (Mat3() << 1, 0, 0, 0, 0, -1, 0, 1, 0).finished();
    CHECK(camera.pose.R == expected);
    CHECK(camera.pose.centre() == Vec3(0, -4, 0));
    // NeRF's own ray code puts the principal point at W / 2 with pixel centres at integers.
    options.nerf_principal_point = NerfPrincipalPoint::HalfSize;
    check_intrinsics(parse_camera(text, CameraFormat::Nerf, "t.json", options).camera, f, f, 400, 300);
}

TEST_CASE("transforms.json: instant-ngp's and nerfstudio's intrinsics, per frame, and their models") {
    const std::string text = R"({
  "fl_x": 1000, "fl_y": 1001, "cx": 540, "cy": 960, "w": 1080.0, "h": 1920,
  "k1": 0.1, "k2": -0.01, "p1": 0.001, "p2": 0.002,
  "frames": [
    {"file_path": "a.jpg", "transform_matrix": [[1, 0, 0, 1], [0, 1, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]},
    {"file_path": "b.jpg", "fl_x": 900, "k3": 0.5, "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}
  ]
})";
    const CameraSet set = parse_camera_set(text, CameraFormat::Nerf, "t.json");
    REQUIRE(set.cameras.size() == 2);
    const Camera& a = set.cameras[0].file.camera;
    CHECK(a.lens.type == LensType::OpenCv4);
    CHECK(a.lens.coefficients == std::vector<double>{0.1, -0.01, 0.001, 0.002});
    check_intrinsics(a, 1000, 1001, 539.5, 959.5);
    CHECK(a.size == ImageSize{1080, 1920});
    // An identity camera-to-world in OpenGL's axes: the camera looks along the world's -z.
    CHECK(a.pose.R == Mat3(Eigen::Vector3d(1, -1, -1).asDiagonal()));
    CHECK(a.pose.centre() == Vec3(1, 2, 3));
    const Camera& b = set.cameras[1].file.camera;
    CHECK(b.lens.type == LensType::OpenCv5);
    CHECK(b.intrinsics.fx == 900);

    const auto error_of = [](const std::string& json) {
        return file_error_of([&] { (void)parse_camera_set(json, CameraFormat::Nerf, "t.json"); });
    };
    CHECK(parse_camera_set(R"({"fl_x": 500, "w": 640, "h": 480, "k4": 0.1})", CameraFormat::Nerf, "t.json")
              .cameras[0]
              .file.camera.lens == Lens{LensType::BrownK4, {0, 0, 0, 0, 0, 0.1}});
    CHECK(error_of(R"({"fl_x": 500, "w": 640})") == "t.json: \"w\": given without \"h\"");
    CHECK(error_of(R"({"fl_x": 500, "w": 640.5, "h": 480})") ==
          "t.json: \"w\": expected a whole number in [1, 1000000], got 640.5");
    CHECK(error_of(R"({"fl_x": 500, "w": 640, "h": 480, "camera_model": "VR180"})") ==
          "t.json: \"camera_model\": must be OPENCV, PINHOLE, SIMPLE_PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV_FISHEYE, "
          "EQUIRECTANGULAR or FISHEYE624, got 'VR180'");
    CHECK(error_of(R"({"fl_x": 500, "w": 640, "h": 480, "frames": [{"transform_matrix": [[2, 0, 0, 0], [0, 2, 0, 0], [0, 0, 2, 0], [0, 0, 0, 1]]}]})")
              .starts_with("t.json: \"frames[0].transform_matrix\": "));
    ReadOptions other_size;
    other_size.size = ImageSize{100, 100};
    CHECK(file_error_of([&] {
              (void)parse_camera_set(R"({"fl_x": 500, "w": 640, "h": 480})", CameraFormat::Nerf, "t.json", other_size);
          }) == "t.json: \"w\": the file says 640x480, the image size given is 100x100");

    // nerfstudio's EQUIRECTANGULAR: fl_x = W / 2 spans pi over half the width, so it is
    // LONLAT with fx = fl_x / pi.
    const Camera pano =
        parse_camera(R"({"camera_model": "EQUIRECTANGULAR", "fl_x": 1000, "fl_y": 500, "cx": 1000, "cy": 500, "w": 2000, "h": 1000})",
                     CameraFormat::Nerf, "t.json")
            .camera;
    CHECK(pano.lens.type == LensType::Lonlat);
    check_intrinsics(pano, 1000 / std::numbers::pi, 500 / std::numbers::pi, 999.5, 499.5);
}

TEST_CASE("transforms.json without a size takes it from the first frame's image, as a PNG or JPEG header says") {
    test::TempDir dir;
    fs::create_directories(dir.path() / "train");
    // A PNG's signature and IHDR chunk: width 320 and height 200, big-endian.
    std::string png = "\x89PNG\r\n\x1a\n";
    png += std::string("\0\0\0\x0dIHDR", 8);
    png += std::string("\0\0\x01\x40\0\0\0\xc8", 8);
    png += std::string(13, '\0');
    write_file_atomically(dir.path() / "train" / "r_0.png", png);
    write_file_atomically(dir.path() / "transforms.json",
                          R"({"camera_angle_x": 1.0, "frames": [{"file_path": "./train/r_0"}]})");
    const Camera camera = read_camera_file(dir.path() / "transforms.json").camera;
    CHECK(camera.size == ImageSize{320, 200});
    CHECK(camera.intrinsics.cx == 159.5);

    // A JPEG: SOI, an APP0 segment of 4 bytes, then SOF0 with height 240 and width 352.
    const std::string jpeg = std::string("\xff\xd8\xff\xe0\x00\x04\x00\x00\xff\xc0\x00\x11\x08\x00\xf0\x01\x60\x03", 18) +
                             std::string(16, '\0');
    write_file_atomically(dir.path() / "photo.jpg", jpeg);
    write_file_atomically(dir.path() / "transforms.json", R"({"fl_x": 300, "frames": [{"file_path": "photo.jpg"}]})");
    CHECK(read_camera_file(dir.path() / "transforms.json").camera.size == ImageSize{352, 240});
}

TEST_CASE("transforms.json is written with COLMAP's pixel corner, OpenGL's camera-to-world, and NeRF's angles") {
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {500.0, 500.0, 319.5, 239.5, 0.0};
    camera.lens = {LensType::Fisheye, {0.1, 0.2, 0.3, 0.4}};
    camera.pose = Pose::from_centre(Mat3::Identity(), Vec3(1, 2, 3));
    WriteOptions options;
    options.image_name = "images/0001.png";
    const std::string text = format_camera(camera, CameraFormat::Nerf, options);
    CHECK_THAT(text, Catch::Contains("\"camera_model\": \"OPENCV_FISHEYE\""));
    CHECK_THAT(text, Catch::Contains("\"cx\": 320.0"));
    CHECK_THAT(text, Catch::Contains("\"file_path\": \"images/0001.png\""));
    // camera_angle_x = 2 atan(320 / 500).
    const auto angle_at = text.find("\"camera_angle_x\": ");
    REQUIRE(angle_at != std::string::npos);
    CHECK(std::stod(text.substr(angle_at + 18)) == 2.0 * std::atan(320.0 / 500.0));
    const Camera back = parse_camera(text, CameraFormat::Nerf, "t.json").camera;
    CHECK(back.lens.coefficients == camera.lens.coefficients);
    CHECK(back.intrinsics.cx == camera.intrinsics.cx);
    CHECK(back.pose.R == camera.pose.R);
    CHECK(back.pose.centre() == camera.pose.centre());

    Camera mei = camera;
    mei.lens = {LensType::Mei, {1.2, 0, 0, 0, 0}};
    CHECK_THROWS_WITH(format_camera(mei, CameraFormat::Nerf),
                      "NeRF transforms.json has no model for a MEI lens (it holds PINHOLE, OPENCV4, OPENCV5, BROWN_K4, FISHEYE, LONLAT "
                      "and RAD_TAN_THIN_PRISM_FISHEYE)");
    Camera rational = camera;
    rational.lens = {LensType::OpenCv8, {0, 0, 0, 0, 0, 0.1, 0, 0}};
    CHECK_THROWS_WITH(format_camera(rational, CameraFormat::Nerf),
                      "transforms.json holds OpenCV's k1 k2 p1 p2 k3 only; this OPENCV8 lens's k4 is 0.1");
}

TEST_CASE(".cahvor: JPL's C, A, H, V as K and the camera's placement, and CAHVOR's O and R") {
    // A camera at C = (1, 2, 3) whose axes are the reference's turned a quarter about z:
    // H' = (0, 1, 0), V' = (-1, 0, 0), A = (0, 0, 1); fx 1000, fy 1100, cx 320, cy 240, so
    // H = 1000 H' + 320 A and V = 1100 V' + 240 A.
    const std::string text = "# a comment\n"
                             "Dimensions = 640 480\n"
                             "Model = CAHV = perspective, linear\n"
                             "C = 1 2 3\n"
                             "A = 0 0 1\n"
                             "H = 0 1000 320\n"
                             "V = -1100 0 240\n"
                             "Hs = 1000\n"
                             "Theta = -1.5707963267948966 (-90.0 deg)\n";
    const Camera camera = parse_camera(text, CameraFormat::Cahvor, "c.cahvor").camera;
    CHECK(camera.lens.type == LensType::Pinhole);
    check_intrinsics(camera, 1000, 1100, 320, 240);
    // The rows of R are the camera's axes in the reference frame.
    CHECK(camera.pose.R == (Mat3() << 0, 1, 0, -1, 0, 0, 0, 0, 1).finished());
    CHECK(camera.pose.centre() == Vec3(1, 2, 3));

    // CAHVOR: O along the camera's axis turned by alpha about V' and beta up: with the
    // identity placement, O = (sin a cos b, sin b, cos a cos b).
    const double a = 0.01;
    const double b = -0.02;
    const std::string cahvor = "Dimensions = 640 480\nModel = CAHVOR = perspective, distortion\nC = 0 0 0\nA = 0 0 1\n"
                               "H = 1000 0 320\nV = 0 1000 240\n" +
                               ("O = " + std::to_string(std::sin(a) * std::cos(b)) + " " + std::to_string(std::sin(b)) +
                                " " + std::to_string(std::cos(a) * std::cos(b)) + "\n") +
                               "R = 0 -0.1 0.01\n";
    const Camera distorted = parse_camera(cahvor, CameraFormat::Cahvor, "c.cahvor").camera;
    REQUIRE(distorted.lens.type == LensType::Cahvor);
    CHECK(distorted.lens.coefficients[0] == Approx(a).margin(1e-6));
    CHECK(distorted.lens.coefficients[1] == Approx(b).margin(1e-6));
    CHECK(distorted.lens.coefficients[3] == -0.1);
    // mrcal's OpenCV lens in a CAHV file.
    const Camera opencv = parse_camera(text + "LENSMODEL_OPENCV4 = 0.1 0.2 0.3 0.4\n", CameraFormat::Cahvor, "c").camera;
    CHECK(opencv.lens.type == LensType::OpenCv4);
    CHECK(opencv.lens.coefficients == std::vector<double>{0.1, 0.2, 0.3, 0.4});

    const auto error_of = [](const std::string& t) {
        return file_error_of([&] { (void)parse_camera(t, CameraFormat::Cahvor, "c.cahvor"); });
    };
    CHECK(error_of("Dimensions = 640 480\nC = 0 0 0\nA = 0 0 1\nH = 1000 0 320\n") == "c.cahvor: \"V\": missing");
    CHECK(error_of("Dimensions = 640\n") == "c.cahvor: line 1: \"Dimensions\": expected 2 numbers, got '640'");
    CHECK(error_of("C = 0 0 0\nC = 1 1 1\n") == "c.cahvor: line 2: \"C\" given more than once");
    CHECK(error_of("just words\n") == "c.cahvor: line 1: expected \"key = value\"");
    CHECK(error_of("Dimensions = 640 480\nC = 0 0 0\nA = 0 0 1\nH = 0 0 320\nV = 0 1000 240\n") ==
          "c.cahvor: \"H\", \"V\": parallel to \"A\": no focal length");
}

TEST_CASE("The format is told from the contents where the extension is shared or missing") {
    test::TempDir dir;
    write_file_atomically(dir.path() / "cams.txt", "# Camera list\n1 PINHOLE 640 480 500 510 320 240\n");
    CHECK(read_camera_set(dir.path() / "cams.txt").format == CameraFormat::Colmap);
    write_file_atomically(dir.path() / "model", "Dimensions = 640 480\nC = 0 0 0\nA = 0 0 1\nH = 1000 0 320\nV = 0 1000 240\n");
    CHECK(read_camera_set(dir.path() / "model").format == CameraFormat::Cahvor);
    write_file_atomically(dir.path() / "transforms.json", R"({"fl_x": 500, "w": 640, "h": 480})");
    CHECK(read_camera_set(dir.path() / "transforms.json").format == CameraFormat::Nerf);
    fs::create_directories(dir.path() / "empty");
    CHECK_THAT(file_error_of([&] { (void)read_camera_set(dir.path() / "empty"); }),
               Catch::EndsWith("a folder, and not a COLMAP model folder (it has no cameras.bin or cameras.txt, nor a "
                                               "folder inside that has)"));
    write_file_atomically(dir.path() / "odd", "!!! nothing\n");
    CHECK_THAT(file_error_of([&] { (void)read_camera_set(dir.path() / "odd"); }),
               Catch::Contains("unknown camera file format"));
}

TEST_CASE("ROS camera_info: the raw camera, and the rectified one its P describes, in the pair's rectified frame") {
    // A right camera of a stereo pair: R turns its raw frame a quarter about z into the
    // rectified one; P = K' [I | t] with Tx = -fx' * 0.1 (a baseline of 0.1).
    const std::string text = R"(image_width: 640
image_height: 480
camera_name: right
camera_matrix:
  rows: 3
  cols: 3
  data: [500, 0, 320, 0, 501, 240, 0, 0, 1]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [-0.1, 0.01, 0.001, -0.002, 0]
rectification_matrix:
  rows: 3
  cols: 3
  data: [0, -1, 0, 1, 0, 0, 0, 0, 1]
projection_matrix:
  rows: 3
  cols: 4
  data: [400, 0, 330, -40, 0, 400, 250, 0, 0, 0, 1, 0]
)";
    const CameraSet set = parse_camera_set(text, CameraFormat::Ros, "right.yaml");
    REQUIRE(set.cameras.size() == 2);
    CHECK(set.cameras[0].name == "right");
    CHECK(set.cameras[1].name == "right/rectified");
    const Camera& raw = set.cameras[0].file.camera;
    CHECK(raw.lens.type == LensType::OpenCv5);  // plumb_bob's five, as OpenCV's own files
    check_intrinsics(raw, 500, 501, 320, 240);
    const Camera& rectified = set.cameras[1].file.camera;
    CHECK(rectified.lens.type == LensType::Pinhole);
    check_intrinsics(rectified, 400, 400, 330, 250);
    // The rectified camera sits 0.1 to the right of the first: X_rect = X + (-0.1, 0, 0).
    CHECK(rectified.pose.R == Mat3::Identity());
    CHECK(rectified.pose.t == Vec3(-0.1, 0, 0));
    // The raw camera: the same centre, X_raw = R^T X_rect.
    CHECK(raw.pose.R == kQuarterTurnZ.transpose());
    CHECK((raw.pose.centre() - Vec3(0.1, 0, 0)).norm() < 1e-16);
    // R must be 3x3: nine numbers in another shape are refused.
    const std::string square = "rectification_matrix:\n  rows: 3\n  cols: 3";
    std::string column = text;
    column.replace(column.find(square), square.size(), "rectification_matrix:\n  rows: 9\n  cols: 1");
    CHECK_THAT(file_error_of([&] { (void)parse_camera_set(column, CameraFormat::Ros, "right.yaml"); }),
               Catch::Contains("right.yaml: line 14: \"rectification_matrix\": expected a 3x3 matrix"));

    // Written: K, D with its distortion_model, R = I, P = [K | 0]; numbers as PyYAML reads floats.
    Camera camera;
    camera.size = {640, 480};
    camera.intrinsics = {500.0, 501.0, 319.5, 239.5, 0.0};
    camera.lens = {LensType::Fisheye, {0.1, 0.01, 0.001, 1e-9}};
    const std::string written = format_camera(camera, CameraFormat::Ros);
    CHECK_THAT(written, Catch::Contains("distortion_model: equidistant\n"));
    CHECK_THAT(written, Catch::Contains("  data: [0.1, 0.01, 0.001, 1.0e-09]\n"));
    CHECK_THAT(written, Catch::Contains("  data: [500.0, 0.0, 319.5, 0.0, 0.0, 501.0, 239.5, 0.0, 0.0, 0.0, 1.0, 0.0]\n"));
    const CameraSet back = parse_camera_set(written, CameraFormat::Ros, "back.yaml");
    CHECK(back.cameras[0].file.camera.lens == camera.lens);
    CHECK(back.cameras[0].file.camera.intrinsics.K() == camera.intrinsics.K());
    // camera_info holds no pose.
    camera.pose.t = Vec3(1, 0, 0);
    CHECK_THROWS_WITH(format_camera(camera, CameraFormat::Ros), Catch::Contains("holds no pose") && Catch::Contains("--no-pose"));
    WriteOptions drop;
    drop.drop_pose = true;
    CHECK_NOTHROW(format_camera(camera, CameraFormat::Ros, drop));
    camera.lens = {LensType::Mei, {1.0, 0, 0, 0, 0}};
    CHECK_THROWS_AS(format_camera(camera, CameraFormat::Ros, drop), NotRepresentable);
}

TEST_CASE("Kalibr camchain written: each model's Kalibr names, its leading coefficients first, read back the same") {
    Camera camera;
    camera.size = {752, 480};
    camera.intrinsics = {460.0, 459.0, 365.5, 249.5, 0.0};
    camera.lens = {LensType::Mei, {1.5, -0.2, 0.03, 1e-4, -2e-4}};
    camera.pose = {kQuarterTurnZ, Vec3(0.01, -0.02, 0.03)};
    const std::string text = format_camera(camera, CameraFormat::Kalibr);
    CHECK_THAT(text, Catch::Contains("  camera_model: omni\n"));
    CHECK_THAT(text, Catch::Contains("  distortion_model: radtan\n"));
    CHECK_THAT(text, Catch::Contains("  intrinsics: [1.5, 460.0, 459.0, 365.5, 249.5]\n"));
    CHECK_THAT(text, Catch::Contains("  distortion_coeffs: [-0.2, 0.03, 1.0e-04, -2.0e-04]\n"));
    CHECK_THAT(text, Catch::Contains("  - [0.0, -1.0, 0.0, 0.01]\n"));
    const NamedCamera back = parse_camera_set(text, CameraFormat::Kalibr, "chain.yaml").cameras.front();
    CHECK(back.name == "cam0");
    CHECK(back.file.camera.lens == camera.lens);
    CHECK(back.file.camera.intrinsics.K() == camera.intrinsics.K());
    CHECK(back.file.camera.pose.R == camera.pose.R);
    CHECK(back.file.camera.pose.t == camera.pose.t);
    camera.lens = {LensType::Fisheye, {0.1, 0.01, 0.001, 1e-4}};
    CHECK_THAT(format_camera(camera, CameraFormat::Kalibr), Catch::Contains("  distortion_model: equidistant\n"));
    // An OPENCV8 whose k3..k6 are 0 is an OPENCV4 (radtan); with k6 set it is refused.
    camera.lens = {LensType::OpenCv8, {0.1, 0.01, 0.001, 1e-4, 0, 0, 0, 0}};
    CHECK_THAT(format_camera(camera, CameraFormat::Kalibr), Catch::Contains("  distortion_model: radtan\n"));
    camera.lens = {LensType::OpenCv8, {0.1, 0.01, 0.001, 1e-4, 0, 0, 0, 0.5}};
    CHECK_THROWS_WITH(format_camera(camera, CameraFormat::Kalibr), Catch::StartsWith("Kalibr has no model for a OPENCV8 lens"));
}

TEST_CASE("Open3D's camera JSON: Eigen's column-major matrices, world-to-camera extrinsic, and trajectories") {
    // Open3D's default PrimeSense camera, as write_pinhole_camera_intrinsic writes it.
    const std::string intrinsic = R"({
	"height" : 480,
	"intrinsic_matrix" : [ 525.0, 0.0, 0.0, 0.0, 525.0, 0.0, 319.5, 239.5, 1.0 ],
	"width" : 640
})";
    const Camera primesense = parse_camera(intrinsic, CameraFormat::Open3d, "o3d.json").camera;
    check_intrinsics(primesense, 525, 525, 319.5, 239.5);
    CHECK(primesense.size == ImageSize{640, 480});
    // A trajectory of two cameras; the second's extrinsic, column by column, is the quarter
    // turn about z and t = (1, 2, 3).
    const std::string trajectory = R"({"class_name": "PinholeCameraTrajectory", "parameters": [
  {"class_name": "PinholeCameraParameters", "extrinsic": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1],
   "intrinsic": {"width": 640, "height": 480, "intrinsic_matrix": [500,0,0, 0,500,0, 320,240,1]}},
  {"class_name": "PinholeCameraParameters", "extrinsic": [0,1,0,0, -1,0,0,0, 0,0,1,0, 1,2,3,1],
   "intrinsic": {"width": 640, "height": 480, "intrinsic_matrix": [500,0,0, 0,500,0, 320,240,1]}}]})";
    const CameraSet set = parse_camera_set(trajectory, CameraFormat::Open3d, "traj.json");
    REQUIRE(set.cameras.size() == 2);
    CHECK(set.cameras[1].file.camera.pose.R == kQuarterTurnZ);
    CHECK(set.cameras[1].file.camera.pose.t == Vec3(1, 2, 3));
    // Written as PinholeCameraParameters, and read back.
    Camera camera = set.cameras[1].file.camera;
    camera.intrinsics.skew = 0.25;
    const std::string written = format_camera(camera, CameraFormat::Open3d);
    CHECK_THAT(written, Catch::Contains("\"class_name\": \"PinholeCameraParameters\""));
    const Camera back = parse_camera(written, CameraFormat::Open3d, "back.json").camera;
    CHECK(back.intrinsics.K() == camera.intrinsics.K());
    CHECK(back.pose.R == camera.pose.R);
    CHECK(back.pose.t == camera.pose.t);
    camera.lens = {LensType::OpenCv4, {0.1, 0, 0, 0}};
    CHECK_THROWS_WITH(format_camera(camera, CameraFormat::Open3d), "Open3D's cameras have no distortion; this camera's lens is OPENCV4");
    CHECK(file_error_of([&] { (void)parse_camera(R"({"width": 640, "height": 480, "intrinsic_matrix": [1, 2, 3]})",
                                                  CameraFormat::Open3d, "o.json"); }) ==
          "o.json: \"intrinsic_matrix\": expected 9 numbers, got 3");
}

TEST_CASE("EuRoC's sensor.yaml: the camera in the body frame, inverted") {
    // The camera at (1, 2, 3) in the body frame, turned a quarter about z.
    const std::string text = R"(# General sensor definitions.
sensor_type: camera
comment: VI-Sensor cam0 (MT9M034)
T_BS:
  cols: 4
  rows: 4
  data: [0.0, -1.0, 0.0, 1.0,
         1.0, 0.0, 0.0, 2.0,
         0.0, 0.0, 1.0, 3.0,
         0.0, 0.0, 0.0, 1.0]
rate_hz: 20
resolution: [752, 480]
camera_model: pinhole
intrinsics: [458.654, 457.296, 367.215, 248.375] #fu, fv, cu, cv
distortion_model: radial-tangential
distortion_coefficients: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]
)";
    test::TempDir dir;
    write_file_atomically(dir.path() / "sensor.yaml", text);
    const CameraSet set = read_camera_set(dir.path() / "sensor.yaml");
    CHECK(set.format == CameraFormat::Euroc);
    const NamedCamera& named = set.cameras.front();
    CHECK(named.name == "VI-Sensor cam0 (MT9M034)");
    check_intrinsics(named.file.camera, 458.654, 457.296, 367.215, 248.375);
    CHECK(named.file.camera.lens.coefficients.front() == -0.28340811);
    CHECK(named.file.camera.pose.R == kQuarterTurnZ.transpose());
    CHECK(named.file.camera.pose.centre() == Vec3(1, 2, 3));
}

TEST_CASE("OpenCV's other layouts: ORB-SLAM's settings and stereo files, each camera placed") {
    // ORB-SLAM3 1.0: Camera1, Camera2 and Stereo.T_c1_c2 (camera 2 in camera 1's frame: 0.11 to its right).
    const std::string orb3 = R"(%YAML:1.0
File.version: "1.0"
Camera.type: "KannalaBrandt8"
Camera1.fx: 190.97
Camera1.fy: 190.97
Camera1.cx: 254.93
Camera1.cy: 256.89
Camera1.k1: 0.0034
Camera1.k2: 0.0007
Camera1.k3: -0.0020
Camera1.k4: 0.0002
Camera2.fx: 190.44
Camera2.fy: 190.43
Camera2.cx: 252.59
Camera2.cy: 254.91
Camera2.k1: 0.0034
Camera2.k2: 0.0008
Camera2.k3: -0.0020
Camera2.k4: 0.0002
Camera.width: 512
Camera.height: 512
Stereo.T_c1_c2: !!opencv-matrix
  rows: 4
  cols: 4
  dt: f
  data: [1, 0, 0, 0.11, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
)";
    const CameraSet set = parse_camera_set(orb3, CameraFormat::OpenCvYaml, "tumvi.yaml");
    REQUIRE(set.cameras.size() == 2);
    CHECK(set.cameras[0].name == "Camera1");
    CHECK(set.cameras[0].file.camera.lens == Lens{LensType::Fisheye, {0.0034, 0.0007, -0.0020, 0.0002}});
    CHECK(set.cameras[0].file.camera.size == ImageSize{512, 512});
    CHECK(set.cameras[1].file.camera.pose.centre() == Vec3(0.11, 0, 0));
    // ORB-SLAM2: Camera.*, no size in the file: --image-size.
    const std::string orb2 = "%YAML:1.0\nCamera.fx: 517.3\nCamera.fy: 516.5\nCamera.cx: 318.6\nCamera.cy: 255.3\n"
                             "Camera.k1: 0.2624\nCamera.k2: -0.9531\nCamera.p1: -0.0054\nCamera.p2: 0.0026\nCamera.k3: 1.1633\n";
    CHECK_THAT(file_error_of([&] { (void)parse_camera_set(orb2, CameraFormat::OpenCvYaml, "tum1.yaml"); }),
               Catch::Contains("\"Camera.width\": missing"));
    ReadOptions sized;
    sized.size = ImageSize{640, 480};
    const Camera tum = parse_camera(orb2, CameraFormat::OpenCvYaml, "tum1.yaml", sized).camera;
    CHECK(tum.lens == Lens{LensType::OpenCv5, {0.2624, -0.9531, -0.0054, 0.0026, 1.1633}});
    // ORB-SLAM2's RGB-D settings: Camera.bf next to DepthMapFactor is the depth sensor's
    // baseline, not a second image; KITTI's stereo settings (no DepthMapFactor) have one.
    const std::string rgbd = "%YAML:1.0\nCamera.fx: 400\nCamera.fy: 400\nCamera.cx: 320\nCamera.cy: 240\n"
                             "Camera.width: 640\nCamera.height: 480\nCamera.bf: 40.0\n";
    CHECK(parse_camera_set(rgbd + "DepthMapFactor: 5000.0\n", CameraFormat::OpenCvYaml, "TUM1.yaml").cameras.size() == 1);
    const CameraSet kitti = parse_camera_set(rgbd, CameraFormat::OpenCvYaml, "KITTI00-02.yaml");
    REQUIRE(kitti.cameras.size() == 2);
    CHECK(kitti.cameras[1].file.camera.pose.centre() == Vec3(0.1, 0, 0));  // 40 / 400
    CHECK_THAT(file_error_of([&] {
                   (void)parse_camera_set("%YAML:1.0\nCamera.fx: 400\nCamera.fy: 400\nCamera.cx: 320\nCamera.cy: 240\n"
                                          "Camera.width: 640\nCamera.height: 480\nCamera.bf: -40.0\n",
                                          CameraFormat::OpenCvYaml, "bad.yaml");
               }),
               Catch::Contains("bad.yaml: line 8: \"Camera.bf\": must be > 0 (the baseline times fx), got '-40.0'"));
    // OpenCV's stereo_calib sample: M1 D1 M2 D2 and R T (camera 2 from camera 1).
    const std::string stereo = R"(%YAML:1.0
M1: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 500., 0., 320., 0., 500., 240., 0., 0., 1. ]
D1: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ -0.1, 0.01, 0., 0., 0. ]
M2: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 510., 0., 321., 0., 510., 241., 0., 0., 1. ]
D2: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ -0.11, 0.02, 0., 0., 0.001 ]
R: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 0., -1., 0., 1., 0., 0., 0., 0., 1. ]
T: [ -0.12, 0., 0.001 ]
)";
    const CameraSet pair = parse_camera_set(stereo, CameraFormat::OpenCvYaml, "intrinsics.yml", sized);
    REQUIRE(pair.cameras.size() == 2);
    CHECK(pair.cameras[0].file.camera.lens == Lens{LensType::OpenCv5, {-0.1, 0.01, 0, 0, 0}});
    CHECK(pair.cameras[1].file.camera.lens.type == LensType::OpenCv5);
    CHECK(pair.cameras[1].file.camera.pose.R == kQuarterTurnZ);
    CHECK(pair.cameras[1].file.camera.pose.t == Vec3(-0.12, 0, 0.001));
}

TEST_CASE("OpenImuCameraCalibrator's JSON, as UMI ships its GoPro calibration: fy is the aspect ratio times f") {
    // The numbers of UMI's example/calibration/gopro_intrinsics_2_7k.json.
    const std::string text = R"({
    "final_reproj_error": 0.2916398582648,
    "fps": 59.94005994005994,
    "image_height": 2028,
    "image_width": 2704,
    "intrinsic_type": "FISHEYE",
    "intrinsics": {
        "aspect_ratio": 1.0029788958491257,
        "focal_length": 796.8544625226342,
        "principal_pt_x": 1354.4265245977356,
        "principal_pt_y": 1011.4847310011687,
        "radial_distortion_1": -0.02196117964405394,
        "radial_distortion_2": -0.018959717016668237,
        "radial_distortion_3": 0.001693880829392453,
        "radial_distortion_4": -0.00016807228608000285,
        "skew": 0.0
    },
    "nr_calib_images": 59,
    "stabelized": false
})";
    test::TempDir dir;
    write_file_atomically(dir.path() / "gopro_intrinsics_2_7k.json", text);
    const CameraSet set = read_camera_set(dir.path() / "gopro_intrinsics_2_7k.json");
    CHECK(set.format == CameraFormat::Openicc);
    const Camera& camera = set.cameras.front().file.camera;
    CHECK(camera.size == ImageSize{2704, 2028});
    check_intrinsics(camera, 796.8544625226342, 1.0029788958491257 * 796.8544625226342, 1354.4265245977356,
                     1011.4847310011687);
    CHECK(camera.lens == Lens{LensType::Fisheye,
                              {-0.02196117964405394, -0.018959717016668237, 0.001693880829392453,
                               -0.00016807228608000285}});
    // The calibrator's other types, each with the parameters its writer puts in the file
    // (theia's models: Double Sphere and EUCM as Usenko's papers define them).
    const auto with = [](const std::string& type, const std::string& parameters) {
        return R"({"image_width": 960, "image_height": 540, "intrinsic_type": ")" + type +
               R"(", "intrinsics": {"focal_length": 400.0, "aspect_ratio": 1.25, "principal_pt_x": 480.5,
               "principal_pt_y": 270.25, "skew": 0.0)" + parameters + "}}";
    };
    const Camera ds = parse_camera(with("DOUBLE_SPHERE", R"(, "xi": -0.09694, "alpha": 0.52873)"), CameraFormat::Openicc,
                                   "ds.json").camera;
    check_intrinsics(ds, 400.0, 500.0, 480.5, 270.25);
    CHECK(ds.lens == Lens{LensType::DoubleSphere, {-0.09694, 0.52873}});
    const Camera eucm = parse_camera(with("EXTENDED_UNIFIED", R"(, "alpha": 0.6, "beta": 1.1)"), CameraFormat::Openicc,
                                     "eucm.json").camera;
    CHECK(eucm.lens == Lens{LensType::Eucm, {0.6, 1.1}});
    CHECK(parse_camera(with("PINHOLE", ""), CameraFormat::Openicc, "p.json").camera.lens.type == LensType::Pinhole);
    // DIVISION_UNDISTORTION: Theia's k is per squared pixel; libcam's DIVISION takes it per
    // squared focal length, k f^2 = -3.588e-07 * 400^2 = -0.057408 (worked by hand).
    const Camera division = parse_camera(R"({"image_width": 960, "image_height": 540,
        "intrinsic_type": "DIVISION_UNDISTORTION", "intrinsics": {"focal_length": 400.0, "aspect_ratio": 1.0,
        "principal_pt_x": 480.5, "principal_pt_y": 270.25, "div_undist_distortion": -3.588e-07}})",
                                         CameraFormat::Openicc, "d.json").camera;
    check_intrinsics(division, 400.0, 400.0, 480.5, 270.25);
    REQUIRE(division.lens.type == LensType::Division);
    CHECK(division.lens.coefficients[0] == Approx(-0.057408).epsilon(1e-14));
    // With fx != fy Theia's division (in pixels) is not radial in m: refused, saying so.
    CHECK_THAT(file_error_of([&] {
                   (void)parse_camera(with("DIVISION_UNDISTORTION", R"(, "div_undist_distortion": -3.588e-07)"),
                                      CameraFormat::Openicc, "d.json");
               }),
               Catch::StartsWith("d.json: \"intrinsics.aspect_ratio\": the division undistortion lens is read with "
                                 "an aspect ratio of 1 only"));
    CHECK_THAT(file_error_of([&] { (void)parse_camera(with("FOV", ""), CameraFormat::Openicc, "f.json"); }),
               Catch::Contains("\"intrinsic_type\": must be FISHEYE, DOUBLE_SPHERE, EXTENDED_UNIFIED, "
                               "DIVISION_UNDISTORTION or PINHOLE"));
    CHECK_THAT(file_error_of([&] { (void)parse_camera(with("DOUBLE_SPHERE", R"(, "xi": 0.1)"), CameraFormat::Openicc, "x.json"); }),
               Catch::Contains("x.json: \"intrinsics.alpha\": missing"));
    CHECK_THROWS_AS(format_camera(camera, CameraFormat::Openicc), NotRepresentable);
}

TEST_CASE("OpenImuCameraCalibrator's layout as other writers fill it: focal lengths, OpenCV's list, the image's shape refused") {
    // A script writing cv2.calibrateCamera's K and dist in the calibrator's layout
    // (focal_length_x, focal_length_y, "radial_distortion": dist[0], OpenCV's order).
    const Camera opencv = parse_camera(R"({"image_width": 1920.0, "image_height": 1080, "intrinsic_type": "PINHOLE",
        "intrinsics": {"focal_length_x": 1000.5, "focal_length_y": 998.25, "principal_pt_x": 961.5,
        "principal_pt_y": 540.75, "skew": 0.0, "radial_distortion": [-0.12, 0.03, 0.001, -0.002, 0.004]}})",
                                       CameraFormat::Openicc, "gopro_intrinsics_pinhole.json").camera;
    check_intrinsics(opencv, 1000.5, 998.25, 961.5, 540.75);
    CHECK(opencv.lens == Lens{LensType::OpenCv5, {-0.12, 0.03, 0.001, -0.002, 0.004}});
    const Camera four = parse_camera(R"({"image_width": 640, "image_height": 480, "intrinsic_type": "PINHOLE",
        "intrinsics": {"focal_length_x": 500, "focal_length_y": 501, "principal_pt_x": 320, "principal_pt_y": 240,
        "dist_coeffs": [0.1, -0.2, 0.0, 0.0]}})",
                                     CameraFormat::Openicc, "s21.json").camera;
    CHECK(four.lens == Lens{LensType::OpenCv4, {0.1, -0.2, 0.0, 0.0}});
    // UMI's RealSense colour camera (example/calibration/realsense_intrinsics.json), as UMI
    // ships it: fx and fy themselves, no distortion, no skew.
    const Camera umi = parse_camera(R"({
    "image_height": 720,
    "image_width": 1280,
    "intrinsic_type": "PINHOLE",
    "intrinsics": {
      "fx": 914.43774414,
      "fy": 912.53448486,
      "principal_pt_x": 646.18066406,
      "principal_pt_y": 369.3788147
    }
}  )",
                                    CameraFormat::Openicc, "realsense_intrinsics.json").camera;
    check_intrinsics(umi, 914.43774414, 912.53448486, 646.18066406, 369.3788147);
    CHECK(umi.size == ImageSize{1280, 720});
    CHECK(umi.lens.type == LensType::Pinhole);
    CHECK(umi.intrinsics.skew == 0.0);
    // Found by its keys among the .json formats.
    {
        test::TempDir dir;
        const auto path = dir / "realsense_intrinsics.json";
        std::ofstream(path) << R"({"image_height": 720, "image_width": 1280, "intrinsic_type": "PINHOLE",
            "intrinsics": {"fx": 914.43774414, "fy": 912.53448486, "principal_pt_x": 646.18066406,
            "principal_pt_y": 369.3788147}})";
        CHECK(read_camera_set(path).format == CameraFormat::Openicc);
    }
    // Without any focal length, one line saying which keys give one.
    CHECK_THAT(file_error_of([&] {
                   (void)parse_camera(R"({"image_width": 640, "image_height": 480, "intrinsic_type": "PINHOLE",
                       "intrinsics": {"principal_pt_x": 320, "principal_pt_y": 240}})",
                                      CameraFormat::Openicc, "none.json");
               }),
               Catch::Contains("none.json: \"intrinsics\": no focal length: expected the calibrator's focal_length"));
    // A RealSense's PINHOLE with fisheye keys at 0 and aspect_ratio 1: no distortion.
    const auto realsense = [](const std::string& aspect, const std::string& k1) {
        return R"({"image_width": 848, "image_height": 480, "intrinsic_type": "PINHOLE", "intrinsics": {"aspect_ratio": )" +
               aspect + R"(, "focal_length": 419.8328552246094, "principal_pt_x": 429.5089416503906,
               "principal_pt_y": 237.1636505126953, "radial_distortion_1": )" + k1 +
               R"(, "radial_distortion_2": 0.0, "skew": 0.0}})";
    };
    const Camera plain = parse_camera(realsense("1.0", "0.0"), CameraFormat::Openicc, "realsense_intrinsics.json").camera;
    check_intrinsics(plain, 419.8328552246094, 419.8328552246094, 429.5089416503906, 237.1636505126953);
    CHECK(plain.lens.type == LensType::Pinhole);
    // 848 / 480 = 1.7666...: the image's shape in the focal's aspect, which would make fy
    // 742 px: refused, saying so.
    CHECK_THAT(file_error_of([&] {
                   (void)parse_camera(realsense("1.7666666666666666", "0.0"), CameraFormat::Openicc, "r.json");
               }),
               Catch::Contains("r.json: \"intrinsics.aspect_ratio\": 1.7666666666666666 is the image's width / height"));
    CHECK_THAT(file_error_of([&] { (void)parse_camera(realsense("1.0", "0.1"), CameraFormat::Openicc, "k.json"); }),
               Catch::Contains("k.json: \"intrinsics.radial_distortion_1\": a PINHOLE with fisheye coefficients"));
    CHECK_THAT(file_error_of([&] {
                   (void)parse_camera(R"({"image_width": 640, "image_height": 480, "intrinsic_type": "PINHOLE",
                       "intrinsics": {"focal_length_x": 500, "focal_length_y": 501, "principal_pt_x": 320,
                       "principal_pt_y": 240, "dist_coeffs": [0.1, -0.2, 0.0]}})",
                                      CameraFormat::Openicc, "three.json");
               }),
               Catch::Contains("three.json: \"intrinsics.dist_coeffs\": expected OpenCV's 4, 5, 8, 12 or 14 coefficients"));
}

TEST_CASE("basalt's calibration JSON written: every key basalt's loader asks for, UCM in basalt's parametrisation") {
    Camera camera;
    camera.size = {512, 512};
    camera.intrinsics = {380.0, 379.5, 255.5, 256.25, 0.0};
    camera.lens = {LensType::Ucm, {1.5}};
    camera.pose = {kQuarterTurnZ, Vec3(0.01, -0.02, 0.03)};
    const std::string text = format_camera(camera, CameraFormat::Basalt);
    // The keys of basalt's serialize(Calibration) (basalt/serialization/headers_serialization.h).
    for (const char* key : {"\"T_imu_cam\"", "\"intrinsics\"", "\"resolution\"", "\"calib_accel_bias\"",
                            "\"calib_gyro_bias\"", "\"imu_update_rate\"", "\"accel_noise_std\"", "\"gyro_noise_std\"",
                            "\"accel_bias_std\"", "\"gyro_bias_std\"", "\"cam_time_offset_ns\"", "\"vignette\""}) {
        CHECK_THAT(text, Catch::Contains(key));
    }
    // basalt's ucm: alpha = xi / (1 + xi) = 0.6, f / (1 + xi) = 152 and 151.8.
    CHECK_THAT(text, Catch::Contains("\"camera_type\": \"ucm\""));
    CHECK_THAT(text, Catch::Contains("\"alpha\": 0.6"));
    CHECK_THAT(text, Catch::Contains("\"fx\": 152.0"));
    // The camera in the IMU frame: R^T is a quarter turn the other way, qz = -sin(45 deg);
    // its centre -R^T t = (0.02, 0.01, -0.03).
    CHECK_THAT(text, Catch::Contains("\"px\": 0.02"));
    CHECK_THAT(text, Catch::Contains("\"py\": 0.01"));
    CHECK_THAT(text, Catch::Contains("\"pz\": -0.03"));
    const Camera back = parse_camera(text, CameraFormat::Basalt, "calib.json").camera;
    CHECK(back.lens.type == LensType::Ucm);
    CHECK_THAT(back.lens.coefficients[0], Catch::WithinRel(1.5, 1e-15));
    CHECK_THAT(back.intrinsics.fx, Catch::WithinRel(380.0, 1e-15));
    CHECK((back.pose.R - camera.pose.R).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((back.pose.t - camera.pose.t).cwiseAbs().maxCoeff() < 1e-15);

    camera.lens = {LensType::OpenCv5, {-0.2, 0.05, 1e-3, -2e-3, 0.01}};
    const std::string radtan8 = format_camera(camera, CameraFormat::Basalt);
    CHECK_THAT(radtan8, Catch::Contains("\"camera_type\": \"pinhole-radtan8\""));
    CHECK_THAT(radtan8, Catch::Contains("\"k3\": 0.01"));
    CHECK_THAT(radtan8, Catch::Contains("\"k6\": 0.0"));
    camera.lens = {LensType::Fov, {0.9}};
    CHECK_THAT(format_camera(camera, CameraFormat::Basalt), Catch::Contains("\"w\": 0.9"));
    camera.lens = {LensType::Mei, {1.5, -0.2, 0.03, 1e-4, -2e-4}};
    CHECK_THROWS_WITH(format_camera(camera, CameraFormat::Basalt), Catch::StartsWith("basalt has no model for a MEI lens"));
    // A MEI without distortion is a UCM, and written as one.
    camera.lens = {LensType::Mei, {1.5, 0, 0, 0, 0}};
    CHECK_THAT(format_camera(camera, CameraFormat::Basalt), Catch::Contains("\"camera_type\": \"ucm\""));
    camera.lens = {LensType::Pinhole, {}};
    camera.intrinsics.skew = 0.5;
    CHECK_THROWS_WITH(format_camera(camera, CameraFormat::Basalt), Catch::Contains("no skew"));
}

TEST_CASE("Blender's camera JSON: bpy's settings to K and the pose, worked by hand, and what it refuses") {
    const std::string text = R"({"format": "libcam Blender cameras", "cameras": [
      {"name": "Side", "frame": 7, "resolution_x": 1600, "resolution_y": 1200, "resolution_percentage": 50,
       "type": "PERSP", "lens": 35, "sensor_fit": "VERTICAL", "sensor_height": 20, "pixel_aspect_y": 1.5,
       "shift_x": 0.1, "shift_y": -0.2,
       "matrix_world": [[2, 0, 0, 1], [0, 0, -2, 2], [0, 2, 0, 3], [0, 0, 0, 1]]}]})";
    const CameraSet set = parse_camera_set(text, CameraFormat::BlenderJson, "b.json");
    REQUIRE(set.cameras.size() == 1);
    CHECK(set.cameras[0].name == "Side@7");
    const Camera& camera = set.cameras[0].file.camera;
    // 1600x1200 at 50%: 800x600. The sensor fitted down: fy = 35 x 600 / 20 = 1050; pixels
    // 1.5 times taller than wide: fx = 1.5 fy = 1575. The shift is in units of the fitted
    // side, each axis in its own pixels: 0.1 x 20 / 35 x 1575 = 90 across, -0.2 x 600 = -120
    // down (Blender's y up): cx = 399.5 - 90, cy = 299.5 - 120.
    CHECK(camera.size == ImageSize{800, 600});
    CHECK(camera.intrinsics.fy == Approx(1050).epsilon(1e-15));
    CHECK(camera.intrinsics.fx == Approx(1575).epsilon(1e-15));
    CHECK(camera.intrinsics.cx == Approx(309.5).epsilon(1e-15));
    CHECK(camera.intrinsics.cy == Approx(179.5).epsilon(1e-15));
    // The object scaled by 2 (Blender renders without the scale) and turned a quarter about
    // X: it looks along +Y with +Z up, at (1, 2, 3).
    Mat3 expected_R;
    expected_R << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    CHECK((camera.pose.R - expected_R).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((camera.pose.centre() - Vec3(1, 2, 3)).norm() < 1e-15);
    // Written back: the same camera (the sensor fitted across, 36 mm wide).
    const Camera back = parse_camera(format_camera(camera, CameraFormat::BlenderJson), CameraFormat::BlenderJson, "c.json").camera;
    CHECK(back.intrinsics.K().isApprox(camera.intrinsics.K(), 1e-14));
    CHECK(back.pose.R.isApprox(camera.pose.R, 1e-14));
    CHECK(back.pose.t.isApprox(camera.pose.t, 1e-14));

    // A panoramic equisolid fisheye with wide pixels: Cycles' sensor is 36 mm across and
    // 36 x (480 x 1) / (640 x 2) = 13.5 mm down (its sensor_height, 24, is not used):
    // fx = 9 x 640 / 36 = 160, fy = 9 x 480 / 13.5 = 320. The shift moves the axis by
    // shift x W and shift x H: cx = 319.5 - 0.05 x 640 = 287.5, cy = 239.5 + 0.1 x 480 = 287.5.
    const std::string fisheye = R"({"format": "libcam Blender cameras", "cameras": [
      {"resolution_x": 640, "resolution_y": 480, "pixel_aspect_x": 2, "type": "PANO",
       "panorama_type": "FISHEYE_EQUISOLID", "fisheye_lens": 9, "fisheye_fov": 3.14, "sensor_fit": "HORIZONTAL",
       "sensor_width": 36, "sensor_height": 24, "shift_x": 0.05, "shift_y": 0.1}]})";
    const Camera solid = parse_camera_set(fisheye, CameraFormat::BlenderJson, "f.json").cameras.at(0).file.camera;
    CHECK(solid.lens.type == LensType::Equisolid);
    CHECK(solid.intrinsics.fx == Approx(160).epsilon(1e-15));
    CHECK(solid.intrinsics.fy == Approx(320).epsilon(1e-15));
    CHECK(solid.intrinsics.cx == Approx(287.5).epsilon(1e-15));
    CHECK(solid.intrinsics.cy == Approx(287.5).epsilon(1e-15));
    const Camera solid_back =
        parse_camera(format_camera(solid, CameraFormat::BlenderJson), CameraFormat::BlenderJson, "g.json").camera;
    CHECK(solid_back.intrinsics.K().isApprox(solid.intrinsics.K(), 1e-14));

    const auto refused = [](const std::string& camera_json) {
        return file_error_of([&] {
            (void)parse_camera_set(R"({"format": "libcam Blender cameras", "cameras": [)" + camera_json + "]}",
                                   CameraFormat::BlenderJson, "bad.json");
        });
    };
    CHECK_THAT(refused(R"({"type": "ORTHO", "resolution_x": 10, "resolution_y": 10})"),
               Catch::Contains("bad.json: \"cameras[0].type\": an orthographic camera"));
    CHECK_THAT(refused(R"({"type": "PANO", "panorama_type": "MIRRORBALL", "resolution_x": 10, "resolution_y": 10})"),
               Catch::Contains("\"cameras[0].panorama_type\": libcam reads FISHEYE_EQUIDISTANT") &&
                   Catch::Contains("got 'MIRRORBALL'"));
    CHECK_THAT(refused(R"({"type": "PERSP", "lens": 50, "resolution_x": 10, "resolution_y": 10, "pixel_aspect_x": 0.5})"),
               Catch::Contains("pixel_aspect_x: Blender takes 1 to 200, got 0.5"));
    CHECK_THAT(refused(R"({"type": "PERSP", "lens": 50, "resolution_x": 10, "resolution_y": 10, "sensor_fit": "WIDE"})"),
               Catch::Contains("\"cameras[0].sensor_fit\": expected AUTO, HORIZONTAL or VERTICAL, got 'WIDE'"));
    CHECK_THAT(refused(R"({"type": "PERSP", "lens": 50, "resolution_x": 10, "resolution_y": 10,
                         "matrix_world": [[-1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]})"),
               Catch::Contains("\"cameras[0].matrix_world\""));
    CHECK_THAT(refused(R"({"type": "PERSP", "resolution_x": 10, "resolution_y": 10})"), Catch::Contains("lens"));
    CHECK_THAT(file_error_of([&] { (void)parse_camera_set("import bpy\n", CameraFormat::Blender, "camera.py"); }),
               Catch::Contains("camera.py: a Blender script is not read back"));
    // Written: a skewed pinhole and a distorted lens are not Blender's.
    Camera skewed = camera;
    skewed.intrinsics.skew = 2;
    CHECK_THROWS_AS(format_camera(skewed, CameraFormat::Blender), NotRepresentable);
    Camera distorted = camera;
    distorted.lens = {LensType::OpenCv4, {0.1, 0, 0, 0}};
    CHECK_THROWS_AS(format_camera(distorted, CameraFormat::BlenderJson), NotRepresentable);
    // ... and the refusal says what to do instead.
    CHECK_THROWS_WITH(format_camera(distorted, CameraFormat::Blender), Catch::Contains("libcam render-plan plans a render"));
}

// ---- COLMAP's EQUIRECTANGULAR (COLMAP 4.1, id 17, parameters "w, h")
TEST_CASE("COLMAP's EQUIRECTANGULAR read from cameras.txt and cameras.bin as LONLAT over the whole sphere",
          "[colmap][equirectangular]") {
    const std::string text = "1 EQUIRECTANGULAR 4000 2000 4000 2000\n";
    std::string bytes;
    const auto put = [](std::string& out, const auto& value) {
        out.append(reinterpret_cast<const char*>(&value), sizeof(value));
    };
    put(bytes, std::uint64_t{1});
    put(bytes, std::uint32_t{1});
    put(bytes, std::int32_t{17});
    put(bytes, std::uint64_t{4000});
    put(bytes, std::uint64_t{2000});
    put(bytes, 4000.0);
    put(bytes, 2000.0);
    for (const auto& [file, source] : {std::pair{text, "cameras.txt"}, std::pair{bytes, "cameras.bin"}}) {
        INFO(source);
        const CameraSet set = parse_camera_set(file, CameraFormat::Colmap, source);
        REQUIRE(set.cameras.size() == 1);
        const Camera& camera = set.cameras[0].file.camera;
        CHECK(camera.lens.type == LensType::Lonlat);
        CHECK(camera.size == ImageSize{4000, 2000});
        // fx = w / (2 pi), fy = h / pi: 2000 / pi both; the centre at (w / 2, h / 2) - 0.5.
        CHECK(camera.intrinsics.fx == Approx(2000 / std::numbers::pi).epsilon(1e-15));
        CHECK(camera.intrinsics.fy == Approx(2000 / std::numbers::pi).epsilon(1e-15));
        CHECK(camera.intrinsics.cx == 1999.5);
        CHECK(camera.intrinsics.cy == 999.5);
    }
    const Camera camera = parse_camera_set(text, CameraFormat::Colmap, "cameras.txt").cameras[0].file.camera;
    CHECK_THAT(format_camera_files(camera, CameraFormat::Colmap)[0].text,
               Catch::EndsWith("\n1 EQUIRECTANGULAR 4000 2000 4000 2000\n"));
    CHECK_THAT(file_error_of([] {
                   (void)parse_camera_set("1 EQUIRECTANGULAR 4000 2000 4000\n", CameraFormat::Colmap, "cameras.txt");
               }),
               Catch::Contains("cameras.txt"));
}
