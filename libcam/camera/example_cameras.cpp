#include "libcam/camera/example_cameras.hpp"

#include <string>

#include "libcam/error.hpp"

namespace libcam {

namespace {

Camera synthetic_camera(ImageSize size, double f, Lens lens) {
    Camera camera;
    camera.size = size;
    // An off-centre principal point and slightly non-square pixels, as calibrations give.
    camera.intrinsics = {f, f * 1.004, 0.5 * static_cast<double>(size.width - 1) + 13.0,
                         0.5 * static_cast<double>(size.height - 1) - 7.0, 0.0};
    camera.lens = std::move(lens);
    return camera;
}

// A real calibration of a wide-angle lens on a 6016x4016 sensor (OpenCV's rational model):
// strong distortion (k1 0.479, k4 0.767) on which OpenCV's default undistortPoints is off
// by hundreds of pixels in the corners.
Camera wide_camera() {
    Camera camera;
    camera.size = {6016, 4016};
    camera.intrinsics = {2073.872915, 2077.452267, 3004.686823, 1997.377253, 0.0};
    camera.lens = {LensType::OpenCv8,
                   {0.4791613797, 0.0266824914, 4.398264387e-05, -1.180073913e-05, 8.959722542e-05, 0.7666912469,
                    0.09633561231, 0.001407513313}};
    return camera;
}

// basalt's calibration of TUM-VI's cam0 (512x512, Double Sphere): a real fisheye whose
// image reaches almost to the model's rim.
Camera tum_vi_camera() {
    Camera camera;
    camera.size = {512, 512};
    camera.intrinsics = {158.28600034966976, 158.2743455478755, 254.96116578191652, 256.8894394501779, 0.0};
    camera.lens = {LensType::DoubleSphere, {-0.17213086034353242, 0.5931177593944744}};
    return camera;
}

}  // namespace

std::vector<ExampleCamera> example_cameras() {
    return {
        {"mild", "OPENCV8, 1600x1200, mild distortion",
         synthetic_camera({1600, 1200}, 900, {LensType::OpenCv8, {0.1, 0.02, 1e-4, -1e-4, 0.001, 0.12, 0.015, 0.0005}})},
        {"strong", "OPENCV8, 1600x1200, folds over inside the corners",
         synthetic_camera({1600, 1200}, 900, {LensType::OpenCv8, {-0.33, 0.09, 1e-3, -8e-4, -0.01, 0.02, 0.003, 1e-4}})},
        {"fisheye", "FISHEYE, 1600x1200, corners past 90 degrees",
         synthetic_camera({1600, 1200}, 420, {LensType::Fisheye, {-0.013, -0.0057, 0.0023, -0.0009}})},
        {"wide", "OPENCV8, 6016x4016, a real wide-angle calibration", wide_camera()},
        {"double-sphere", "DOUBLE_SPHERE, 512x512, a real fisheye calibration (TUM-VI, by basalt)", tum_vi_camera()},
    };
}

Camera example_camera(std::string_view name) {
    std::string names;
    for (const ExampleCamera& example : example_cameras()) {
        if (example.name == name) return example.camera;
        names += (names.empty() ? "" : ", ") + std::string(example.name);
    }
    throw InvalidArgument("example camera: no camera named '" + std::string(name) + "' (choose " + names + ")");
}

}  // namespace libcam
