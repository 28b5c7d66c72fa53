// OpenSfM's reconstruction.json with tracks.csv, and OpenMVG's sfm_data.json: cameras and
// observations, on hand-made files whose pixels are worked out by hand from each tool's
// formulas, and on the real files of the folder of real data beside the source tree (its SOURCES.md, section 5, gives the
// expected numbers, recomputed there independently of libcam).

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <string>

#include "../real_cameras.hpp"
#include "../temp_dir.hpp"
#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"

namespace {

using namespace libcam;
namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

std::string error_of(const fs::path& path) {
    try {
        read_observations(path);
    } catch (const FileError& error) {
        return error.what();
    }
    return "no error";
}

std::string camera_error_of(const fs::path& path) {
    try {
        read_camera_set(path);
    } catch (const FileError& error) {
        return error.what();
    }
    return "no error";
}

// One 640x480 perspective camera (focal 0.5: 320 px) with k1 = 0.1, at the origin looking
// down +Z, and the point (0.2, -0.1, 2): at (0.1, -0.05) on the image plane, r^2 =
// 0.0125, distortion 1 + 0.1 r^2 = 1.00125, so OpenSfM's normalized point is 0.5 *
// 1.00125 * (0.1, -0.05) = (0.0500625, -0.02503125): libcam's pixel is that times 640
// plus ((640 - 1) / 2, (480 - 1) / 2) = (351.54, 223.48).
std::string opensfm_reconstruction(const std::string& projection_type = "perspective") {
    return R"([{"cameras": {"cam": {"projection_type": ")" + projection_type +
           R"(", "width": 640, "height": 480, "focal": 0.5, "k1": 0.1, "k2": 0.0}},
  "shots": {"a.jpg": {"camera": "cam", "rotation": [0, 0, 0], "translation": [0, 0, 0]}},
  "points": {"7": {"coordinates": [0.2, -0.1, 2.0], "color": [1, 2, 3]}}}])";
}

constexpr const char* kTracks =
    "OPENSFM_TRACKS_VERSION_v1\n"
    "a.jpg\t7\t3\t0.0500625\t-0.02503125\t0.002\t10\t20\t30\n"
    "b.jpg\t7\t4\t0.1\t0.1\t0.002\t10\t20\t30\n"   // a shot no reconstruction holds
    "a.jpg\t8\t5\t0.2\t0.2\t0.002\t10\t20\t30\n";  // a track that is not a point

// An sfm_data.json with two pinhole_radial_k3 intrinsics (the second names its type by
// id alone, as cereal writes a type's later objects) and one pinhole_brown_t2, three
// views at the origin, and the point (0.2, -0.1, 2) seen by each. f = 1000, pp = (800, 600):
//  radial k1 = 0.1: 1000 * 1.00125 * (0.1, -0.05) + pp = (900.125, 549.9375);
//  brown t1 = 0.01: t = (2 t1 x y, t1 (r^2 + 2 y^2)) = (-1e-4, 1.75e-4): (899.9, 550.175).
std::string openmvg_sfm_data(const std::string& brown_type = "pinhole_brown_t2") {
    const auto view = [](int id, int intrinsic) {
        return R"({"key": )" + std::to_string(id) + R"(, "value": {"polymorphic_id": 1073741824, "ptr_wrapper": {"id": )" +
               std::to_string(2147483649 + id) + R"(, "data": {"local_path": "", "filename": "v)" + std::to_string(id) +
               R"(.jpg", "width": 1600, "height": 1200, "id_view": )" + std::to_string(id) +
               R"(, "id_intrinsic": )" + std::to_string(intrinsic) + R"(, "id_pose": )" + std::to_string(id) + "}}}}";
    };
    const auto pose = [](int id) {
        return R"({"key": )" + std::to_string(id) +
               R"(, "value": {"rotation": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "center": [0, 0, 0]}})";
    };
    return R"({"sfm_data_version": "0.3", "root_path": "/x",
  "views": [)" + view(0, 0) + ", " + view(1, 1) + ", " + view(2, 2) + R"(],
  "intrinsics": [
    {"key": 0, "value": {"polymorphic_id": 2147483649, "polymorphic_name": "pinhole_radial_k3", "ptr_wrapper": {"id": 2147483652,
      "data": {"width": 1600, "height": 1200, "focal_length": 1000, "principal_point": [800, 600], "disto_k3": [0.1, 0, 0]}}}},
    {"key": 1, "value": {"polymorphic_id": 1, "ptr_wrapper": {"id": 2147483653,
      "data": {"width": 1600, "height": 1200, "focal_length": 1000, "principal_point": [800, 600], "disto_k3": [0.1, 0, 0]}}}},
    {"key": 2, "value": {"polymorphic_id": 2147483650, "polymorphic_name": ")" + brown_type + R"(", "ptr_wrapper": {"id": 2147483654,
      "data": {"width": 1600, "height": 1200, "focal_length": 1000, "principal_point": [800, 600], "disto_t2": [0, 0, 0, 0.01, 0]}}}}],
  "extrinsics": [)" + pose(0) + ", " + pose(1) + ", " + pose(2) + R"(],
  "structure": [{"key": 5, "value": {"X": [0.2, -0.1, 2.0], "observations": [
    {"key": 0, "value": {"id_feat": 1, "x": [900.125, 549.9375]}},
    {"key": 1, "value": {"id_feat": 2, "x": [900.125, 549.9375]}},
    {"key": 2, "value": {"id_feat": 3, "x": [899.9, 550.175]}}]}}],
  "control_points": []})";
}

}  // namespace

