// The calibration files other tools wrote for real cameras (a folder of them beside the
// source tree; see LIBCAM_REAL_CAMERAS_DIR in tests/CMakeLists.txt): the ones libcam
// reads give the numbers written in them, copied here by hand from each file's text; every
// other one is refused with a libcam error naming the file, never a crash and never a
// camera read wrongly.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "libcam/error.hpp"
#include "lens_cases.hpp"
#include "real_cameras.hpp"
#include "libcam/io/camera_file.hpp"

using namespace libcam;
using libcam::test::real_cameras_folder;
using libcam::test::real_cameras_present;
namespace fs = std::filesystem;

namespace {

const fs::path kFolder = real_cameras_folder();

// What a file holds, from its text.
struct Expected {
    const char* path;    // inside the folder
    const char* camera;  // which camera of the file (--camera): "" for the first
    LensType type;
    ImageSize size;
    double fx, fy, cx, cy;
    double first_coefficient;  // 0 for PINHOLE
    ImageSize given_size = {0, 0};  // --image-size, for a file that does not record it
};

ReadOptions options_for(const Expected& e) {
    ReadOptions options;
    if (e.given_size.width > 0) options.size = e.given_size;
    return options;
}

const std::vector<Expected> kReadable{
    {"colmap-fiord-fisheye/camera_intrinsics.yaml", "", LensType::Fisheye, {3264, 3264}, 991.0, 991.0, 1612.0, 1617.0,
     0.024943212941115993},
    {"opencv-calib-sample-outputs/fisheye_cali/out_camera_data.xml", "", LensType::OpenCv5, {640, 480}, 243.40126575350806,
     243.40126575350806, 319.5, 239.5, -0.25283129827330714},
    {"mrcal/cam0.opencv8.cameramodel", "", LensType::OpenCv8, {4000, 2200}, 1761.181055, 1761.250444, 1965.706996,
     1087.518797, -0.01266096516},
    {"mrcal/opencv8-0.cameramodel", "", LensType::OpenCv8, {6016, 4016}, 2073.872915, 2077.452267, 3004.686823, 1997.377253,
     0.4791613797},
    {"mrcal/opencv8-1.cameramodel", "", LensType::OpenCv8, {6016, 4016}, 2073.872915, 2077.452267, 3004.686823, 1997.377253,
     0.4791613797},
    // mrcal's splined models: the first coefficient is the spline's order.
    {"mrcal/cam0.splined.cameramodel", "", LensType::SplinedStereographic, {4000, 2200}, 1761.181055, 1761.250444,
     1965.706996, 1087.518797, 3.0},
    {"mrcal/splined-0.cameramodel", "", LensType::SplinedStereographic, {6016, 4016}, 2018.95821, 2058.977247, 3017.639608,
     1957.291928, 3.0},
    {"mrcal/splined-1.cameramodel", "", LensType::SplinedStereographic, {6016, 4016}, 2018.95821, 2058.977247, 3017.639608,
     1957.291928, 3.0},
    {"mrcal/pinhole-narrow-yawed-left.cameramodel", "", LensType::Pinhole, {3008, 2008}, 2405.678127, 2453.362582,
     1508.569804, 978.395964, 0.0},
    {"mrcal/pinhole-narrow-yawed-right.cameramodel", "", LensType::Pinhole, {3008, 2008}, 2405.678127, 2453.362582,
     1508.569804, 978.395964, 0.0},
    // Kalibr's camchains (as Kalibr writes them, and as OpenVINS ships them).
    {"open_vins/euroc_mav/kalibr_imucam_chain.yaml", "", LensType::OpenCv4, {752, 480}, 458.654, 457.296, 367.215, 248.375, -0.28340811},
    {"open_vins/euroc_mav/kalibr_imucam_chain.yaml", "cam1", LensType::OpenCv4, {752, 480}, 457.587, 456.134, 379.999, 255.238, -0.28368365},
    {"open_vins/kaist/kalibr_imucam_chain.yaml", "", LensType::OpenCv4, {1280, 560}, 816.9037899277, 811.5680382849, 608.5072628169, 263.4759976444, -0.0561430278},
    {"open_vins/rs_d455/kalibr_imucam_chain.yaml", "", LensType::OpenCv4, {848, 480}, 416.85223429743274, 414.92069080087543, 421.02459311003213, 237.76180565241077, -0.045761895748285604},
    {"open_vins/rs_t265/kalibr_imucam_chain.yaml", "", LensType::Fisheye, {848, 800}, 282.019963259348, 280.7145153126385, 415.9558137753508, 396.6613771975339, -0.003269003229949738},
    {"open_vins/tum_vi/kalibr_imucam_chain.yaml", "", LensType::Fisheye, {512, 512}, 190.97847715128717, 190.9733070521226, 254.93170605935475, 256.8974428996504, 0.0034823894022493434},
    {"open_vins/uzhfpv_indoor/kalibr_imucam_chain.yaml", "", LensType::Fisheye, {640, 480}, 278.66723066149086, 278.48991409740296, 319.75221200593535, 241.96858910358173, -0.013721808247486035},
    {"kalibr/camchain-camera.yaml", "", LensType::Fisheye, {640, 480}, 277.95596230891084, 278.4167467580337, 315.5269754313737, 244.46893770533453, -0.005908650672531068},
    {"kalibr/camchain-imucam-camera_imu.yaml", "", LensType::Fisheye, {640, 480}, 274.51623038381354, 275.33528152592356, 313.61364519480173, 251.55631360961928, -0.027396339719770575},
    // basalt's calibrations: the first coefficient is xi (ds), alpha (eucm) or k1 (kb4).
    {"basalt/euroc_ds_calib.json", "", LensType::DoubleSphere, {752, 480}, 349.7560023050409, 348.72454229977035, 365.89440762590147, 249.32995565708703, -0.2409573942178872},
    {"basalt/euroc_eucm_calib.json", "", LensType::Eucm, {752, 480}, 460.76484651566466, 459.4051018049483, 365.8937161309615, 249.33499869752444, 0.5903365915227143},
    {"basalt/t265_kb4_calib.json", "", LensType::Fisheye, {848, 800}, 286.60144163375526, 286.4617087423328, 422.2765876951761, 395.2246466040553, -0.006762412326815424},
    {"basalt/tumvi_512_ds_calib.json", "", LensType::DoubleSphere, {512, 512}, 158.28600034966976, 158.2743455478755, 254.96116578191652, 256.8894394501779, -0.17213086034353242},
    {"basalt/tumvi_512_eucm_calib.json", "", LensType::Eucm, {512, 512}, 191.14799836282188, 191.13150963902817, 254.9585771534443, 256.88154645599445, 0.6291060881178562},
    // camodocal's (VINS-Fusion): MEI's first coefficient is xi, its K gamma1 gamma2 u0 v0.
    {"vins-fusion/A3_ptgrey/left.yaml", "", LensType::OpenCv4, {640, 512}, 443.6476851702351, 443.83960982739706, 318.7128184842236, 249.90737366327537, -0.13445051055717713},
    {"vins-fusion/euroc/cam0_mei.yaml", "", LensType::Mei, {752, 480}, 2138.7619122017772, 2131.5886210259278, 361.198566332638, 248.27644773395667, 3.6313355285286337},
    {"vins-fusion/euroc/cam0_pinhole.yaml", "", LensType::OpenCv4, {752, 480}, 461.15862106007575, 459.75286598073296, 362.65929181685937, 248.52105668448124, -0.2954564510698775},
    {"vins-fusion/mynteye/left_mei.yaml", "", LensType::Mei, {752, 480}, 895.9437186180799, 897.4158147903275, 372.21680816143993, 238.33534175557006, 1.4456544769803834},
    // COLMAP's and transforms.json's pixel (0, 0) is the image's corner: libcam's cx is theirs - 0.5.
    {"colmap-fiord-fisheye/cameras.txt", "id:2", LensType::Fisheye, {3264, 3264}, 991, 991, 1612 - 0.5, 1617 - 0.5,
     0.024943212941115993},
    {"instant-ngp/transforms.json", "images/0002.jpg", LensType::OpenCv4, {1080, 1920}, 1375.52, 1374.49, 554.558 - 0.5,
     965.268 - 0.5, 0.0578421},
    // NeRF's lego scene: only camera_angle_x; 800x800 images; the principal point at the centre.
    {"nerf-synthetic-blender/transforms_train.json", "./train/r_1", LensType::Pinhole, {800, 800},
     400 / std::tan(0.6911112070083618 / 2), 400 / std::tan(0.6911112070083618 / 2), 399.5, 399.5, 0.0, {800, 800}},
    // mrcal's CAHV text of a pinhole: its Hs, Vs, Hc, Vc lines say fx, fy, cx, cy.
    {"mrcal/splined-0.scale0.6.cahvor", "", LensType::Pinhole, {6016, 4016}, 1211.374926, 1235.386348, 3017.639608,
     1957.291928, 0.0},
};

}  // namespace

