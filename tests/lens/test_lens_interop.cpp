// Camera files with distortion: every model round-trips through every format that can
// hold it, and a format that cannot is an error, never a silent conversion.

#include <catch2/catch.hpp>

#include "lens_cases.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/mrcal.hpp"
#include "libcam/interop/opencv.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/detail/opencv_storage.hpp"

using namespace libcam;
using namespace libcam::test;

namespace {

// Which formats hold which models, by hand: OpenCV's calibration file only its own
// radial-tangential models (FISHEYE's four numbers would read back as OPENCV4);
// mrcal has PINHOLE, OPENCV4/5/8/12, STEREOGRAPHIC, LONLAT, LATLON, CAHVOR and CAHVORE
// of libcam's models; libcam's JSON holds every model.
bool holds(CameraFormat format, LensType type) {
    switch (format) {
        case CameraFormat::Json: return true;
        case CameraFormat::OpenCvYaml:
        case CameraFormat::OpenCvXml:
            return type == LensType::Pinhole || type == LensType::OpenCv4 || type == LensType::OpenCv5 ||
                   type == LensType::OpenCv8 || type == LensType::OpenCv12 || type == LensType::OpenCv14 ||
                   type == LensType::Fisheye;
        case CameraFormat::Cameramodel:
            return type == LensType::Pinhole || type == LensType::OpenCv4 || type == LensType::OpenCv5 ||
                   type == LensType::OpenCv8 || type == LensType::OpenCv12 || type == LensType::Stereographic ||
                   type == LensType::Lonlat || type == LensType::Latlon || type == LensType::Cahvor ||
                   type == LensType::Cahvore || type == LensType::SplinedStereographic;
        case CameraFormat::Gl: return type == LensType::Pinhole;
        default: return false;  // the formats this test does not write
    }
}

Camera posed(Camera camera) {
    camera.pose = Pose::from_rvec(Vec3(0.1, -0.2, 0.05), Vec3(0.3, 1.5, -2.0));
    return camera;
}

}  // namespace

TEST_CASE("Every model round-trips through JSON, OpenCV YAML and XML, and .cameramodel where the format holds it") {
    for (const LensCase& c : lens_cases()) {
        const Camera camera = posed(c.camera);
        for (CameraFormat format : {CameraFormat::Json, CameraFormat::OpenCvYaml, CameraFormat::OpenCvXml, CameraFormat::Cameramodel}) {
            INFO(c.name << " as " << to_string(format));
            if (!holds(format, camera.lens.type)) {
                CHECK_THROWS_AS(format_camera(camera, format), NotRepresentable);
                continue;
            }
            const Camera back = parse_camera(format_camera(camera, format), format, "round trip").camera;
            CHECK(back.lens == camera.lens);
            CHECK(back.size.width == camera.size.width);
            CHECK(back.size.height == camera.size.height);
            CHECK((back.intrinsics.K() - camera.intrinsics.K()).cwiseAbs().maxCoeff() == 0.0);
            CHECK((back.pose.R - camera.pose.R).cwiseAbs().maxCoeff() < 1e-15);
            CHECK((back.pose.t - camera.pose.t).cwiseAbs().maxCoeff() == 0.0);
        }
    }
}

TEST_CASE("OpenCV's file: the number of distortion coefficients names the model") {
    const auto yaml = [](const std::string& dist_rows, const std::string& dist_data) {
        return "%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n"
               "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
               "   data: [ 500., 0., 319.5, 0., 501., 239.5, 0., 0., 1. ]\n"
               "distortion_coefficients: !!opencv-matrix\n   rows: " + dist_rows + "\n   cols: 1\n   dt: d\n"
               "   data: [ " + dist_data + " ]\n";
    };
    const Camera opencv8 = parse_opencv_storage(yaml("8", "-0.1, 0.02, 1e-4, -2e-4, 0.003, 0.05, 0.004, 1e-5"), "8.yaml");
    CHECK(opencv8.lens == Lens{LensType::OpenCv8, {-0.1, 0.02, 1e-4, -2e-4, 0.003, 0.05, 0.004, 1e-5}});
    const Camera opencv4 = parse_opencv_storage(yaml("4", "-0.1, 0.02, 1e-4, -2e-4"), "4.yaml");
    CHECK(opencv4.lens.type == LensType::OpenCv4);
    const Camera opencv14 = parse_opencv_storage(yaml("14", "1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 0.01, 0.02"), "14.yaml");
    CHECK(opencv14.lens.type == LensType::OpenCv14);
    CHECK(parse_opencv_storage(yaml("5", "0., 0., 0., 0., 0."), "zeros.yaml").lens == Lens{});
    CHECK_THROWS_WITH(parse_opencv_storage(yaml("6", "1, 2, 3, 4, 5, 6"), "6.yaml"),
                      Catch::Contains("6.yaml") && Catch::Contains("4, 5, 8, 12 or 14"));
}

