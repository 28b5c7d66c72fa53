#include "bench_cases.hpp"

namespace libcam::cli {

namespace {

Camera bench_camera(ImageSize size, double f, Lens lens) {
    Camera camera;
    camera.size = size;
    // An off-centre principal point, as calibrations give.
    camera.intrinsics = {f, f * 1.004, 0.5 * static_cast<double>(size.width - 1) + 13.0,
                         0.5 * static_cast<double>(size.height - 1) - 7.0, 0.0};
    camera.lens = std::move(lens);
    return camera;
}

}  // namespace

std::vector<BenchCase> builtin_bench_cases() {
    Camera wide;
    wide.size = {6016, 4016};
    wide.intrinsics = {2073.872915, 2077.452267, 3004.686823, 1997.377253, 0.0};
    wide.lens = {LensType::Opencv8,
                 {0.4791613797, 0.0266824914, 4.398264387e-05, -1.180073913e-05, 8.959722542e-05, 0.7666912469,
                  0.09633561231, 0.001407513313}};
    return {
        {"mild", bench_camera({1600, 1200}, 900,
                              {LensType::Opencv8, {0.1, 0.02, 1e-4, -1e-4, 0.001, 0.12, 0.015, 0.0005}})},
        {"strong", bench_camera({1600, 1200}, 900,
                                {LensType::Opencv8, {-0.33, 0.09, 1e-3, -8e-4, -0.01, 0.02, 0.003, 1e-4}})},
        {"fisheye", bench_camera({1600, 1200}, 420, {LensType::Fisheye, {-0.013, -0.0057, 0.0023, -0.0009}})},
        {"wide", wide},
    };
}

}  // namespace libcam::cli