TEST_CASE("Real calibration files libcam reads give the numbers written in them", "[files][real]") {
    if (!real_cameras_present()) return;
    for (const Expected& e : kReadable) {
        CAPTURE(e.path, e.camera);
        const Camera camera = read_camera_file(kFolder / e.path, e.camera, std::nullopt, options_for(e)).camera;
        CHECK(camera.lens.type == e.type);
        CHECK(camera.size == e.size);
        CHECK(camera.intrinsics.fx == e.fx);
        CHECK(camera.intrinsics.fy == e.fy);
        CHECK(camera.intrinsics.cx == e.cx);
        CHECK(camera.intrinsics.cy == e.cy);
        CHECK((camera.lens.coefficients.empty() ? 0.0 : camera.lens.coefficients.front()) == e.first_coefficient);
    }
}

TEST_CASE("Every real calibration file is read, and one that leaves out what libcam needs is refused with one line",
          "[files][real]") {
    if (!real_cameras_present()) return;
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(kFolder)) {
        if (!entry.is_regular_file() || entry.path().filename() == "SOURCES.md") continue;
        const std::string relative = fs::relative(entry.path(), kFolder).generic_string();
        const bool readable = std::any_of(kReadable.begin(), kReadable.end(), [&](const Expected& e) { return relative == e.path; });
        if (readable) continue;
        CAPTURE(relative);
        try {
            (void)read_camera_set(entry.path());
            FAIL("read as a camera, but this test does not know what it holds");
        } catch (const Error& error) {  // FileError, or InvalidArgument for a value libcam cannot take
            const std::string message = error.what();
            CHECK(message.starts_with(entry.path().string() + ": "));
            CHECK(message.find('\n') == std::string::npos);
        }
    }
    // NeRF's synthetic scenes do not record the image size, and the images are not there.
    const fs::path lego = kFolder / "nerf-synthetic-blender/transforms_train.json";
    CHECK_THROWS_WITH(read_camera_set(lego), lego.string() + ": \"w\", \"h\": missing: the file does not record the "
                                                           "image size, and the first frame's image is not there to read "
                                                           "it from; give the size (--image-size WxH) (read as NeRF "
                                                           "transforms.json, by its extension .json and its keys)");
}