TEST_CASE("OpenSfM: a hand-made reconstruction with its tracks reprojects to the pixel worked by hand") {
    test::TempDir dir;
    write(dir / "reconstruction.json", opensfm_reconstruction());
    write(dir / "tracks.csv", kTracks);
    const ObservationSet set = read_observations(dir / "reconstruction.json");
    CHECK(set.tool == ObservationTool::OpenSfm);
    CHECK(set.pixel_offset == Vec2(0.5, 0.5));
    REQUIRE(set.cameras.size() == 1);
    CHECK(set.cameras[0].camera.intrinsics.fx == 320.0);
    CHECK(set.cameras[0].camera.intrinsics.cx == 319.5);
    CHECK(set.cameras[0].camera.lens.type == LensType::OpenCv4);
    REQUIRE(set.views.size() == 1);
    CHECK(set.views[0].name == "a.jpg");
    REQUIRE(set.points.size() == 1);
    CHECK(set.point_ids[0] == 7);
    REQUIRE(set.observations.size() == 1);  // the other two rows are not of this reconstruction
    CHECK(set.observations[0].pixel.x() == Approx(0.0500625 * 640 + 319.5).epsilon(1e-14));
    CHECK(set.observations[0].pixel.y() == Approx(-0.02503125 * 640 + 239.5).epsilon(1e-14));
    const Reprojection r = reproject(set);
    CHECK(r.residuals[0].error_px < 1e-9);

    // The same file read as cameras: one per shot, with its pose and its camera's id.
    const CameraSet cameras = read_camera_set(dir / "reconstruction.json");
    CHECK(cameras.format == CameraFormat::OpenSfm);
    REQUIRE(cameras.cameras.size() == 1);
    CHECK(cameras.cameras[0].name == "a.jpg");
    CHECK(cameras.cameras[0].intrinsics_name == "cam");
}

TEST_CASE("OpenSfM: what libcam cannot hold, and malformed files, give one line naming the field") {
    test::TempDir dir;
    write(dir / "reconstruction.json", opensfm_reconstruction("fisheye62"));
    CHECK_THAT(camera_error_of(dir / "reconstruction.json"),
               Catch::Contains("\"[0].cameras.cam.projection_type\": 'fisheye62' is refused"));
    write(dir / "reconstruction.json", opensfm_reconstruction("pinhole"));
    CHECK_THAT(camera_error_of(dir / "reconstruction.json"), Catch::Contains("unknown projection type 'pinhole'"));

    write(dir / "reconstruction.json", opensfm_reconstruction());
    CHECK_THAT(error_of(dir / "reconstruction.json"), Catch::Contains("no tracks.csv beside it"));
    write(dir / "tracks.csv", "OPENSFM_TRACKS_VERSION_v1\na.jpg\t7\t3\tabc\t0.1\t0.002\t1\t2\t3\n");
    CHECK_THAT(error_of(dir / "reconstruction.json"), Catch::Contains("tracks.csv: line 2: x: 'abc' is not a finite number"));
    write(dir / "tracks.csv", "OPENSFM_TRACKS_VERSION_v1\na.jpg\t7\t3\n");
    CHECK_THAT(error_of(dir / "reconstruction.json"), Catch::Contains("tracks.csv: line 2: expected shot, track"));
    write(dir / "tracks.csv", "OPENSFM_TRACKS_VERSION_v9\n");
    CHECK_THAT(error_of(dir / "reconstruction.json"), Catch::Contains("unknown tracks version"));

    write(dir / "reconstruction.json",
          R"([{"cameras": {}, "shots": {"a.jpg": {"camera": "nobody", "rotation": [0, 0, 0], "translation": [0, 0, 0]}}}])");
    CHECK_THAT(camera_error_of(dir / "reconstruction.json"),
               Catch::Contains("\"[0].shots.a.jpg.camera\": 'nobody' is not one of the cameras"));
    write(dir / "reconstruction.json",
          R"([{"cameras": {"c": {"projection_type": "perspective", "width": 0, "height": 4, "focal": 1, "k1": 0, "k2": 0}}}])");
    CHECK_THAT(camera_error_of(dir / "reconstruction.json"), Catch::Contains("width"));
}

