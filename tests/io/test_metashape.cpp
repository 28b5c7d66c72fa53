// Agisoft Metashape's cameras.xml and calibration XML: the real files of
// real-data/metashape (SOURCES.md section 4 gives their numbers), and small documents
// whose pixels are worked out here with Metashape's own formula (its manual's appendix
// "Camera models"), which is what pins the P1/P2 swap, b1/b2 and the pixel centre.

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "cli_runner.hpp"
#include "error_message.hpp"
#include "real_cameras.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using libcam::test::file_error_of;

namespace {

// Metashape's terms of a frame or fisheye sensor.
struct Terms {
    double w, h, f, cx, cy, b1, b2, k1, k2, k3, k4, p1, p2;
};

// Metashape's pixel of a camera-frame point (its convention: the top-left pixel's centre
// is (0.5, 0.5)), by the manual's formula, written out term by term.
Vec2 metashape_pixel(const Terms& c, const Vec3& point, bool fisheye) {
    double x = point.x() / point.z();
    double y = point.y() / point.z();
    if (fisheye) {
        const double r0 = std::sqrt(x * x + y * y);
        x = x * std::atan(r0) / r0;
        y = y * std::atan(r0) / r0;
    }
    const double r2 = x * x + y * y;
    const double radial = 1 + c.k1 * r2 + c.k2 * r2 * r2 + c.k3 * r2 * r2 * r2 + c.k4 * r2 * r2 * r2 * r2;
    const double xd = x * radial + (c.p1 * (r2 + 2 * x * x) + 2 * c.p2 * x * y);
    const double yd = y * radial + (c.p2 * (r2 + 2 * y * y) + 2 * c.p1 * x * y);
    return {c.w * 0.5 + c.cx + xd * c.f + xd * c.b1 + yd * c.b2, c.h * 0.5 + c.cy + yd * c.f};
}

const Terms kFrame{640, 480, 1000, 12.5, -7.25, 3, -1.5, 0.1, -0.05, 0.01, 0, 0.002, -0.003};

std::string sensor_xml(const Terms& c, const std::string& type) {
    auto n = [](double v) { return std::to_string(v); };
    return "      <sensor id=\"0\" label=\"lens A\" type=\"" + type + "\">\n"
           "        <resolution width=\"640\" height=\"480\"/>\n"
           "        <calibration type=\"" + type + "\" class=\"initial\">\n"
           "          <resolution width=\"640\" height=\"480\"/>\n          <f>999</f>\n        </calibration>\n"
           "        <calibration type=\"" + type + "\" class=\"adjusted\">\n"
           "          <resolution width=\"640\" height=\"480\"/>\n"
           "          <f>" + n(c.f) + "</f><cx>" + n(c.cx) + "</cx><cy>" + n(c.cy) + "</cy><b1>" + n(c.b1) +
           "</b1><b2>" + n(c.b2) + "</b2>\n          <k1>" + n(c.k1) + "</k1><k2>" + n(c.k2) + "</k2><k3>" +
           n(c.k3) + "</k3><k4>" + n(c.k4) + "</k4><p1>" + n(c.p1) + "</p1><p2>" + n(c.p2) + "</p2>\n"
           "        </calibration>\n      </sensor>\n";
}

// A camera-to-chunk rotation about y and a chunk-to-world rotation about z, scale 2.
const Mat3 kCameraToChunk = (Mat3() << 0.6, 0, 0.8, 0, 1, 0, -0.8, 0, 0.6).finished();
const Vec3 kCameraInChunk(1, -2, 0.5);
const Mat3 kChunkToWorld = (Mat3() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished();
const Vec3 kChunkTranslation(10, 20, 30);
constexpr double kChunkScale = 2.0;
// .xml holds several formats: an error says which one the file's keys made it.
const std::string kAsMetashape = " (read as Agisoft Metashape XML, by its extension .xml and its keys)";

std::string document_xml(const std::string& sensor, const std::string& version = "2.0.0") {
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<document version=\"" + version + "\">\n"
           "  <chunk label=\"Chunk 1\" enabled=\"true\">\n    <sensors next_id=\"1\">\n" + sensor +
           "    </sensors>\n    <components next_id=\"1\" active_id=\"0\">\n"
           "      <component id=\"0\" label=\"Component 1\"/>\n    </components>\n"
           "    <cameras next_id=\"3\" next_group_id=\"1\">\n"
           "      <group id=\"0\" label=\"folder\" type=\"folder\">\n"
           "      <camera id=\"0\" sensor_id=\"0\" component_id=\"0\" label=\"IMG_0001\">\n"
           "        <transform>0.6 0 0.8 1 0 1 0 -2 -0.8 0 0.6 0.5 0 0 0 1</transform>\n      </camera>\n"
           "      </group>\n"
           "      <camera id=\"1\" sensor_id=\"0\" component_id=\"0\" label=\"IMG_0002\"/>\n"
           "    </cameras>\n"
           "    <transform>\n      <rotation locked=\"true\">0 -1 0 1 0 0 0 0 1</rotation>\n"
           "      <translation locked=\"true\">10 20 30</translation>\n      <scale locked=\"true\">2</scale>\n"
           "    </transform>\n  </chunk>\n</document>\n";
}

// A world point and the same point in the camera's own (chunk-scaled) frame, undoing
// Metashape's chain world = s R_chunk (R_cam X_cam + t_cam) + t_chunk by hand.
Vec3 camera_point_of(const Vec3& world) {
    const Vec3 in_chunk = kChunkToWorld.transpose() * (world - kChunkTranslation) / kChunkScale;
    return kCameraToChunk.transpose() * (in_chunk - kCameraInChunk);
}

// World points 7 units in front of the test's camera, at the centre and towards each side.
std::vector<Vec3> points_in_view() {
    const Vec3 camera_in_world = kChunkScale * (kChunkToWorld * kCameraInChunk) + kChunkTranslation;
    const Vec3 forward = kChunkToWorld * kCameraToChunk * Vec3(0, 0, 1);
    const Vec3 right = kChunkToWorld * kCameraToChunk * Vec3(1, 0, 0);
    const Vec3 down = kChunkToWorld * kCameraToChunk * Vec3(0, 1, 0);
    std::vector<Vec3> points;
    for (const auto& [a, b] : {std::pair{0.0, 0.0}, {0.3, -0.2}, {-0.25, 0.35}, {0.4, 0.3}}) {
        points.push_back(camera_in_world + 7.0 * forward + 7.0 * a * right + 7.0 * b * down);
    }
    return points;
}

void check_pixels(const Camera& camera, const Terms& terms, bool fisheye) {
    const PreparedCamera prepared(camera);
    for (const Vec3& world : points_in_view()) {
        const Vec2 expected = metashape_pixel(terms, camera_point_of(world), fisheye) - Vec2(0.5, 0.5);
        const Projection got = prepared.project(world);
        REQUIRE(got.valid);
        CHECK(std::abs(got.pixel.x() - expected.x()) < 1e-9);
        CHECK(std::abs(got.pixel.y() - expected.y()) < 1e-9);
    }
}

}  // namespace

TEST_CASE("metashape: a frame sensor projects as Metashape's formula, P1/P2 swapped, b1 b2 as fx and skew") {
    const test::TempDir dir;
    const auto path = write_file(dir, "cameras.xml", document_xml(sensor_xml(kFrame, "frame")));
    const CameraSet set = read_camera_set(path);
    CHECK(set.format == CameraFormat::Metashape);
    // The aligned camera first; the one without a transform (IMG_0002, not aligned) after
    // it, with its sensor's calibration and said to be unposed.
    REQUIRE(set.cameras.size() == 2);
    CHECK(set.cameras[0].name == "IMG_0001");
    CHECK(set.cameras[0].intrinsics_name == "lens A");
    CHECK_FALSE(set.cameras[0].unposed);
    CHECK(set.cameras[1].name == "IMG_0002");
    CHECK(set.cameras[1].intrinsics_name == "lens A");
    CHECK(set.cameras[1].unposed);
    CHECK(set.cameras[1].file.camera.intrinsics.K() == set.cameras[0].file.camera.intrinsics.K());
    CHECK(set.cameras[1].file.camera.lens == set.cameras[0].file.camera.lens);
    const Camera& camera = set.cameras[0].file.camera;
    CHECK(camera.lens.type == LensType::OpenCv5);
    CHECK(camera.intrinsics.fx == 1003.0);
    CHECK(camera.intrinsics.fy == 1000.0);
    CHECK(camera.intrinsics.skew == -1.5);
    CHECK(camera.intrinsics.cx == 320 + 12.5 - 0.5);
    CHECK(camera.intrinsics.cy == 240 - 7.25 - 0.5);
    check_pixels(camera, kFrame, false);
}

TEST_CASE("metashape: a fisheye sensor is Kannala-Brandt, k4 included") {
    Terms fisheye{640, 480, 300, -4, 6.5, 0, 0, 0.02, -0.01, 0.003, -0.0007, 0, 0};
    const test::TempDir dir;
    const auto path = write_file(dir, "cameras.xml", document_xml(sensor_xml(fisheye, "fisheye")));
    const Camera camera = read_camera_set(path).cameras.at(0).file.camera;
    CHECK(camera.lens.type == LensType::Fisheye);
    check_pixels(camera, fisheye, true);
}

TEST_CASE("metashape: a frame sensor with k4 (r^8) is BROWN_K4 and projects as Metashape's formula") {
    Terms with_k4 = kFrame;
    with_k4.k4 = 0.004;
    const test::TempDir dir;
    const auto path = write_file(dir, "cameras.xml", document_xml(sensor_xml(with_k4, "frame")));
    const Camera camera = read_camera_set(path).cameras.at(0).file.camera;
    CHECK(camera.lens.type == LensType::BrownK4);
    // OpenCV's order, Metashape's P1 and P2 swapped, k4 last.
    CHECK(camera.lens.coefficients == std::vector<double>{0.1, -0.05, -0.003, 0.002, 0.01, 0.004});
    check_pixels(camera, with_k4, false);
}

TEST_CASE("metashape: with no aligned camera, each camera is listed unposed with its sensor's calibration") {
    const test::TempDir dir;
    // As Metashape 1.5 exports a chunk before alignment: each camera's <reference> (its
    // GPS position) and no <transform>.
    std::string text = document_xml(sensor_xml(kFrame, "frame"), "1.5.0");
    text.replace(text.find("<transform>0.6"), std::string("<transform>").size(), "<reference>");
    text.replace(text.find("</transform>\n      </camera>"), std::string("</transform>").size(), "</reference>");
    const auto path = write_file(dir, "cameras.xml", text);
    const CameraSet set = read_camera_set(path);
    REQUIRE(set.cameras.size() == 2);
    for (const NamedCamera& named : set.cameras) {
        CHECK(named.unposed);
        CHECK(named.intrinsics_name == "lens A");
        CHECK(named.file.camera.pose.R == Mat3::Identity());
        CHECK(named.file.camera.pose.t == Vec3::Zero());
        // The sensor's adjusted calibration, by the header's mapping: fx = f + b1, cx = w/2 + cx - 0.5.
        CHECK(named.file.camera.intrinsics.fx == 1003.0);
        CHECK(named.file.camera.intrinsics.cx == 320 + 12.5 - 0.5);
    }
    CHECK(set.cameras[0].name == "IMG_0001");
    CHECK(set.cameras[1].name == "IMG_0002");
    // By its label, and by its sensor's label (the sensor's first camera).
    CHECK(&select_camera(set, "IMG_0002", path.string()) == &set.cameras[1]);
    CHECK(&select_camera(set, "lens A", path.string()) == &set.cameras[0]);
}

TEST_CASE("metashape: a chunk without cameras gives each calibrated sensor, without a pose") {
    const test::TempDir dir;
    std::string text = document_xml(sensor_xml(kFrame, "frame"), "1.5.0");
    const std::size_t cameras = text.find("    <cameras ");
    text.erase(cameras, text.find("    </cameras>\n") + std::string("    </cameras>\n").size() - cameras);
    const CameraSet set = read_camera_set(write_file(dir, "cameras.xml", text));
    REQUIRE(set.cameras.size() == 1);
    CHECK(set.cameras[0].name == "lens A");
    CHECK_FALSE(set.cameras[0].unposed);
    CHECK(set.cameras[0].file.camera.pose.R == Mat3::Identity());
}

TEST_CASE("metashape: a spherical sensor is LONLAT") {
    const test::TempDir dir;
    const std::string sensor = "      <sensor id=\"0\" label=\"360\" type=\"spherical\">\n"
                               "        <resolution width=\"4000\" height=\"2000\"/>\n"
                               "        <calibration type=\"spherical\" class=\"adjusted\">\n"
                               "          <resolution width=\"4000\" height=\"2000\"/><f>636.6</f>\n"
                               "        </calibration>\n      </sensor>\n";
    const Camera camera = read_camera_set(write_file(dir, "cameras.xml", document_xml(sensor))).cameras.at(0).file.camera;
    CHECK(camera.lens.type == LensType::Lonlat);
    // The point X in the camera's frame, taken to the world by Metashape's chain and back
    // by the pose read (which sees it scaled by the chunk's scale: LONLAT does not mind).
    const Vec3 in_camera = camera.pose.R * (kChunkScale * (kChunkToWorld * (kCameraToChunk * Vec3(1, -0.5, 2) +
                                                                             kCameraInChunk)) + kChunkTranslation) +
                           camera.pose.t;
    // Metashape: u = w/2 + f atan2(X, Z), v = h/2 + f atan2(Y, sqrt(X^2 + Z^2)), in its +0.5 pixels.
    const Vec3 X(1, -0.5, 2);
    const Vec2 expected(2000 + 636.6 * std::atan2(X.x(), X.z()) - 0.5,
                        1000 + 636.6 * std::atan2(X.y(), std::hypot(X.x(), X.z())) - 0.5);
    const Projection got = PreparedCamera(camera).project_camera_point(in_camera);
    REQUIRE(got.valid);
    CHECK(std::abs(got.pixel.x() - expected.x()) < 1e-9);
    CHECK(std::abs(got.pixel.y() - expected.y()) < 1e-9);
}

TEST_CASE("metashape: the calibration XML of Export Calibration is one camera") {
    const test::TempDir dir;
    const auto path = write_file(dir, "lens.xml",
                                 "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<calibration>\n"
                                 "  <projection>frame</projection>\n  <width>640</width>\n  <height>480</height>\n"
                                 "  <f>1000</f>\n  <cx>12.5</cx>\n  <cy>-7.25</cy>\n  <b1>3</b1>\n  <b2>-1.5</b2>\n"
                                 "  <k1>0.1</k1>\n  <k2>-0.05</k2>\n  <k3>0.01</k3>\n  <p1>0.002</p1>\n"
                                 "  <p2>-0.003</p2>\n  <date>2020-07-15T09:43:30Z</date>\n</calibration>\n");
    const CameraSet set = read_camera_set(path);
    CHECK(set.format == CameraFormat::Metashape);
    REQUIRE(set.cameras.size() == 1);
    const Camera& camera = set.cameras[0].file.camera;
    const PreparedCamera prepared(camera);
    for (const Vec3& point : {Vec3(0.1, 0.2, 1), Vec3(-0.3, 0.25, 1), Vec3(0.35, -0.3, 1.5)}) {
        const Vec2 expected = metashape_pixel(kFrame, point, false) - Vec2(0.5, 0.5);
        const Projection got = prepared.project_camera_point(point);
        CHECK(std::abs(got.pixel.x() - expected.x()) < 1e-9);
        CHECK(std::abs(got.pixel.y() - expected.y()) < 1e-9);
    }
}

TEST_CASE("metashape: what libcam cannot hold, and malformed files, are refused in one line") {
    const test::TempDir dir;
    std::string bad_f = document_xml(sensor_xml(kFrame, "frame"));
    bad_f.replace(bad_f.find("<f>1000.000000</f>"), 18, "<f>abc</f>");
    const auto bad = write_file(dir, "bad_f.xml", bad_f);
    CHECK(file_error_of([&] { read_camera_set(bad); }) ==
          bad.string() + ": line 13: sensor 0 ('lens A') <f>: must be a finite number, got 'abc'" + kAsMetashape);

    std::string short_transform = document_xml(sensor_xml(kFrame, "frame"));
    short_transform.replace(short_transform.find(" 0 0 0 1</transform>"), 20, " 0 0 0</transform>");
    const auto cut = write_file(dir, "cut.xml", short_transform);
    CHECK(file_error_of([&] { read_camera_set(cut); }) ==
          cut.string() + ": line 24: camera 0 ('IMG_0001') <transform>: expected 16 numbers, got 15" + kAsMetashape);

    std::string no_sensor = document_xml(sensor_xml(kFrame, "frame"));
    no_sensor.replace(no_sensor.find("sensor_id=\"0\""), 13, "sensor_id=\"7\"");
    const auto orphan = write_file(dir, "orphan.xml", no_sensor);
    CHECK(file_error_of([&] { read_camera_set(orphan); }) ==
          orphan.string() + ": line 23: camera 0 ('IMG_0001'): sensor_id '7' is not a sensor" + kAsMetashape);

    // A sensor's own type and size, which the adjusted calibration's stand for, checked all
    // the same: a type Metashape does not have, a negative width.
    std::string hologram = document_xml(sensor_xml(kFrame, "frame"));
    hologram.replace(hologram.find("type=\"frame\">"), 14, "type=\"hologram\">");
    const auto unknown = write_file(dir, "hologram.xml", hologram);
    CHECK(file_error_of([&] { read_camera_set(unknown); }) ==
          unknown.string() + ": line 5: sensor 0 ('lens A') <sensor> type: 'hologram' is not one of Metashape's sensor "
                             "types (frame, fisheye, spherical, cylindrical, rpc)" + kAsMetashape);
    std::string negative = document_xml(sensor_xml(kFrame, "frame"));
    negative.replace(negative.find("<resolution width=\"640\""), 23, "<resolution width=\"-640\"");
    const auto minus = write_file(dir, "negative.xml", negative);
    CHECK(file_error_of([&] { read_camera_set(minus); }) ==
          minus.string() + ": line 6: sensor 0 ('lens A') <resolution> width: must be a whole number of pixels in "
                           "[1, 1000000], got '-640'" + kAsMetashape);

    const auto collection = write_file(dir, "old.xml", "<?xml version=\"1.0\"?>\n<document><collection/></document>\n");
    CHECK_THROWS_AS(read_camera_set(collection, CameraFormat::Metashape), FileError);
}

// ---- real files (real-data/metashape; SOURCES.md section 4) ---------------------------

TEST_CASE("metashape: hwiyoung calib_lcam.xml and calib_lcam2.xml (Export Calibration)") {
    for (const auto& [name, cy] : {std::pair{"calib_lcam.xml", -12.57474453}, {"calib_lcam2.xml", 12.57474453}}) {
        const auto path = test::real_data_path(std::string("metashape/hwiyoung-MappingLocalization/calibration/") + name);
        if (!test::real_data_present(path)) {
            WARN("skipped: " << path << " is absent");
            continue;
        }
        const CameraSet set = read_camera_set(path);
        CHECK(set.format == CameraFormat::Metashape);
        REQUIRE(set.cameras.size() == 1);
        const Camera& camera = set.cameras[0].file.camera;
        CHECK(camera.size.width == 1384);
        CHECK(camera.size.height == 1032);
        CHECK(camera.intrinsics.fx == 1278.27004761879825);
        CHECK(camera.intrinsics.fy == 1278.27004761879825);
        CHECK(camera.intrinsics.cx == Approx(692 - 10.21222021 - 0.5).epsilon(1e-15));
        CHECK(camera.intrinsics.cy == Approx(516 + cy - 0.5).epsilon(1e-15));
        CHECK(camera.lens.type == LensType::OpenCv5);
        // OpenCV's k1 k2 p1 p2 k3: Metashape's p2 first, then its p1.
        CHECK(camera.lens.coefficients == std::vector<double>{-0.17759609150540318, 0.15681000753497404,
                                                               -8.50563182421899e-05, 0.00039689851424900256,
                                                               -0.08057988377985598});
    }
}

TEST_CASE("metashape: hwiyoung cameras.xml (1.5.0, no camera aligned) lists its 100 calibrated cameras unposed") {
    const auto path = test::real_data_path("metashape/hwiyoung-MappingLocalization/cameras.xml");
    if (!test::real_data_present(path)) {
        WARN("skipped: " << path << " is absent");
        return;
    }
    const CameraSet set = read_camera_set(path);
    // 120 cameras: 50 each of train_L and train_R, whose sensors are calibrated; the 20 of
    // test_L and test_R, whose sensors have no calibration, give none.
    REQUIRE(set.cameras.size() == 100);
    CHECK(std::all_of(set.cameras.begin(), set.cameras.end(), [](const NamedCamera& c) { return c.unposed; }));
    const NamedCamera& left = select_camera(set, "018864_L", path.string());
    CHECK(&left == &set.cameras[0]);
    CHECK(left.intrinsics_name == "train_L");
    // train_L's calibration as the file gives it: f 1278.2700476188, cy offset 12.57474453.
    CHECK(left.file.camera.intrinsics.fx == 1278.2700476188);
    CHECK(left.file.camera.intrinsics.cy == Approx(516 + 12.57474453 - 0.5).epsilon(1e-15));
    const NamedCamera& right = select_camera(set, "018864_R", path.string());
    CHECK(right.intrinsics_name == "train_R");
    CHECK(right.file.camera.intrinsics.fx == 1279.71039201197);
    // A sensor's label still finds its first camera.
    CHECK(&select_camera(set, "train_R", path.string()) == &right);
}

TEST_CASE("metashape: lab336 cameras.xml (2.0.0): 47 sensors, 47 aligned cameras") {
    const auto path = test::real_data_path("metashape/lab336-4DGS-Preprocess/cameras.xml");
    if (!test::real_data_present(path)) {
        WARN("skipped: " << path << " is absent");
        return;
    }
    const CameraSet set = read_camera_set(path);
    REQUIRE(set.cameras.size() == 47);
    const NamedCamera& first = set.cameras[0];
    CHECK(first.name == "1");
    CHECK(first.intrinsics_name == "unknown");
    const Camera& camera = first.file.camera;
    CHECK(camera.intrinsics.fx == 2856.9524860679976);
    CHECK(camera.intrinsics.cx == Approx(2112 + 3.1437666644205513 - 0.5).epsilon(1e-15));
    CHECK(camera.intrinsics.cy == Approx(1120 + 10.928669663959289 - 0.5).epsilon(1e-15));
    CHECK(camera.lens.type == LensType::OpenCv4);
    CHECK(camera.lens.coefficients == std::vector<double>{0.053295306997250054, -0.064655168915133746, 0, 0});
    // Its transform: camera to chunk, the chunk having no transform of its own.
    const Vec3 centre = camera.pose.centre();
    CHECK(centre.x() == Approx(0.696751976213839).margin(1e-12));
    CHECK(centre.y() == Approx(-2.1700298864605485).margin(1e-12));
    CHECK(centre.z() == Approx(-3.8210114260949233).margin(1e-12));
    CHECK(camera.pose.R(0, 1) == 0.14160089135320919);  // R = the transform's rotation transposed
    CHECK(set.cameras[46].name == "47");
}

TEST_CASE("metashape: bitbyt3r cameras.xml (1.5): b1 b2 as fx and skew, 94 cameras") {
    const auto path = test::real_data_path("metashape/bitbyt3r-metashape-automation/cameras.xml");
    if (!test::real_data_present(path)) {
        WARN("skipped: " << path << " is absent");
        return;
    }
    const CameraSet set = read_camera_set(path);
    REQUIRE(set.cameras.size() == 94);
    CHECK(set.cameras[0].name == "001");
    CHECK(set.cameras[0].intrinsics_name == "Canon EOS REBEL T5i (37mm)");
    const Camera& camera = set.cameras[0].file.camera;
    CHECK(camera.intrinsics.fx == 8397.0800252741 + 0.256163863908223);
    CHECK(camera.intrinsics.fy == 8397.0800252741);
    CHECK(camera.intrinsics.skew == -22.8315524998528);
    CHECK(camera.intrinsics.cx == 2591.5);
    CHECK(camera.intrinsics.cy == 1727.5);
    CHECK(camera.lens.coefficients == std::vector<double>{-0.0603472625149708, 0.184858521842878, 0.00126022593561743,
                                                           -0.00119014441157678});
    CHECK(camera.pose.centre().x() == Approx(-0.54581061063111036).margin(1e-12));
}

TEST_CASE("metashape: OpenCV's XML stays OpenCV's, and PhotoScan 0.9's collection (amarburg) is read") {
    const auto opencv = test::real_data_path("metashape/3dom-fbk-deep-image-matching/camera_calib.xml");
    if (test::real_data_present(opencv)) CHECK(read_camera_set(opencv).format == CameraFormat::OpenCvXml);
    const auto old = test::real_data_path("metashape/amarburg-photoscan_outputs/demo/cameras.xml");
    if (!test::real_data_present(old)) return;
    const CameraSet set = read_camera_set(old);
    CHECK(set.format == CameraFormat::Metashape);
    REQUIRE(set.cameras.size() == 16);  // 16 <camera>, each with a <transform>
    const NamedCamera& first = set.cameras[0];
    CHECK(first.name == "IMG_7618.jpg");
    CHECK_FALSE(first.unposed);
    const Camera& camera = first.file.camera;
    // Its <calibration> as written: cx, cy absolute, less half a pixel into OpenCV's.
    CHECK(camera.size == ImageSize{972, 648});
    CHECK(camera.intrinsics.fx == 1.8707469131103019e+003);
    CHECK(camera.intrinsics.fy == 1.8738616128634769e+003);
    CHECK(camera.intrinsics.cx == 5.2586579873845619e+002 - 0.5);
    CHECK(camera.intrinsics.cy == 4.0083738488303931e+002 - 0.5);
    CHECK(camera.intrinsics.skew == -8.6319592049510652e-001);
    CHECK(camera.lens == Lens{LensType::OpenCv5, {-1.6675726916786160e-001, 7.5676071357423513e-001,
                                                   -1.4556415480751863e-003, -5.2912191800171066e-005,
                                                   -2.1665527393930941e+000}});
    // Its centre: the collection's transform (s R | t) applied to the camera's position
    // (the fourth column of its own transform), worked out here from the file's numbers.
    const double c[3] = {7.0737615896838760e-002, -4.0025763682849508e-001, 2.0569299557796403e-001};
    const double g[12] = {2.7694900329729840e+001, 2.5392011594365184e+002, 5.4118470162177800e+001,
                          6.6670066415987478e+005, 2.5949821314888629e+002, -2.8762442620351280e+001,
                          2.1542666622218207e+000, 5.4456422027225094e+006, 8.0567652359546997e+000,
                          5.3558736089261856e+001, -2.5541689826685177e+002, 4.6848797492713061e+002};
    for (int i = 0; i < 3; ++i) {
        const double world = g[4 * i] * c[0] + g[4 * i + 1] * c[1] + g[4 * i + 2] * c[2] + g[4 * i + 3];
        CHECK(camera.pose.centre()(i) == Approx(world).epsilon(1e-12));
    }
}

namespace {

// Agisoft Lens's pixel of a camera-frame point (its manual 0.4, "Camera model"), pixel
// (0, 0) the top-left pixel's corner: P1 and P2 in OpenCV's order, cx and cy absolute.
Vec2 agisoft_lens_pixel(double fx, double fy, double cx, double cy, double skew, const double k[3], double p1,
                        double p2, const Vec3& point) {
    const double x = point.x() / point.z(), y = point.y() / point.z();
    const double r2 = x * x + y * y;
    const double radial = 1 + k[0] * r2 + k[1] * r2 * r2 + k[2] * r2 * r2 * r2;
    const double xd = x * radial + p2 * (r2 + 2 * x * x) + 2 * p1 * x * y;
    const double yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
    return {cx + xd * fx + yd * skew, cy + yd * fy};
}

}  // namespace

TEST_CASE("metashape: PhotoScan 0.9's collection projects as Agisoft Lens's formula, its scaled transform undone") {
    // As PhotoScan 0.9's Export Cameras writes it: one camera posed by the same rotations
    // as the documents above (camera to collection), the collection's transform a 4x4
    // [s R | t] with s = 2; and one camera not aligned.
    const double k[3] = {0.1, -0.05, 0.01};
    const std::string calibration =
        "      <calibration>\n        <width>640</width>\n        <height>480</height>\n"
        "        <fx>1000</fx>\n        <fy>1002</fy>\n        <cx>330.25</cx>\n        <cy>245.5</cy>\n"
        "        <skew>-0.8</skew>\n        <k1>0.1</k1>\n        <k2>-0.05</k2>\n        <k3>0.01</k3>\n"
        "        <p1>0.002</p1>\n        <p2>-0.003</p2>\n      </calibration>\n";
    const std::string text =
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<collection>\n  <cameras>\n"
        "    <camera label=\"IMG_0001.jpg\">\n      <resolution width=\"640\" height=\"480\"/>\n" + calibration +
        "      <transform>0.6 0 0.8 1 0 1 0 -2 -0.8 0 0.6 0.5 0 0 0 1</transform>\n    </camera>\n"
        "    <camera label=\"IMG_0002.jpg\">\n      <resolution width=\"640\" height=\"480\"/>\n" + calibration +
        "    </camera>\n  </cameras>\n"
        "  <transform>0 -2 0 10 2 0 0 20 0 0 2 30 0 0 0 1</transform>\n</collection>\n";
    const test::TempDir dir;
    const auto path = write_file(dir, "cameras.xml", text);
    const CameraSet set = read_camera_set(path);
    CHECK(set.format == CameraFormat::Metashape);
    REQUIRE(set.cameras.size() == 2);
    CHECK(set.cameras[0].name == "IMG_0001.jpg");
    CHECK_FALSE(set.cameras[0].unposed);
    CHECK(set.cameras[1].name == "IMG_0002.jpg");
    CHECK(set.cameras[1].unposed);
    const PreparedCamera prepared(set.cameras[0].file.camera);
    for (const Vec3& world : points_in_view()) {
        const Vec2 expected =
            agisoft_lens_pixel(1000, 1002, 330.25, 245.5, -0.8, k, 0.002, -0.003, camera_point_of(world)) - Vec2(0.5, 0.5);
        const Projection got = prepared.project(world);
        REQUIRE(got.valid);
        CHECK(std::abs(got.pixel.x() - expected.x()) < 1e-9);
        CHECK(std::abs(got.pixel.y() - expected.y()) < 1e-9);
    }
    // A collection transform that is no rotation with a scale: one line saying so.
    std::string sheared = text;
    sheared.replace(sheared.find("0 -2 0 10"), 9, "1 -2 0 10");
    const std::string message = file_error_of([&] { (void)read_camera_set(write_file(dir, "sheared.xml", sheared)); });
    CHECK_THAT(message, Catch::Contains("<collection> <transform>: not a rotation with a scale and a translation"));
    CHECK(message.find('\n') == std::string::npos);
}

// ---- the writer -----------------------------------------------------------------------

namespace {

// A term of a written file: the number in <name>...</name> within `text`, 0 where absent
// (Metashape leaves zeros out).
double written_term(const std::string& text, const std::string& name) {
    const std::string open = "<" + name + ">";
    const std::size_t at = text.find(open);
    if (at == std::string::npos) return 0.0;
    return std::stod(text.substr(at + open.size(), text.find('<', at + open.size()) - at - open.size()));
}

Terms written_terms(const std::string& text, double w, double h) {
    return {w, h, written_term(text, "f"), written_term(text, "cx"), written_term(text, "cy"),
            written_term(text, "b1"), written_term(text, "b2"), written_term(text, "k1"), written_term(text, "k2"),
            written_term(text, "k3"), written_term(text, "k4"), written_term(text, "p1"), written_term(text, "p2")};
}

// OpenCV's projection of a camera-frame point with distortion k1 k2 p1 p2 k3 (calib3d's
// documented formula, as cv::projectPoints computes it), worked out term by term; with a
// sixth coefficient, BROWN_K4's k4 r^8 added to the radial factor (brown_k4.hpp).
Vec2 opencv_pixel(const Camera& camera, const Vec3& point) {
    const double x = point.x() / point.z(), y = point.y() / point.z();
    const std::vector<double>& d = camera.lens.coefficients;
    const double r2 = x * x + y * y;
    const double k4 = d.size() > 5 ? d[5] : 0.0;  // BROWN_K4's r^8 term
    const double radial = 1 + d[0] * r2 + d[1] * r2 * r2 + d[4] * r2 * r2 * r2 + k4 * r2 * r2 * r2 * r2;
    const double xd = x * radial + 2 * d[2] * x * y + d[3] * (r2 + 2 * x * x);
    const double yd = y * radial + d[2] * (r2 + 2 * y * y) + 2 * d[3] * x * y;
    const Intrinsics& K = camera.intrinsics;
    return {K.fx * xd + K.skew * yd + K.cx, K.fy * yd + K.cy};
}

Camera opencv5_camera() {
    Camera camera;
    camera.size = {1280, 720};
    camera.intrinsics = {1001.125, 987.5, 700.25, 300.125, 2.5};
    camera.lens = {LensType::OpenCv5, {-0.2, 0.05, 1e-3, -2e-3, 0.01}};
    camera.pose = Pose::from_rvec(Vec3(0.3, -2.1, 0.7), Vec3(-12.5, 0.001, 4.0));
    return camera;
}

// The written terms, put through Metashape's own formula (its +0.5 pixels), give the
// pixels the camera's formula (opencv_pixel) gives.
void check_terms_give_opencv_pixels(const Terms& terms, const Camera& camera) {
    for (const Vec3& point : {Vec3(0.1, 0.2, 1), Vec3(-0.3, 0.25, 1), Vec3(0.35, -0.3, 1.5)}) {
        const Vec2 expected = opencv_pixel(camera, point);
        const Vec2 got = metashape_pixel(terms, point, false) - Vec2(0.5, 0.5);
        CHECK((got - expected).norm() < 1e-9);
    }
}

}  // namespace

TEST_CASE("metashape: written cameras.xml reads back the same camera, its terms in Metashape's conventions") {
    const test::TempDir dir;
    const Camera camera = opencv5_camera();
    WriteOptions options;
    options.image_name = "IMG_0042.JPG";
    options.camera_name = "lens B";
    const std::filesystem::path path = dir.path() / "cameras.xml";
    write_camera_file(path, camera, CameraFormat::Metashape, options);
    const CameraSet set = read_camera_set(path);
    CHECK(set.format == CameraFormat::Metashape);
    REQUIRE(set.cameras.size() == 1);
    CHECK(set.cameras[0].name == "IMG_0042");
    CHECK(set.cameras[0].intrinsics_name == "lens B");
    const Camera& back = set.cameras[0].file.camera;
    CHECK(back.size == camera.size);
    CHECK((back.intrinsics.K() - camera.intrinsics.K()).cwiseAbs().maxCoeff() < 1e-12);
    CHECK(back.lens == camera.lens);
    CHECK((back.pose.R - camera.pose.R).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((back.pose.t - camera.pose.t).cwiseAbs().maxCoeff() < 1e-14);

    // The written terms, put through Metashape's own formula (its +0.5 pixels), give the
    // pixels OpenCV's formula gives with the OpenCV lens: f = fy, b1 = fx - fy, b2 = skew,
    // P1 = OpenCV's p2.
    const std::string text = test::read_whole_file(path);
    const Terms terms = written_terms(text, 1280, 720);
    CHECK(terms.f == 987.5);
    CHECK(terms.b1 == 1001.125 - 987.5);
    CHECK(terms.b2 == 2.5);
    CHECK(terms.cx == 700.25 - 639.5);
    CHECK(terms.cy == 300.125 - 359.5);
    CHECK(terms.p1 == -2e-3);
    CHECK(terms.p2 == 1e-3);
    check_terms_give_opencv_pixels(terms, camera);
}

TEST_CASE("metashape: a BROWN_K4 camera is written as a frame sensor with k4 and reads back the same") {
    const test::TempDir dir;
    Camera camera = opencv5_camera();
    camera.lens = {LensType::BrownK4, {-0.2, 0.05, 1e-3, -2e-3, 0.01, -0.003}};
    const std::filesystem::path path = dir.path() / "cameras.xml";
    write_camera_file(path, camera, CameraFormat::Metashape);
    const Camera back = read_camera_set(path).cameras.at(0).file.camera;
    CHECK(back.lens == camera.lens);
    CHECK((back.intrinsics.K() - camera.intrinsics.K()).cwiseAbs().maxCoeff() < 1e-12);
    const std::string text = test::read_whole_file(path);
    const Terms terms = written_terms(text, 1280, 720);
    CHECK(terms.k4 == -0.003);
    CHECK(terms.p1 == -2e-3);
    CHECK(terms.p2 == 1e-3);
    check_terms_give_opencv_pixels(terms, camera);
}

TEST_CASE("metashape: --no-pose writes Export Calibration's file, and what Metashape cannot hold is refused") {
    const test::TempDir dir;
    Camera camera = opencv5_camera();
    WriteOptions options;
    options.drop_pose = true;
    const std::filesystem::path path = dir.path() / "lens.xml";
    write_camera_file(path, camera, CameraFormat::Metashape, options);
    const std::string text = test::read_whole_file(path);
    CHECK(text.find("<calibration>") != std::string::npos);
    CHECK(text.find("<projection>frame</projection>") != std::string::npos);
    CHECK(text.find("<width>1280</width>") != std::string::npos);
    const Camera back = read_camera_file(path).camera;
    CHECK((back.intrinsics.K() - camera.intrinsics.K()).cwiseAbs().maxCoeff() < 1e-12);
    CHECK(back.lens == camera.lens);
    CHECK(back.pose.R == Mat3::Identity());

    camera.lens = {LensType::OpenCv8, {0.4, 0.05, 1e-3, -2e-3, 0.01, 0.7, 0.1, 0.02}};
    // The refusal names the file it was for.
    CHECK_THROWS_WITH(write_camera_file(dir.path() / "rational.xml", camera, CameraFormat::Metashape),
                      (dir.path() / "rational.xml").string() +
                          ": Agisoft Metashape XML has no model for a OPENCV8 lens (it holds PINHOLE, OPENCV4, OPENCV5, "
                          "BROWN_K4, FISHEYE and LONLAT)");
    CHECK_FALSE(std::filesystem::exists(dir.path() / "rational.xml"));
    camera.lens = {LensType::Lonlat, {}};
    CHECK_THROWS_AS(write_camera_file(dir.path() / "sphere.xml", camera, CameraFormat::Metashape), NotRepresentable);
    camera.intrinsics = {636.5, 636.5, 1999.5, 999.5, 0.0};
    camera.size = {4000, 2000};
    write_camera_file(dir.path() / "sphere.xml", camera, CameraFormat::Metashape);
    CHECK(read_camera_file(dir.path() / "sphere.xml").camera.lens.type == LensType::Lonlat);
}
