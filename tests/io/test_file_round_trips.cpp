// Round trips between every pair of formats that can hold a camera, and COLMAP's own
// program reading what libcam writes (colmap model_converter, text to binary and back).

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "libcam/error.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/camera_formats.hpp"
#include "libcam/lens/lens_model.hpp"
#include "temp_dir.hpp"

using namespace libcam;
namespace fs = std::filesystem;

namespace {

// Every format libcam writes and reads back, from the table of formats, but ROS's
// camera_info, which holds no pose (its round trips are in test_io_formats.cpp), and the
// Blender script, which is Python (its JSON twin is here), and OCamCalib's
// calib_results.txt, which holds no pose and keeps the polynomial in the file's pixels (its
// round trips are in test_ocamcalib.cpp), and DriveWorks' rig.json, which likewise keeps
// the F-theta polynomial in pixels and the pose as roll-pitch-yaw in degrees (its round
// trips are in test_driveworks_rig.cpp).
std::vector<CameraFormat> written_formats() {
    std::vector<CameraFormat> formats;
    for (const CameraFormatInfo& format : camera_formats()) {
        if (format.writes && format.format != CameraFormat::Ros && format.format != CameraFormat::Blender &&
            format.format != CameraFormat::OcamCalib && format.format != CameraFormat::DriveworksRig) {
            formats.push_back(format.format);
        }
    }
    return formats;
}

struct Case {
    const char* what;
    Camera camera;
    std::vector<CameraFormat> holders;  // the formats that can hold it (the others refuse it)
};

Camera camera_with(const Lens& lens, double skew = 0.0) {
    Camera camera;
    camera.size = {1280, 720};
    camera.intrinsics = {1001.123456789012, 987.6543210987654, 700.25, 300.125, skew};
    camera.lens = lens;
    camera.pose = Pose::from_rvec(Vec3(0.3, -2.1, 0.7), Vec3(-12.5, 0.001, 1e4));
    return camera;
}

Camera square_pixels(Camera camera) {
    camera.intrinsics.fy = camera.intrinsics.fx;
    return camera;
}

// WoodScape's fisheye as its files hold it: fx = 1, fy = the aspect ratio.
Camera woodscape_camera() {
    Camera camera = camera_with({LensType::ThetaPolynomial, {339.749, -31.988, 48.275, -7.201}});
    camera.intrinsics.fx = 1.0;
    camera.intrinsics.fy = 1.0625;
    return camera;
}

std::vector<Case> cases() {
    using F = CameraFormat;
    return {
        {"pinhole", camera_with({LensType::Pinhole, {}}),
         {F::Json, F::OpenCvYaml, F::OpenCvXml, F::Cameramodel, F::Gl, F::Colmap, F::Nerf, F::Kalibr, F::Open3d,
          F::Basalt, F::BlenderJson, F::Metashape, F::AliceVision}},
        {"skewed pinhole", camera_with({LensType::Pinhole, {}}, 3.5),
         {F::Json, F::OpenCvYaml, F::OpenCvXml, F::Gl, F::Open3d, F::Metashape}},
        {"OPENCV4", camera_with({LensType::OpenCv4, {-0.2, 0.05, 1e-3, -2e-3}}),
         {F::Json, F::OpenCvYaml, F::OpenCvXml, F::Cameramodel, F::Colmap, F::Nerf, F::Kalibr, F::Basalt,
          F::Metashape, F::AliceVision}},
        {"OPENCV5", camera_with({LensType::OpenCv5, {-0.2, 0.05, 1e-3, -2e-3, 0.01}}),
         {F::Json, F::OpenCvYaml, F::OpenCvXml, F::Cameramodel, F::Colmap, F::Nerf, F::Basalt, F::Metashape,
          F::AliceVision}},
        {"OPENCV8", camera_with({LensType::OpenCv8, {0.4, 0.05, 1e-3, -2e-3, 0.01, 0.7, 0.1, 0.02}}),
         {F::Json, F::OpenCvYaml, F::OpenCvXml, F::Cameramodel, F::Colmap, F::Basalt}},
        {"FISHEYE", camera_with({LensType::Fisheye, {0.01, -0.002, 3e-4, -4e-5}}),
         {F::Json, F::OpenCvYaml, F::OpenCvXml, F::Colmap, F::Nerf, F::Kalibr, F::Basalt, F::Metashape,
          F::AliceVision}},
        {"LONLAT", camera_with({LensType::Lonlat, {}}), {F::Json, F::Cameramodel, F::Nerf, F::BlenderJson}},
        // Metashape's spherical sensor has one focal length (pixels per radian both ways).
        {"LONLAT, fx = fy", square_pixels(camera_with({LensType::Lonlat, {}})),
         {F::Json, F::Cameramodel, F::Nerf, F::BlenderJson, F::Metashape}},
        {"RAD_TAN_THIN_PRISM_FISHEYE",
         camera_with({LensType::RadTanThinPrismFisheye,
                      {0.02, -3e-3, 4e-4, -5e-5, 6e-6, -7e-7, 1.1e-3, -9e-4, 7e-4, -3e-4, -5e-4, 2e-4}}),
         {F::Json, F::Colmap, F::Nerf}},
        {"CYLINDRICAL", camera_with({LensType::Cylindrical, {}}), {F::Json}},
        // PanoTools' a b c, on a pinhole or a fisheye projection: libcam's JSON alone writes
        // them (lensfun, Hugin and Gyroflow are read only).
        {"PTLENS", camera_with({LensType::Ptlens, {-0.25, 0.2, -0.13}}), {F::Json}},
        {"EQUIDISTANT_RADIAL", camera_with({LensType::EquidistantRadial, {-0.002, -0.015, -0.06, 0.0}}), {F::Json}},
        {"EQUISOLID_RADIAL", camera_with({LensType::EquisolidRadial, {-0.074, 0.21, -0.12, 0.0}}), {F::Json}},
        {"STEREOGRAPHIC_RADIAL", camera_with({LensType::StereographicRadial, {0.021, -0.081, 0.014, 0.003}}), {F::Json}},
        // Brown's lens to r^8: Metashape's frame sensor and nerfstudio's k4 hold it (RealityCapture's
        // files are read only).
        {"BROWN_K4", camera_with({LensType::BrownK4, {-0.2, 0.05, 1e-3, -2e-3, 0.01, -0.002}}),
         {F::Json, F::Metashape, F::Nerf}},
        {"MEI", camera_with({LensType::Mei, {1.1, -0.1, 0.01, 1e-3, -1e-3}}), {F::Json, F::Kalibr}},
        {"DOUBLE_SPHERE", camera_with({LensType::DoubleSphere, {-0.24, 0.57}}), {F::Json, F::Kalibr, F::Basalt}},
        {"EUCM", camera_with({LensType::Eucm, {0.59, 1.1}}), {F::Json, F::Colmap, F::Kalibr, F::Basalt}},
        {"FOV", camera_with({LensType::Fov, {0.92}}), {F::Json, F::Colmap, F::Kalibr, F::Basalt, F::AliceVision}},
        {"OCAMCALIB", camera_with({LensType::OcamCalib, {1.001, 0.002, -0.003, 0.0, -0.45, 0.02, -0.003, 0.0}}),
         {F::Json}},
        // COLMAP's DIVISION (and SIMPLE_DIVISION, read).
        {"DIVISION", camera_with({LensType::Division, {-0.08}}), {F::Json, F::Colmap}},
        // WoodScape's coefficients are in pixels: its files hold fx = 1 (the writer scales
        // them by fx, so another fx comes back as 1 with the coefficients scaled).
        {"THETA_POLYNOMIAL", woodscape_camera(), {F::Json, F::Woodscape}},
        // NVIDIA's F-theta, either polynomial the reference (DriveWorks' rig.json, which
        // holds both, is read back in test_driveworks_rig.cpp).
        {"FTHETA", camera_with({LensType::FTheta, {1.0004, 0.0002, -0.0001, 1.0, 8e-3, 0.012, 1.4e-3, 0.0, 1.4}}),
         {F::Json}},
        {"FTHETA_FORWARD",
         camera_with({LensType::FThetaForward, {1.0002, 0.0001, -0.0003, 1.0, -0.0125, -0.033, 0.005, 0.0, 1.4}}),
         {F::Json}},
    };
}

// Where a format's file (or folder) goes: named after the format, with its first ending.
fs::path place(const fs::path& dir, const std::string& stem, CameraFormat format) {
    const CameraFormatInfo info = camera_formats()[static_cast<std::size_t>(format)];
    const std::string ending = info.extensions.empty() ? "" : std::string(info.extensions.front());
    return dir / (stem + "-" + std::string(info.name) + ending);
}

bool holds(const Case& c, CameraFormat format) {
    return std::find(c.holders.begin(), c.holders.end(), format) != c.holders.end();
}

// The same camera: K and the pose to `tolerance` (COLMAP's and NeRF's pixel corner adds
// and takes 0.5; COLMAP's quaternion; gl's matrices), the same model or one that nests it
// (COLMAP's FULL_OPENCV holds OPENCV5 with k4 = k5 = k6 = 0) with the same coefficients.
void check_same(const Camera& got, const Camera& expected, double tolerance) {
    CHECK(got.size == expected.size);
    CHECK((got.intrinsics.K() - expected.intrinsics.K()).cwiseAbs().maxCoeff() <=
          tolerance * expected.intrinsics.K().cwiseAbs().maxCoeff());
    CHECK((got.pose.R - expected.pose.R).cwiseAbs().maxCoeff() <= tolerance);
    CHECK((got.pose.t - expected.pose.t).cwiseAbs().maxCoeff() <= tolerance * expected.pose.t.cwiseAbs().maxCoeff());
    const LensInfo& a = lens_info(got.lens.type);
    const LensInfo& b = lens_info(expected.lens.type);
    CHECK(a.family == b.family);
    std::vector<double> padded = expected.lens.coefficients;
    padded.resize(got.lens.coefficients.size(), 0.0);
    CHECK(got.lens.coefficients == padded);
}

}  // namespace