TEST_CASE("mrcal's files: its lens models map by name, configurations included, and bad ones are refused") {
    const auto cameramodel = [](const std::string& model, const std::string& intrinsics) {
        return "{\n 'lensmodel': '" + model + "',\n 'intrinsics': [ " + intrinsics +
               " ],\n 'imagersize': [ 640, 480 ],\n 'extrinsics': [ 0, 0, 0, 0, 0, 0 ]\n}\n";
    };
    const Camera opencv8 = parse_cameramodel(
        cameramodel("LENSMODEL_OPENCV8", "500, 501, 319.5, 239.5, -0.1, 0.02, 1e-4, -2e-4, 0.003, 0.05, 0.004, 1e-5"), "a");
    CHECK(opencv8.lens == Lens{LensType::OpenCv8, {-0.1, 0.02, 1e-4, -2e-4, 0.003, 0.05, 0.004, 1e-5}});
    CHECK(parse_cameramodel(cameramodel("LENSMODEL_LATLON", "500, 501, 319.5, 239.5"), "b").lens.type == LensType::Latlon);
    const Camera cahvor =
        parse_cameramodel(cameramodel("LENSMODEL_CAHVOR", "500, 501, 319.5, 239.5, 0.01, -0.02, 0.1, 0.2, 0.3"), "c");
    CHECK(cahvor.lens == Lens{LensType::Cahvor, {0.01, -0.02, 0.1, 0.2, 0.3}});
    // CAHVORE's linearity is in mrcal's name, and is libcam's last coefficient.
    const Camera cahvore = parse_cameramodel(
        cameramodel("LENSMODEL_CAHVORE_linearity=0.25", "500, 501, 319.5, 239.5, 0.01, -0.02, 0.1, 0.2, 0.3, 1e-3, 2e-3, 3e-3"),
        "d");
    CHECK(cahvore.lens == Lens{LensType::Cahvore, {0.01, -0.02, 0.1, 0.2, 0.3, 1e-3, 2e-3, 3e-3, 0.25}});
    // SPLINED_STEREOGRAPHIC's configuration is in mrcal's name, and is libcam's first four
    // coefficients; the control points follow.
    std::string splined_intrinsics = "500, 501, 319.5, 239.5";
    std::vector<double> splined{2, 3, 4, 100};
    for (int i = 0; i < 2 * 3 * 4; ++i) {
        // The number the text says (9 * 1e-3 is not the double nearest 9e-3).
        const std::string control = std::to_string(i) + "e-3";
        splined_intrinsics += ", " + control;
        splined.push_back(std::stod(control));
    }
    const Camera spline = parse_cameramodel(
        cameramodel("LENSMODEL_SPLINED_STEREOGRAPHIC_order=2_Nx=3_Ny=4_fov_x_deg=100", splined_intrinsics), "e");
    CHECK(spline.lens == Lens{LensType::SplinedStereographic, splined});
    // A configuration mrcal's name allows but its spline does not (order 4; a cubic
    // over 3 knots) is refused by name before mrcal ever evaluates it.
    CHECK_THROWS_WITH(parse_cameramodel(cameramodel("LENSMODEL_SPLINED_STEREOGRAPHIC_order=4_Nx=3_Ny=4_fov_x_deg=100",
                                                    splined_intrinsics),
                                        "order.cameramodel"),
                      Catch::Contains("order.cameramodel") && Catch::Contains("order") && Catch::Contains("got 4"));
    CHECK_THROWS_WITH(parse_cameramodel(cameramodel("LENSMODEL_SPLINED_STEREOGRAPHIC_order=3_Nx=3_Ny=4_fov_x_deg=100",
                                                    splined_intrinsics),
                                        "knots.cameramodel"),
                      Catch::Contains("knots.cameramodel") && Catch::Contains("Nx") && Catch::Contains("got 3"));
    // A model mrcal itself does not know.
    CHECK_THROWS_WITH(parse_cameramodel(cameramodel("LENSMODEL_OPENCV9", "500, 501, 319.5, 239.5"), "f.cameramodel"),
                      Catch::Contains("f.cameramodel"));
    const Camera fisheye = lens_camera(LensType::Fisheye, {0.01, 0, 0, 0});
    CHECK_THROWS_WITH(format_cameramodel(fisheye), Catch::Contains("FISHEYE") && Catch::Contains("mrcal"));
    CHECK_THROWS_AS(mrcal_lensmodel_name(fisheye.lens), NotRepresentable);
    CHECK(mrcal_lensmodel_name(Lens{LensType::Stereographic, {}}) == "LENSMODEL_STEREOGRAPHIC");
}

TEST_CASE("A JSON file's coefficients must match its model") {
    const Camera camera = posed(lens_camera(LensType::OpenCv5, {0.1, 0.01, 0, 0, 0.001}));
    std::string text = format_camera(camera, CameraFormat::Json);
    const std::size_t at = text.find("0.001");
    REQUIRE(at != std::string::npos);
    text.replace(at, 5, "0.001, 7");
    CHECK_THROWS_WITH(parse_camera(text, CameraFormat::Json, "six.json"),
                      Catch::Contains("six.json") && Catch::Contains("OPENCV5 takes 5 coefficients, got 6"));
}

TEST_CASE("opencv_distortion hands OpenCV the coefficients of the models it has, and refuses the others") {
    const Lens fisheye{LensType::Fisheye, {0.1, 0.2, 0.3, 0.4}};
    const cv::Mat dist = opencv_distortion(fisheye);
    REQUIRE(dist.total() == 4);
    CHECK(dist.at<double>(3) == 0.4);
    CHECK(opencv_distortion(Lens{}).total() == 0);
    CHECK_THROWS_AS(opencv_distortion(Lens{LensType::Lonlat, {}}), NotRepresentable);
}
