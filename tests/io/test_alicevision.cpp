// AliceVision's (Meshroom's) SfMData JSON: the real cameras.sfm of real-data (SOURCES.md
// section 5 gives its numbers), and small files written here the way AliceVision's
// sfmDataIO/jsonIO.cpp writes each version (every value a string, "" for an empty list),
// holding the camera of AliceVision's own sample scene (sfmDataIO/sceneSample.cpp: 4092 x
// 2048, fx 1000, fy 2000, principal point offset (-26, 16), pose 0 the angle-axis
// (-1, -1, -1) at centre (-1, -1, -1)), which its compatibility files write in every
// version. Pixels of the distortion models are worked out here with AliceVision's own
// formulas (camera/Distortion*.cpp, Equidistant.cpp), written out term by term.

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "libcam/camera/camera.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/observations.hpp"
#include "libcam/text/number_format.hpp"
#include "error_message.hpp"
#include "real_cameras.hpp"
#include "temp_dir.hpp"

using namespace libcam;
using libcam::test::file_error_of;

namespace {

// The sample scene's pose 0 as AliceVision writes it: rotation column by column.
const std::string kSamplePose =
    R"("poses": [{"poseId": "0", "pose": {"transform": {"rotation": ["0.22629564095020641", "-0.18300791965761709",)"
    R"( "0.95671227870741093", "0.95671227870741093", "0.22629564095020641", "-0.18300791965761709",)"
    R"( "-0.18300791965761709", "0.95671227870741093", "0.22629564095020641"], "center": ["-1", "-1", "-1"]},)"
    R"( "locked": "0"}}])";

const std::string kSampleView =
    R"("views": [{"viewId": "0", "poseId": "0", "intrinsicId": "1", "path": "", "width": "4092", "height": "2048",)"
    R"( "metadata": ""}])";

// One intrinsic of the sample scene (radial3, k = 0.1, 0.05, -0.001) in `version`'s keys.
std::string sample_file(const std::string& version, const std::string& intrinsic_keys) {
    return "{\"version\": [" + version + "], " + kSampleView + ", \"intrinsics\": [{\"intrinsicId\": \"1\", "
           "\"width\": \"4092\", \"height\": \"2048\", \"sensorWidth\": \"36\", \"sensorHeight\": \"24\", "
           "\"serialNumber\": \"\", " + intrinsic_keys + ", \"distortionParams\": [\"0.10000000000000001\", "
           "\"0.050000000000000003\", \"-0.001\"], \"locked\": \"0\"}], " + kSamplePose + "}";
}

void check_sample_camera(const Camera& camera) {
    CHECK(camera.size == ImageSize{4092, 2048});
    CHECK(camera.intrinsics.fx == Approx(1000.0).epsilon(1e-14));
    CHECK(camera.intrinsics.fy == Approx(2000.0).epsilon(1e-14));
    CHECK(camera.intrinsics.cx == 4092.0 / 2 - 26);
    CHECK(camera.intrinsics.cy == 2048.0 / 2 + 16);
    CHECK(camera.lens.type == LensType::OpenCv5);
    CHECK(camera.lens.coefficients == std::vector<double>{0.1, 0.05, 0.0, 0.0, -0.001});
    // Pose3(angle-axis (-1, -1, -1), centre (-1, -1, -1)): world to camera.
    const Mat3 R = rotation_from_rvec(Vec3(-1, -1, -1));
    CHECK((camera.pose.R - R).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((camera.pose.centre() - Vec3(-1, -1, -1)).cwiseAbs().maxCoeff() < 1e-14);
}

}  // namespace

TEST_CASE("AliceVision: Meshroom's cameras.sfm as SOURCES.md gives it", "[alicevision]") {
    const std::filesystem::path file = test::real_data_path("alicevision-meshroom-LoD2to3/data/meshroom/cameras.sfm");
    if (!test::real_data_present(file)) {
        WARN("skipped: " << file << " is absent");
        return;
    }
    const CameraSet set = read_camera_set(file);
    CHECK(set.format == CameraFormat::AliceVision);
    // 51 views, 34 of them with a pose: those first, then the 17 unposed ones.
    REQUIRE(set.cameras.size() == 51);
    for (std::size_t i = 0; i < set.cameras.size(); ++i) CHECK(set.cameras[i].unposed == (i >= 34));
    const NamedCamera& first = set.cameras.front();
    CHECK(first.name == "D:/DHBW/Studienarbeit/data/20250614_204908.jpg");
    // Found by the image's file name, as a user knows it; an unposed view too.
    CHECK(&select_camera(set, "20250614_204908.jpg", file.string()) == &first);
    const NamedCamera& unposed = select_camera(set, "20250614_203816.jpg", file.string());
    CHECK(unposed.name == "D:/DHBW/Studienarbeit/data/20250614_203816.jpg");
    CHECK(unposed.unposed);
    CHECK(unposed.file.camera.intrinsics.K() == first.file.camera.intrinsics.K());
    CHECK(first.intrinsics_name == "id:2390361049");
    const Camera& camera = first.file.camera;
    CHECK(camera.size == ImageSize{4000, 3000});
    // Version 1.2.6: fx = focalLength w / sensorWidth, fy = fx pixelRatio (1).
    CHECK(camera.intrinsics.fx == Approx(5.678361290663454 * 4000 / 8.1265990486979671).epsilon(1e-15));
    CHECK(camera.intrinsics.fx == Approx(2795.0).margin(0.05));
    CHECK(camera.intrinsics.fy == camera.intrinsics.fx);
    CHECK(camera.intrinsics.cx == Approx(2000 - 32.291769408137576).epsilon(1e-15));
    CHECK(camera.intrinsics.cy == Approx(1500 - 65.688458120059806).epsilon(1e-15));
    CHECK(camera.lens.type == LensType::OpenCv5);
    CHECK(camera.lens.coefficients ==
          std::vector<double>{0.082661234054845489, -0.1084229596836524, 0.0, 0.0, 0.030428071832084524});
    // The first pose's rotation, column by column, and its centre.
    CHECK(camera.pose.R(0, 0) == Approx(-0.54726054226490395).margin(1e-15));
    CHECK(camera.pose.R(1, 0) == Approx(-0.083008287634377204).margin(1e-15));
    CHECK(camera.pose.R(2, 0) == Approx(-0.83283583200048006).margin(1e-15));
    CHECK(camera.pose.R(0, 1) == Approx(0.012701820257427873).margin(1e-15));
    CHECK(camera.pose.R(2, 2) == Approx(-0.54299453619094473).margin(1e-15));
    CHECK((camera.pose.centre() - Vec3(29.731118199918939, -5.099125222686415, 2.5923796491303932)).norm() < 1e-12);
    // It holds no structure: no observations, said in one line.
    const std::string message = file_error_of([&] { read_observations(file); });
    CHECK(message.find("no observation") != std::string::npos);
}

TEST_CASE("AliceVision: every version's focal length and principal point give the sample scene's camera",
          "[alicevision]") {
    test::TempDir dir;
    // 1.2.0: pixels, the principal point absolute.
    const std::string v120 = sample_file("\"1\", \"2\", \"0\"",
        R"("type": "radial3", "pxInitialFocalLength": "-1", "pxFocalLength": ["1000", "2000"], "principalPoint": ["2020", "1040"])");
    // 1.2.2: millimetres; pixelRatio is fx / fy.
    const std::string v122 = sample_file("\"1\", \"2\", \"2\"",
        R"("type": "radial3", "initialFocalLength": "-1", "focalLength": "8.7976539589442808", "pixelRatio": "0.5", )"
        R"("pixelRatioLocked": "true", "principalPoint": ["-26", "16"])");
    // 1.2.5: pixelRatio is fy / fx, CRLF line ends.
    std::string v125 = sample_file("\"1\", \"2\", \"5\"",
        R"("type": "radial3", "initialFocalLength": "-1", "focalLength": "8.7976539589442808", "pixelRatio": "2",)"
        "\r\n" R"("pixelRatioLocked": "true", "principalPoint": ["-26", "16"], "undistortionParams": "")");
    // 1.2.11: focalLength is fy's; the model in type, distortionType and undistortionType.
    const std::string v1211 = sample_file("\"1\", \"2\", \"11\"",
        R"("type": "pinhole", "initialFocalLength": "-1", "focalLength": "17.595307917888562", "pixelRatio": "2", )"
        R"("pixelRatioLocked": "true", "offsetLocked": "false", "scaleLocked": "false", "principalPoint": ["-26", "16"], )"
        R"("distortionLocked": "false", "distortionType": "radialk3", "undistortionType": "none")");
    for (const auto& [name, text] : {std::pair{"v120.sfm", v120}, std::pair{"v122.sfm", v122},
                                      std::pair{"v125.sfm", v125}, std::pair{"v1211.sfm", v1211}}) {
        CAPTURE(name);
        const CameraSet set = read_camera_set(write_file(dir, name, text));
        REQUIRE(set.cameras.size() == 1);
        CHECK(set.cameras[0].intrinsics_name == "id:1");
        check_sample_camera(set.cameras[0].file.camera);
    }
    // The same file as .json is told from OpenMVG's and libcam's by its keys.
    CHECK(read_camera_set(write_file(dir, "sfm.json", v1211)).format == CameraFormat::AliceVision);
}

TEST_CASE("AliceVision: each distortion projects as AliceVision's formulas do", "[alicevision]") {
    test::TempDir dir;
    const auto intrinsic_file = [&](const std::string& type, const std::string& params) {
        return write_file(dir, type + ".sfm",
            "{\"version\": [\"1\", \"2\", \"6\"], \"intrinsics\": [{\"intrinsicId\": \"7\", \"width\": \"1200\", "
            "\"height\": \"800\", \"sensorWidth\": \"6\", \"sensorHeight\": \"4.5\", \"serialNumber\": \"\", \"type\": \"" +
            type + "\", \"initialFocalLength\": \"-1\", \"focalLength\": \"4.5\", \"pixelRatio\": \"1\", "
            "\"pixelRatioLocked\": \"true\", \"principalPoint\": [\"12.5\", \"-7.25\"], \"distortionParams\": " + params +
            "}]}");
    };
    const double f = 4.5 * 1200 / 6.0;  // 900 px
    const Vec2 pp(600 + 12.5, 400 - 7.25);
    const Vec3 point(0.31, -0.22, 1.0);
    const Vec2 p(point.x() / point.z(), point.y() / point.z());
    const double r2 = p.squaredNorm();
    const auto projected = [&](const std::filesystem::path& file) {
        const CameraSet set = read_camera_set(file);
        REQUIRE(set.cameras.size() == 1);
        CHECK(set.cameras[0].name == "id:7");  // no pose: the intrinsic itself
        const Projection projection = PreparedCamera(set.cameras[0].file.camera).project_camera_point(point);
        CHECK(projection.valid);
        return projection.pixel;
    };
    SECTION("brown: k1 k2 k3 t1 t2 (DistortionBrown::addDistortion)") {
        const double k1 = -0.12, k2 = 0.03, k3 = -0.004, t1 = 0.0021, t2 = -0.0013;
        const Vec2 d(p.x() + p.x() * (k1 * r2 + k2 * r2 * r2 + k3 * r2 * r2 * r2) + t2 * (r2 + 2 * p.x() * p.x()) +
                         2 * t1 * p.x() * p.y(),
                     p.y() + p.y() * (k1 * r2 + k2 * r2 * r2 + k3 * r2 * r2 * r2) + t1 * (r2 + 2 * p.y() * p.y()) +
                         2 * t2 * p.x() * p.y());
        const Vec2 got = projected(intrinsic_file("brown", R"(["-0.12", "0.03", "-0.004", "0.0021", "-0.0013"])"));
        CHECK((got - (f * d + pp)).norm() < 1e-9);
    }
    SECTION("fisheye4: theta (1 + k1 theta^2 + ... + k4 theta^8) / r (DistortionFisheye)") {
        const double k[] = {0.05, -0.01, 0.002, -0.0003};
        const double r = std::sqrt(r2);
        const double t = std::atan(r);
        const double td = t + k[0] * std::pow(t, 3) + k[1] * std::pow(t, 5) + k[2] * std::pow(t, 7) + k[3] * std::pow(t, 9);
        const Vec2 got = projected(intrinsic_file("fisheye4", R"(["0.05", "-0.01", "0.002", "-0.0003"])"));
        CHECK((got - (f * (td / r) * p + pp)).norm() < 1e-9);
    }
    SECTION("fisheye1: atan(2 r tan(w / 2)) / (w r) (DistortionFisheye1)") {
        const double w = 0.93;
        const double r = std::sqrt(r2);
        const double coefficient = std::atan(2.0 * r * std::tan(0.5 * w)) / w / r;
        const Vec2 got = projected(intrinsic_file("fisheye1", R"(["0.93"])"));
        CHECK((got - (f * coefficient * p + pp)).norm() < 1e-9);
    }
    SECTION("equidistant_r3: the angle over half the fov, radialk3pt, then the scale (Equidistant::project)") {
        const double k1 = 0.04, k2 = -0.006, k3 = 0.0007;
        const double fmm = f * 6.0 / 1200;              // scale * sensorWidth / max(w, h)
        const double fov = std::min(6.0, 4.5) / fmm;
        const double angle = std::atan2(std::hypot(point.x(), point.y()), point.z());
        const double radial = std::atan2(point.y(), point.x());
        const Vec2 P(std::cos(radial) * angle / (0.5 * fov), std::sin(radial) * angle / (0.5 * fov));
        const double rr = P.squaredNorm();
        const double coefficient = (1 + k1 * rr + k2 * rr * rr + k3 * rr * rr * rr) / (1 + k1 + k2 + k3);
        const Vec2 got = projected(intrinsic_file("equidistant_r3", R"(["0.04", "-0.006", "0.0007"])"));
        CHECK((got - (f * coefficient * P + pp)).norm() < 1e-9);
    }
    SECTION("the 3DE models have no libcam lens: refused in one line") {
        const std::string message = file_error_of([&] {
            read_camera_set(intrinsic_file("3deanamorphic4", R"(["0", "0", "0", "0", "0", "0", "0", "0", "0", "0", "0", "0", "0", "0"])"));
        });
        CHECK(message.find("intrinsics[0].type\": '3deanamorphic4' has no libcam lens") != std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
    }
}

TEST_CASE("AliceVision: the structure's observations, in pixels, reproject through a view's pose", "[alicevision]") {
    test::TempDir dir;
    // Two views of the sample camera without distortion (pinhole), one without a pose; a
    // landmark seen by both. The observation in view 0 is its projection worked out here.
    const Mat3 R = rotation_from_rvec(Vec3(-1, -1, -1));
    const Vec3 X(0.5, -0.25, 3.0);
    const Vec3 x = R * (X - Vec3(-1, -1, -1));
    const Vec2 pixel(1000 * x.x() / x.z() + 2020, 2000 * x.y() / x.z() + 1040);
    const std::string text =
        R"({"version": ["1", "2", "6"], "views": [{"viewId": "0", "poseId": "0", "intrinsicId": "1", "path": "a.jpg", )"
        R"("width": "4092", "height": "2048"}, {"viewId": "9", "poseId": "9", "intrinsicId": "1", "path": "b.jpg"}], )"
        R"("intrinsics": [{"intrinsicId": "1", "width": "4092", "height": "2048", "sensorWidth": "36", "type": "pinhole", )"
        R"("focalLength": "8.7976539589442808", "pixelRatio": "2", "principalPoint": ["-26", "16"], "distortionParams": ""}], )" +
        kSamplePose + R"(, "structure": [{"landmarkId": "42", "descType": "sift", "color": ["1", "2", "3"], )"
        R"("X": ["0.5", "-0.25", "3"], "observations": [{"observationId": "0", "featureId": "5", "x": [")" +
        format_number(pixel.x()) + R"(", ")" + format_number(pixel.y()) +
        R"("], "scale": "2"}, {"observationId": "9", "featureId": "1", "x": ["1", "2"]}]}]}
)";
    const std::filesystem::path file = write_file(dir, "cameras.sfm", text);
    const ObservationSet set = read_observations(file);
    CHECK(set.tool == ObservationTool::AliceVision);
    REQUIRE(set.views.size() == 1);  // view 9 has no pose
    CHECK(set.views[0].name == "a.jpg");
    REQUIRE(set.points.size() == 1);
    CHECK(set.point_ids == std::vector<std::int64_t>{42});
    REQUIRE(set.observations.size() == 1);
    CHECK(set.observations[0].pixel == pixel);
    const Camera camera = [&] {
        Camera c = set.cameras[0].camera;
        c.pose = set.views[0].pose;
        return c;
    }();
    CHECK((PreparedCamera(camera).project(X).pixel - pixel).norm() < 1e-9);
}