TEST_CASE("OpenMVG: a hand-made sfm_data.json reprojects to the pixels worked by hand") {
    test::TempDir dir;
    write(dir / "sfm_data.json", openmvg_sfm_data());
    const ObservationSet set = read_observations(dir / "sfm_data.json");
    CHECK(set.tool == ObservationTool::OpenMvg);
    CHECK(set.pixel_offset == Vec2::Zero());
    REQUIRE(set.cameras.size() == 3);
    CHECK(set.cameras[1].camera.lens == Lens{LensType::OpenCv4, {0.1, 0.0, 0.0, 0.0}});
    // p1 = t1 = 0.01; k3 = 0, so the simplest model holding it is OPENCV4.
    CHECK(set.cameras[2].camera.lens == Lens{LensType::OpenCv4, {0.0, 0.0, 0.01, 0.0}});
    CHECK(set.cameras[0].camera.intrinsics.cx == 800.0);  // OpenMVG's pixel centres are OpenCV's
    REQUIRE(set.views.size() == 3);
    REQUIRE(set.observations.size() == 3);
    CHECK(set.point_ids == std::vector<std::int64_t>{5});
    const Reprojection r = reproject(set);
    for (const ObservationResidual& residual : r.residuals) CHECK(residual.error_px < 1e-9);

    const CameraSet cameras = read_camera_set(dir / "sfm_data.json");
    CHECK(cameras.format == CameraFormat::OpenMvg);
    REQUIRE(cameras.cameras.size() == 3);
    CHECK(cameras.cameras[2].name == "v2.jpg");
    CHECK(cameras.cameras[2].intrinsics_name == "id:2");
}

TEST_CASE("OpenMVG: before SfM every view is a camera with its intrinsic, said to be unposed") {
    test::TempDir dir;
    // As openMVG_main_SfMInit_ImageListing writes it: views and intrinsics, no poses and no
    // structure (here their keys renamed away).
    std::string text = openmvg_sfm_data();
    text.replace(text.find("\"extrinsics\""), 12, "\"no_extrinsics\"");
    text.replace(text.find("\"structure\""), 11, "\"no_structure\"");
    write(dir / "sfm_data.json", text);
    const CameraSet set = read_camera_set(dir / "sfm_data.json");
    REQUIRE(set.cameras.size() == 3);
    for (std::size_t i = 0; i < 3; ++i) {
        const NamedCamera& view = set.cameras[i];
        CHECK(view.name == "v" + std::to_string(i) + ".jpg");
        CHECK(view.intrinsics_name == "id:" + std::to_string(i));
        CHECK(view.unposed);
        CHECK(view.file.camera.pose.R == Mat3::Identity());
        CHECK(view.file.camera.intrinsics.fx == 1000.0);  // each intrinsic's focal_length
    }
    // Intrinsic 2 is pinhole_brown_t2 with t1 = 0.01: OpenCV's p1.
    CHECK(set.cameras[2].file.camera.lens == Lens{LensType::OpenCv4, {0.0, 0.0, 0.01, 0.0}});
    CHECK(&select_camera(set, "v1.jpg", "sfm_data.json") == &set.cameras[1]);

    // A view SfM did not localise (its id_pose not among the extrinsics): the posed views
    // first, then it, unposed.
    text = openmvg_sfm_data();
    const std::string pose_1 = R"({"key": 1, "value": {"rotation")";
    text.replace(text.find(pose_1), pose_1.size(), R"({"key": 7, "value": {"rotation")");
    write(dir / "sfm_data.json", text);
    const CameraSet partial = read_camera_set(dir / "sfm_data.json");
    REQUIRE(partial.cameras.size() == 3);
    CHECK(partial.cameras[0].name == "v0.jpg");
    CHECK(partial.cameras[1].name == "v2.jpg");
    CHECK(partial.cameras[2].name == "v1.jpg");
    CHECK_FALSE(partial.cameras[1].unposed);
    CHECK(partial.cameras[2].unposed);
}

