#pragma once
// The cameras `libcam bench` measures when no file is given.

#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"

namespace libcam::cli {

struct BenchCase {
    std::string name;
    Camera camera;
};

// The library's example cameras (camera/example_cameras.hpp).
std::vector<BenchCase> builtin_bench_cases();

// The cameras `libcam bench --maps` measures: a 1920x1080 OPENCV5 ("hd"), the 6016x4016
// OPENCV8 "wide" and the FISHEYE "fisheye" example cameras.
std::vector<BenchCase> map_bench_cases();

}  // namespace libcam::cli