TEST_CASE("AliceVision: malformed files are refused in one line naming the field", "[alicevision]") {
    test::TempDir dir;
    const auto message_of = [&](const std::string& text) {
        return file_error_of([&] { read_camera_set(write_file(dir, "bad.sfm", text), CameraFormat::AliceVision); });
    };
    const std::string good_intrinsic =
        R"("intrinsicId": "1", "width": "640", "height": "480", "type": "pinhole", "focalLength": "20", "principalPoint": ["0", "0"])";
    CHECK(message_of(R"({"version": ["1", "2", "12"], "intrinsics": [{)" + good_intrinsic + "}]}") ==
          dir.path().string() + "/bad.sfm: \"version\": 1.2.12 is newer than the newest libcam reads (1.2.11)");
    CHECK(message_of(R"({"version": ["1", "2", "6"], "intrinsics": [{"intrinsicId": "1", "width": "six hundred", "height": "480"}]})") ==
          dir.path().string() + "/bad.sfm: \"intrinsics[0].width\": expected a number, got 'six hundred'");
    CHECK(message_of(R"({"version": ["1", "2", "6"], "intrinsics": [{)" + good_intrinsic + R"(, "sensorWidth": "0"}]})") ==
          dir.path().string() + "/bad.sfm: \"intrinsics[0].sensorWidth\": must be positive, got 0");
    CHECK(message_of(R"({"version": ["1", "2", "6"], "intrinsics": [{)" + good_intrinsic +
                     R"(}], "views": [{"viewId": "1", "poseId": "1", "intrinsicId": "1", "path": "a"}], )"
                     R"("poses": [{"poseId": "1", "pose": {"transform": {"rotation": ["1", "0", "0"], "center": ["0", "0", "0"]}}}]})") ==
          dir.path().string() + "/bad.sfm: \"poses[0].pose.transform.rotation\": expected 9 numbers, got a list of 3");
}