TEST_CASE("OpenMVG: what libcam cannot hold, and malformed files, give one line naming the field") {
    test::TempDir dir;
    write(dir / "sfm_data.json", openmvg_sfm_data("pinhole_radial_k9"));
    CHECK_THAT(camera_error_of(dir / "sfm_data.json"),
               Catch::Contains("\"intrinsics[2].value.polymorphic_name\": 'pinhole_radial_k9' is refused"));
    std::string text = openmvg_sfm_data();
    text.replace(text.find("\"disto_t2\": [0, 0, 0, 0.01, 0]"), 30, "\"disto_t2\": [0, 0, 0, 0.01]   ");
    write(dir / "sfm_data.json", text);
    CHECK_THAT(camera_error_of(dir / "sfm_data.json"), Catch::Contains("disto_t2\": expected 5 numbers"));
    text = openmvg_sfm_data();
    text.replace(text.find("{\"key\": 2, \"value\": {\"id_feat\""), 9, "{\"key\": 9");
    write(dir / "sfm_data.json", text);
    CHECK_THAT(error_of(dir / "sfm_data.json"), Catch::Contains("view 9 is not one of the views"));
    text = openmvg_sfm_data();
    text.replace(text.find("[[1, 0, 0]"), 10, "[[2, 0, 0]");
    write(dir / "sfm_data.json", text);
    CHECK_THAT(camera_error_of(dir / "sfm_data.json"), Catch::Contains("extrinsics[0].value"));
}

TEST_CASE("OpenSfM berlin: 3771 observations reproject as SOURCES.md recomputed them", "[real-data]") {
    const fs::path file = test::real_data_path("kapture-samples/berlin/opensfm/reconstruction.json");
    if (!test::real_data_present(file)) return;
    const ObservationSet set = read_observations(file);
    CHECK(set.views.size() == 3);
    CHECK(set.points.size() == 1702);
    CHECK(set.observations.size() == 3771);
    const Reprojection r = reproject(set);
    const ResidualStats& all = r.summary.all;
    CHECK(all.stats.count == 3771);
    // SOURCES.md: mean 5.43e-4 normalized = 1.77 px at 3264 px, median 1.23, max 32.9.
    CHECK(all.mean_px == Approx(1.77).margin(0.005));
    CHECK(all.stats.median_px == Approx(1.23).margin(0.005));
    CHECK(all.stats.max_px == Approx(32.9).margin(0.05));
    CHECK(set.cameras[0].camera.intrinsics.fx == Approx(0.9642521761171555 * 3264).epsilon(1e-15));
}

TEST_CASE("OpenSfM: the older reconstruction without tracks, and ODM's camera dictionary, as cameras", "[real-data]") {
    const fs::path old_file = test::real_data_path("opensfm-fuenwang-PBA/reconstruction.json");
    if (test::real_data_present(old_file)) {
        const CameraSet set = read_camera_set(old_file);
        CHECK(set.format == CameraFormat::OpenSfm);
        CHECK(set.cameras.size() == 3);
        CHECK(set.cameras[0].file.camera.lens == Lens{LensType::OpenCv4, {0.011384880517832378, -0.0009015795437962037, 0.0, 0.0}});
        CHECK_THAT(error_of(old_file), Catch::Contains("no tracks.csv beside it"));
    }
    const fs::path odm = test::real_data_path("opensfm-odm-JNotelddim/cameras.json");
    if (test::real_data_present(odm)) {
        const CameraSet set = read_camera_set(odm);
        CHECK(set.format == CameraFormat::OpenSfm);
        REQUIRE(set.cameras.size() == 1);
        const Camera& camera = set.cameras[0].file.camera;
        // SOURCES.md, in OpenSfM's pixels (libcam's + 0.5): fx = fy = 4090.88, cx 2919.40, cy 2131.30.
        CHECK(camera.intrinsics.fx == Approx(4090.88).margin(0.005));
        CHECK(camera.intrinsics.fy == Approx(4090.88).margin(0.005));
        CHECK(camera.intrinsics.cx + 0.5 == Approx(2919.40).margin(0.005));
        CHECK(camera.intrinsics.cy + 0.5 == Approx(2131.30).margin(0.005));
        CHECK(camera.lens.type == LensType::OpenCv5);
        CHECK(camera.lens.coefficients[2] == -0.002428876236594572);  // p1
        CHECK(camera.lens.coefficients[4] == -0.01149588104588635);   // k3
        CHECK_THAT(error_of(odm), Catch::Contains("cameras alone"));
    }
    const fs::path models = test::real_data_path("kapture-samples/berlin/opensfm/camera_models.json");
    if (test::real_data_present(models)) {
        const CameraSet set = read_camera_set(models);
        REQUIRE(set.cameras.size() == 1);
        CHECK(set.cameras[0].file.camera.lens.type == LensType::Pinhole);  // k1 = k2 = 0
    }
}

