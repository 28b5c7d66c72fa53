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

// "mild" and "strong" OPENCV8 lenses (the strong one folds over inside the image's
// corners), "fisheye" (FISHEYE, corners past 90 degrees), and "wide": a real calibrated
// wide lens (6016x4016 OPENCV8).
std::vector<BenchCase> builtin_bench_cases();

}  // namespace libcam::cli