TEST_CASE("AliceVision: written as Meshroom's cameras.sfm, read back the same", "[alicevision]") {
    test::TempDir dir;
    Camera camera;
    camera.size = {4092, 2048};
    camera.intrinsics = {1000.0, 2000.0, 2020.0, 1040.0, 0.0};
    camera.lens = {LensType::OpenCv5, {0.1, 0.05, 0.002, -0.003, -0.001}};
    camera.pose = Pose::from_centre(rotation_from_rvec(Vec3(-1, -1, -1)), Vec3(-1, -1, -1));
    WriteOptions options;
    options.image_name = "images/a.jpg";
    const std::filesystem::path file = dir.path() / "cameras.sfm";
    write_camera_file(file, camera, CameraFormat::AliceVision, options);
    const CameraSet set = read_camera_set(file);
    REQUIRE(set.cameras.size() == 1);
    CHECK(set.cameras[0].name == "images/a.jpg");
    const Camera& back = set.cameras[0].file.camera;
    CHECK(back.size == camera.size);
    CHECK((back.intrinsics.K() - camera.intrinsics.K()).cwiseAbs().maxCoeff() < 1e-12);
    CHECK(back.lens.coefficients == camera.lens.coefficients);
    CHECK((back.pose.R - camera.pose.R).cwiseAbs().maxCoeff() < 1e-15);
    CHECK((back.pose.t - camera.pose.t).cwiseAbs().maxCoeff() < 1e-14);

    // The layout AliceVision's saveIntrinsic and savePose3 write: every value a string,
    // the model by 1.2.6's name, brown's k1 k2 k3 t1 t2, and the sample scene's rotation
    // in the order its own scene_v1.2.6.json holds it.
    std::ifstream in(file);
    const nlohmann::json written = nlohmann::json::parse(in);
    CHECK(written["version"] == nlohmann::json({"1", "2", "6"}));
    const auto& intrinsic = written["intrinsics"][0];
    CHECK(intrinsic["type"] == "brown");
    CHECK(intrinsic["distortionParams"] == nlohmann::json({"0.1", "0.05", "-0.001", "0.002", "-0.003"}));
    CHECK(intrinsic["principalPoint"] == nlohmann::json({"-26", "16"}));
    for (const char* key : {"serialNumber", "initialFocalLength", "pixelRatioLocked", "sensorWidth", "sensorHeight"}) {
        CHECK(intrinsic.contains(key));
    }
    const auto& rotation = written["poses"][0]["pose"]["transform"]["rotation"];
    const double file_order[] = {0.22629564095020641, -0.18300791965761709, 0.95671227870741093,
                                 0.95671227870741093, 0.22629564095020641,  -0.18300791965761709,
                                 -0.18300791965761709, 0.95671227870741093, 0.22629564095020641};
    for (std::size_t i = 0; i < 9; ++i) CHECK(std::stod(rotation[i].get<std::string>()) == Approx(file_order[i]).margin(1e-15));
    CHECK(written["views"][0]["poseId"] == written["poses"][0]["poseId"]);

    // What it cannot hold: one line, nothing written.
    camera.intrinsics.skew = 2.0;
    CHECK_THROWS_AS(write_camera_file(dir.path() / "skewed.sfm", camera, CameraFormat::AliceVision), NotRepresentable);
    CHECK_FALSE(std::filesystem::exists(dir.path() / "skewed.sfm"));
}