TEST_CASE("OpenMVG maupertuis: 1228 observations reproject as SOURCES.md recomputed them", "[real-data]") {
    const fs::path file =
        test::real_data_path("kapture-samples/maupertuis_openMVG/ChateauMaupertuisTest/reconstruction_global/sfm_data.json");
    if (!test::real_data_present(file)) return;
    const ObservationSet set = read_observations(file);
    CHECK(set.views.size() == 4);
    CHECK(set.points.size() == 365);
    CHECK(set.observations.size() == 1228);
    const Reprojection r = reproject(set);
    const ResidualStats& all = r.summary.all;
    CHECK(all.stats.count == 1228);
    // SOURCES.md: mean 0.470 px, median 0.317, max 3.183, RMS of the residual components 0.4756.
    CHECK(all.mean_px == Approx(0.470).margin(0.0005));
    CHECK(all.stats.median_px == Approx(0.317).margin(0.002));
    CHECK(all.stats.max_px == Approx(3.183).margin(0.0005));
    CHECK(all.stats.rms_px / std::sqrt(2.0) == Approx(0.4756).margin(0.00005));
    const Camera& camera = set.cameras[0].camera;
    CHECK(camera.intrinsics.fx == 1668.7938300915464);
    CHECK(camera.intrinsics.cx == 827.2989627028306);
    CHECK(camera.lens == Lens{LensType::OpenCv5, {-0.15063858971626434, 0.19775746608000222, 0.0, 0.0, 0.012089634954989254}});
}

TEST_CASE("OpenMVG: the views before SfM, and the nested serialization of a fisheye", "[real-data]") {
    const fs::path matches =
        test::real_data_path("kapture-samples/maupertuis_openMVG/ChateauMaupertuisTest/matches/sfm_data.json");
    if (test::real_data_present(matches)) {
        const CameraSet set = read_camera_set(matches);
        CHECK(set.format == CameraFormat::OpenMvg);
        // Its 4 views (MaupertuisTest_01.jpg ... _04.jpg), each with intrinsic 0 (1600x1200,
        // focal_length 1615.5989389233603, principal point (800, 600)), none posed.
        REQUIRE(set.cameras.size() == 4);
        for (std::size_t i = 0; i < 4; ++i) {
            CHECK(set.cameras[i].name == "MaupertuisTest_0" + std::to_string(i + 1) + ".jpg");
            CHECK(set.cameras[i].intrinsics_name == "id:0");
            CHECK(set.cameras[i].unposed);
            CHECK(set.cameras[i].file.camera.intrinsics.fx == 1615.5989389233603);
            CHECK(set.cameras[i].file.camera.intrinsics.cx == 800.0);
            CHECK(set.cameras[i].file.camera.lens.type == LensType::Pinhole);  // k = 0
        }
        CHECK(&select_camera(set, "MaupertuisTest_03.jpg", matches.string()) == &set.cameras[2]);
        CHECK_THAT(error_of(matches), Catch::Contains("no observation"));
    }
    const fs::path t265 = test::real_data_path("kapture-samples/t265/Everest_undistorted/sfm_data_small.json");
    if (test::real_data_present(t265)) {
        const CameraSet set = read_camera_set(t265);
        REQUIRE(set.cameras.size() == 5);
        const Camera& camera = set.cameras[0].file.camera;
        CHECK(camera.size == ImageSize{848, 800});
        CHECK(camera.intrinsics.fx == 288.6195);
        CHECK(camera.intrinsics.cx == 424.0);
        CHECK(camera.lens == Lens{LensType::Fisheye, {0.0, 0.0, 0.0, 0.0}});
    }
}