TEST_CASE("Round trips between every pair of formats that can hold a camera", "[files]") {
    test::TempDir dir;
    int trips = 0;
    const std::vector<CameraFormat> written = written_formats();
    CHECK(written.size() == 14);
    for (const Case& c : cases()) {
        for (const CameraFormat first : written) {
            CAPTURE(c.what, to_string(first));
            const fs::path first_path = place(dir.path(), std::string(c.what) + "-a", first);
            if (!holds(c, first)) {
                // Refused, naming what does not fit, and nothing written.
                CHECK_THROWS_AS(write_camera_file(first_path, c.camera, first), NotRepresentable);
                CHECK_FALSE(fs::exists(first_path));
                continue;
            }
            write_camera_file(first_path, c.camera, first);
            const Camera once = read_camera_file(first_path).camera;
            const double first_tolerance = first == CameraFormat::Gl ? 1e-9 : 1e-12;
            check_same(once, c.camera, first_tolerance);
            for (const CameraFormat second : written) {
                if (!holds(c, second)) continue;
                CAPTURE(to_string(second));
                const fs::path second_path = place(dir.path(), std::string(c.what) + "-b", second);
                write_camera_file(second_path, once, second);
                const Camera twice = read_camera_file(second_path).camera;
                check_same(twice, c.camera, first == CameraFormat::Gl || second == CameraFormat::Gl ? 1e-9 : 1e-12);
                ++trips;
            }
        }
    }
    CHECK(trips == 13 * 13 + 6 * 6 + 10 * 10 + 9 * 9 + 6 * 6 + 9 * 9 + 4 * 4 + 3 * 3 + 1 * 1 + 2 * 2 + 3 * 3 + 4 * 4 + 5 * 5 +
                   5 * 5 /* LONLAT with fx = fy: Metashape too */ + 1 * 1 /* PTLENS, held by libcam's JSON alone */ + 3 * 3 /* BROWN_K4: JSON, Metashape, NeRF */ +
                   3 * 1 * 1 /* EQUIDISTANT_RADIAL, EQUISOLID_RADIAL, STEREOGRAPHIC_RADIAL: JSON alone */ +
                   1 * 1 /* OCAMCALIB: JSON alone */ +
                   2 * 2 /* DIVISION: JSON, COLMAP */ + 2 * 2 /* THETA_POLYNOMIAL: JSON, woodscape */ +
                   1 * 1 /* FTHETA: JSON (the rig's round trips are its own) */ + 1 * 1 /* FTHETA_FORWARD, likewise */);
}

