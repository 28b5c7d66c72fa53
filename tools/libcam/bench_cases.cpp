#include "bench_cases.hpp"

#include "libcam/camera/example_cameras.hpp"

namespace libcam::cli {

namespace {

// A 1920x1080 camera with OpenCV's five coefficients, as calibrated video cameras
// commonly are: the size and model most undistortion maps are built for.
Camera hd_camera() {
    Camera camera;
    camera.size = {1920, 1080};
    camera.intrinsics = {1400.0, 1402.5, 965.3, 537.8, 0.0};
    camera.lens = {LensType::OpenCv5, {-0.31, 0.11, 2e-4, -3e-4, -0.018}};
    return camera;
}

}  // namespace

std::vector<BenchCase> builtin_bench_cases() {
    std::vector<BenchCase> cases;
    for (const ExampleCamera& example : example_cameras()) cases.push_back({std::string(example.name), example.camera});
    return cases;
}

std::vector<BenchCase> map_bench_cases() {
    std::vector<BenchCase> cases{{"hd", hd_camera()}};
    for (const char* name : {"wide", "fisheye"}) cases.push_back({name, example_camera(name)});
    return cases;
}

}  // namespace libcam::cli