TEST_CASE("Rig files: poses in the rig's frame, worked from each file's own transform", "[files][real]") {
    if (!real_cameras_present()) return;
    // Kalibr's T_cam_imu is world (IMU) to camera as it stands: t is its last column.
    const Camera t265 = read_camera_file(kFolder / "open_vins/rs_t265/kalibr_imucam_chain.yaml").camera;
    CHECK(t265.pose.t.x() == 0.009847737933630705);
    CHECK(t265.pose.R(0, 0) == -0.9998761771972654);
    // OpenVINS's T_imu_cam is the camera in the IMU frame: its last column is the centre.
    // KAIST's rotation is printed with five decimals and read as the nearest rotation.
    const Camera kaist = read_camera_file(kFolder / "open_vins/kaist/kalibr_imucam_chain.yaml").camera;
    CHECK((kaist.pose.centre() - Vec3(1.71239, 0.24740, -0.11589)).norm() < 1e-12);
    CHECK((kaist.pose.R.transpose() * kaist.pose.R - Mat3::Identity()).norm() < 1e-14);
    // basalt's T_imu_cam likewise: px py pz is the centre of camera 1.
    const Camera euroc = read_camera_file(kFolder / "basalt/euroc_ds_calib.json", "1").camera;
    CHECK((euroc.pose.centre() - Vec3(-0.01507436282032619, 0.0412627204046637, 0.00316287258752953)).norm() < 1e-15);
    // Every camera of a rig, by name.
    const CameraSet chain = read_camera_set(kFolder / "open_vins/rs_t265/kalibr_imucam_chain.yaml");
    REQUIRE(chain.cameras.size() == 2);
    CHECK(chain.cameras[1].name == "cam1");
    CHECK(chain.format == CameraFormat::Kalibr);
    CHECK_THROWS_WITH(select_camera(chain, "cam2", "rs_t265"),
                      Catch::Contains("no camera 'cam2'; it holds 2 cameras: 0 (cam0), 1 (cam1)"));
    // instant-ngp's frames: camera-to-world in OpenGL's axes. The last column is the
    // centre, and the camera looks along minus the third column.
    const CameraSet fox = read_camera_set(kFolder / "instant-ngp/transforms.json");
    CHECK(fox.format == CameraFormat::Nerf);
    REQUIRE(fox.cameras.size() == 67);
    const Camera& first = fox.cameras[0].file.camera;
    CHECK(fox.cameras[0].name == "images/0001.jpg");
    CHECK((first.pose.centre() - Vec3(3.168359405609479, -5.4794898611466945, -0.9791660699008925)).norm() < 1e-12);
    const Vec3 looking = -Vec3(0.4420900262071262, -0.8940689141475064, -0.07209178487538156);
    CHECK((first.pose.R.row(2).transpose() - looking).norm() < 1e-6);  // the file's rotation is orthonormal to 1e-7
    // COLMAP's camera id names the camera.
    const CameraSet fiord = read_camera_set(kFolder / "colmap-fiord-fisheye/cameras.txt");
    REQUIRE(fiord.cameras.size() == 1);
    CHECK(fiord.cameras[0].name == "id:2");
}

