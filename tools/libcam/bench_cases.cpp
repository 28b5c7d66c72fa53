#include "bench_cases.hpp"

#include "libcam/camera/example_cameras.hpp"

namespace libcam::cli {

std::vector<BenchCase> builtin_bench_cases() {
    std::vector<BenchCase> cases;
    for (const ExampleCamera& example : example_cameras()) cases.push_back({std::string(example.name), example.camera});
    return cases;
}

}  // namespace libcam::cli