TEST_CASE("Each format's row declares the lens models the round trips show it holds", "[files]") {
    // The holders above are worked out from each format's documentation; the table of
    // formats must say the same (a format claiming a model it refuses, or refusing one it
    // claims, fails here).
    // A format holds a model when it holds some camera of it: Metashape's LONLAT needs fx = fy.
    for (const Case& c : cases()) {
        if (c.camera.intrinsics.skew != 0.0) continue;  // skew is refused apart from the model
        for (const CameraFormat format : written_formats()) {
            const CameraFormatInfo info = camera_formats()[static_cast<std::size_t>(format)];
            CAPTURE(c.what, info.name);
            const bool declared = std::find(info.lenses.begin(), info.lenses.end(), c.camera.lens.type) != info.lenses.end();
            bool held = false;
            for (const Case& other : cases()) {
                held = held || (other.camera.lens.type == c.camera.lens.type && other.camera.intrinsics.skew == 0.0 &&
                                holds(other, format));
            }
            // BlenderJson holds FISHEYE only with its coefficients 0 (Blender's equidistant
            // fisheye), which the row does not count as holding the model.
            CHECK(declared == held);
        }
    }
}

TEST_CASE("COLMAP's own program reads libcam's model, and libcam reads COLMAP's binary and text back the same",
          "[files][colmap]") {
    const fs::path colmap = "/usr/bin/colmap";
    if (!fs::exists(colmap)) {
        WARN("skipped: COLMAP's program is not installed (Debian's colmap package)");
        return;
    }
    const std::vector<Lens> lenses = {
        {LensType::Pinhole, {}},
        {LensType::OpenCv4, {-0.2, 0.05, 1e-3, -2e-3}},
        {LensType::OpenCv8, {0.4, 0.05, 1e-3, -2e-3, 0.01, 0.7, 0.1, 0.02}},
        {LensType::Fisheye, {0.01, -0.002, 3e-4, -4e-5}},
        {LensType::Fov, {0.9}},
        {LensType::ThinPrismFisheye, {0.01, -0.002, 1e-4, -2e-4, 3e-4, -4e-5, 1e-4, 2e-4}},
    };
    for (const Lens& lens : lenses) {
        CAPTURE(lens_info(lens.type).name);
        test::TempDir dir;
        Camera camera = camera_with(lens);
        WriteOptions options;
        options.image_name = "frame_0001.jpg";
        write_camera_file(dir.path() / "text", camera, CameraFormat::Colmap, options);
        fs::create_directories(dir.path() / "binary");
        fs::create_directories(dir.path() / "again");
        const test::CliResult to_binary = test::run_program(
            colmap.string(), {"model_converter", "--input_path", (dir.path() / "text").string(), "--output_path",
                              (dir.path() / "binary").string(), "--output_type", "BIN"});
        REQUIRE(to_binary.exit_code == 0);
        const test::CliResult to_text = test::run_program(
            colmap.string(), {"model_converter", "--input_path", (dir.path() / "binary").string(), "--output_path",
                              (dir.path() / "again").string(), "--output_type", "TXT"});
        REQUIRE(to_text.exit_code == 0);
        const CameraSet text = read_camera_set(dir.path() / "text");
        const CameraSet binary = read_camera_set(dir.path() / "binary");
        const CameraSet again = read_camera_set(dir.path() / "again");
        REQUIRE(binary.cameras.size() == 1);
        REQUIRE(again.cameras.size() == 1);
        CHECK(binary.cameras[0].name == "frame_0001.jpg");
        CHECK(binary.cameras[0].intrinsics_name == "id:1");
        // COLMAP parses the text to the same doubles and writes them back with 17 digits.
        for (const CameraSet* set : {&binary, &again}) {
            const Camera& got = set->cameras[0].file.camera;
            const Camera& expected = text.cameras[0].file.camera;
            CHECK(got.lens == expected.lens);
            CHECK(got.intrinsics.K() == expected.intrinsics.K());
            CHECK(got.size == expected.size);
            CHECK((got.pose.R - expected.pose.R).cwiseAbs().maxCoeff() <= 1e-15);
            CHECK(got.pose.t == expected.pose.t);
        }
        check_same(text.cameras[0].file.camera, camera, 1e-12);
    }
}