TEST_CASE("Every camera of every real file libcam reads projects as the library that defines its model does",
          "[files][real]") {
    if (!real_cameras_present()) return;
    std::vector<std::string> done;
    for (const Expected& e : kReadable) {
        if (std::find(done.begin(), done.end(), e.path) != done.end()) continue;
        done.emplace_back(e.path);
        const CameraSet set = read_camera_set(kFolder / e.path, std::nullopt, options_for(e));
        for (const NamedCamera* named : test::distinct_cameras(set)) {
            const Camera& camera = named->file.camera;
            CAPTURE(e.path, named->name);
            // Rays through a grid of the image, projected back by the model's own library
            // (OpenCV, cv::fisheye, cv::omnidir, mrcal) or its paper's formula.
            const test::ReferenceAgreement agreement = test::against_reference(camera);
            REQUIRE(agreement.rays > agreement.pixels / 2);
            const double worst = agreement.worst_px;
            WARN(e.path << " | " << to_string(set.format) << " | " << (named->name.empty() ? "-" : named->name) << " | "
                        << lens_info(camera.lens.type).name << " | " << camera.size.width << "x" << camera.size.height
                        << " | " << worst << " px over " << agreement.rays << " pixels");
            CHECK(worst <= 1e-9);
        }
    }
}