TEST_CASE("AliceVision: a rig's view is its sub-pose after the rig's pose, and older and newer keys", "[alicevision]") {
    test::TempDir dir;
    // The rig (pose 5) at the identity rotation, centre (0, 0, -5): t = (0, 0, 5). The
    // sub-pose at the identity, centre (1, 0, 0): t = (-1, 0, 0). Pose3's product
    // sub * rig: R = I, t = (0, 0, 5) + (-1, 0, 0), so the camera's centre is (1, 0, -5).
    const std::string identity = R"(["1", "0", "0", "0", "1", "0", "0", "0", "1"])";
    const std::string text =
        R"({"version": ["1", "2", "6"], "views": [{"viewId": "1", "poseId": "5", "intrinsicId": "1", "rigId": "3", )"
        R"("subPoseId": "0", "isPoseIndependant": "false", "path": "rig.jpg"}], "intrinsics": [{"intrinsicId": "1", )"
        R"("width": "640", "height": "480", "type": "pinhole", "focalLength": "18", "principalPoint": ["0", "0"]}], )"
        R"("poses": [{"poseId": "5", "pose": {"transform": {"rotation": )" + identity +
        R"(, "center": ["0", "0", "-5"]}}}], "rigs": [{"rigId": "3", "subPoses": [{"status": "constant", "pose": )"
        R"({"rotation": )" + identity + R"(, "center": ["1", "0", "0"]}}]}]})";
    const Camera camera = read_camera_set(write_file(dir, "rig.sfm", text)).cameras.at(0).file.camera;
    CHECK(camera.pose.R == Mat3::Identity());
    CHECK(camera.pose.t == Vec3(-1, 0, 5));
    CHECK(camera.intrinsics.fx == 18 * 640 / 36.0);  // sensorWidth's default, 36 mm

    // Before 1.2.0: one pxFocalLength and the principal point itself.
    const std::string v100 =
        R"({"version": ["1", "0", "0"], "intrinsics": [{"intrinsicId": "2", "width": "640", "height": "480", )"
        R"("type": "radial1", "pxFocalLength": "700", "principalPoint": ["330", "250"], "distortionParams": ["-0.1"]}]})";
    const Camera old = read_camera_set(write_file(dir, "v100.sfm", v100)).cameras.at(0).file.camera;
    CHECK(old.intrinsics.fx == 700);
    CHECK(old.intrinsics.fy == 700);
    CHECK(old.intrinsics.cx == 330);
    CHECK(old.intrinsics.cy == 250);
    CHECK(old.lens == Lens{LensType::OpenCv4, {-0.1, 0.0, 0.0, 0.0}});

    // 1.2.8 on: an undistortion map (the 3DE models' place) has no libcam lens.
    const std::string undistorted =
        R"({"version": ["1", "2", "9"], "intrinsics": [{"intrinsicId": "2", "width": "640", "height": "480", )"
        R"("type": "pinhole", "focalLength": "18", "principalPoint": ["0", "0"], "distortionType": "none", )"
        R"("undistortionType": "3declassicld"}]})";
    const auto path = write_file(dir, "undistorted.sfm", undistorted);
    CHECK(file_error_of([&] { read_camera_set(path); }) ==
          path.string() + ": \"intrinsics[0].undistortionType\": '3declassicld' has no libcam lens (an undistortion "
                          "map: libcam reads intrinsics whose undistortionType is none)");
}

TEST_CASE("AliceVision: a view is found by its image's file name alone, unless two views share it",
          "[alicevision]") {
    test::TempDir dir;
    // Three views of the sample scene's intrinsic, their paths as Meshroom on Windows writes
    // them; only view 0 has a pose (AliceVision lists the localised views' poses alone).
    std::string text = sample_file("\"1\", \"2\", \"5\"",
        R"("type": "radial3", "initialFocalLength": "-1", "focalLength": "8.7976539589442808", "pixelRatio": "2", )"
        R"("pixelRatioLocked": "true", "principalPoint": ["-26", "16"])");
    const std::string views =
        R"("views": [{"viewId": "0", "poseId": "0", "intrinsicId": "1", "path": "D:/photos/day1/IMG_1.jpg", )"
        R"("width": "4092", "height": "2048", "metadata": ""}, )"
        R"({"viewId": "1", "poseId": "1", "intrinsicId": "1", "path": "D:/photos/day2/IMG_1.jpg", )"
        R"("width": "4092", "height": "2048", "metadata": ""}, )"
        R"({"viewId": "2", "poseId": "2", "intrinsicId": "1", "path": "D:\\photos\\day2\\IMG_2.jpg", )"
        R"("width": "4092", "height": "2048", "metadata": ""}])";
    text.replace(text.find(kSampleView), kSampleView.size(), views);
    const std::filesystem::path file = write_file(dir, "cameras.sfm", text);
    const CameraSet set = read_camera_set(file);
    REQUIRE(set.cameras.size() == 3);
    check_sample_camera(set.cameras[0].file.camera);
    CHECK_FALSE(set.cameras[0].unposed);
    CHECK(set.cameras[1].unposed);
    CHECK(set.cameras[2].unposed);
    CHECK(set.cameras[2].file.camera.intrinsics.K() == set.cameras[0].file.camera.intrinsics.K());
    // A backslashed Windows path's file name, and the whole path.
    CHECK(&select_camera(set, "IMG_2.jpg", file.string()) == &set.cameras[2]);
    CHECK(&select_camera(set, "D:/photos/day2/IMG_1.jpg", file.string()) == &set.cameras[1]);
    // Two views' images are IMG_1.jpg: the error names both.
    try {
        select_camera(set, "IMG_1.jpg", file.string());
        FAIL("IMG_1.jpg names two views");
    } catch (const InvalidArgument& error) {
        CHECK(std::string(error.what()) == file.string() + ": the image file name 'IMG_1.jpg' names 2 cameras: "
                                                           "0 (D:/photos/day1/IMG_1.jpg), 1 (D:/photos/day2/IMG_1.jpg); "
                                                           "give one's whole name or its position");
    }
    // A file name no view has: every camera listed.
    CHECK_THROWS_WITH(select_camera(set, "IMG_3.jpg", file.string()), Catch::Contains("no camera 'IMG_3.jpg'"));
}
