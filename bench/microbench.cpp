// Google Benchmark timings of libcam's hot functions on the cameras of `libcam bench`:
//   build/bench/libcam_microbench --benchmark_filter=Unproject
// Each benchmark reports ns per point (the counter ns_per_point) besides the wall time.
// Arguments: the number of threads.

#include <benchmark/benchmark.h>

#include <cstring>

#include "bench_cases.hpp"
#include "libcam/camera/projector.hpp"
#include "libcam/camera/unprojector.hpp"

namespace {

using namespace libcam;

const cli::BenchCase& bench_case(const std::string& name) {
    static const std::vector<cli::BenchCase> cases = cli::builtin_bench_cases();
    for (const cli::BenchCase& c : cases) {
        if (c.name == name) return c;
    }
    throw std::invalid_argument("no bench case " + name);
}

// The same lens (or a pinhole with the same K) on a 1920-pixel-wide sensor.
Camera camera_1920(const std::string& name, LensType type_or_pinhole) {
    Camera camera = bench_case(name).camera;
    const double s = 1920.0 / static_cast<double>(camera.size.width);
    camera.size = {1920, std::lround(s * static_cast<double>(camera.size.height))};
    Intrinsics& k = camera.intrinsics;
    k = {s * k.fx, s * k.fy, s * (k.cx + 0.5) - 0.5, s * (k.cy + 0.5) - 0.5, 0.0};
    if (type_or_pinhole == LensType::Pinhole) camera.lens = Lens{};
    return camera;
}

// A grid of 256 x 256 pixels over the image, corners included.
template <class Scalar>
Points2<Scalar> pixel_grid(const ImageSize& size) {
    constexpr int kSide = 256;
    Points2<Scalar> pixels;
    for (int j = 0; j < kSide; ++j) {
        for (int i = 0; i < kSide; ++i) {
            pixels.x.push_back(Scalar(static_cast<double>(size.width - 1) * i / (kSide - 1)));
            pixels.y.push_back(Scalar(static_cast<double>(size.height - 1) * j / (kSide - 1)));
        }
    }
    return pixels;
}

void report_per_point(benchmark::State& state, std::size_t points) {
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(points));
    state.counters["ns_per_point"] = benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(points),
                                                        benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

template <class Scalar, UnprojectMethod method>
void Unproject(benchmark::State& state, const std::string& name) {
    const Camera& camera = bench_case(name).camera;
    const Unprojector<Scalar> unprojector(camera);
    const Points2<Scalar> pixels = pixel_grid<Scalar>(camera.size);
    Points3<Scalar> directions;
    ValidFlags valid;
    for (auto _ : state) {
        unprojector.unproject(pixels, method, directions, valid, static_cast<int>(state.range(0)));
        benchmark::DoNotOptimize(directions.x.data());
        benchmark::ClobberMemory();
    }
    report_per_point(state, pixels.size());
}

template <class Scalar>
void Project(benchmark::State& state, const std::string& name) {
    const Camera& camera = bench_case(name).camera;
    const Unprojector<double> unprojector(camera);
    Points3<double> rays;
    ValidFlags valid;
    unprojector.unproject(pixel_grid<double>(camera.size), UnprojectMethod::Exact, rays, valid);
    Points3<Scalar> points;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        points.x.push_back(Scalar(rays.x[i]));
        points.y.push_back(Scalar(rays.y[i]));
        points.z.push_back(Scalar(rays.z[i]));
    }
    const Projector<Scalar> projector(camera);
    Points2<Scalar> pixels;
    for (auto _ : state) {
        projector.project(points, pixels, valid, static_cast<int>(state.range(0)));
        benchmark::DoNotOptimize(pixels.x.data());
        benchmark::ClobberMemory();
    }
    report_per_point(state, points.size());
}

// Every pixel's ray of a 1920-wide image through the lens of case `name` (or a pinhole
// with its K).
template <class Scalar, UnprojectMethod method>
void ImageRays(benchmark::State& state, const std::string& name, LensType type) {
    const Unprojector<Scalar> unprojector(camera_1920(name, type));
    Points3<Scalar> directions;
    ValidFlags valid;
    for (auto _ : state) {
        unprojector.unproject_image(method, directions, valid, static_cast<int>(state.range(0)));
        benchmark::DoNotOptimize(directions.x.data());
        benchmark::ClobberMemory();
    }
    report_per_point(state, directions.size());
}

// Writing the bytes ImageRays writes (three coordinates and a flag per pixel), once,
// with `byte` (zeros are written faster than other bytes on some machines).
template <class Scalar>
void ImageMemset(benchmark::State& state, int byte) {
    const Camera camera = camera_1920("wide", LensType::Pinhole);
    const std::size_t n = static_cast<std::size_t>(camera.size.width) * static_cast<std::size_t>(camera.size.height);
    Points3<Scalar> directions;
    directions.resize(n);
    ValidFlags valid(n);
    for (auto _ : state) {
        for (std::vector<Scalar>* v : {&directions.x, &directions.y, &directions.z}) std::memset(v->data(), byte, n * sizeof(Scalar));
        std::memset(valid.data(), byte, n);
        benchmark::ClobberMemory();
    }
    report_per_point(state, n);
}

// The same pixels as numpy's (N, 2) array lies in memory, the directions as its (N, 3).
template <UnprojectMethod method>
void UnprojectInterleaved(benchmark::State& state, const std::string& name) {
    const Camera& camera = bench_case(name).camera;
    const Unprojector<double> unprojector(camera);
    const Points2<double> grid = pixel_grid<double>(camera.size);
    std::vector<double> pixels;
    for (std::size_t i = 0; i < grid.size(); ++i) pixels.insert(pixels.end(), {grid.x[i], grid.y[i]});
    std::vector<double> directions(3 * grid.size());
    ValidFlags valid(grid.size());
    for (auto _ : state) {
        unprojector.unproject_interleaved(pixels, method, directions, valid, static_cast<int>(state.range(0)));
        benchmark::DoNotOptimize(directions.data());
        benchmark::ClobberMemory();
    }
    report_per_point(state, grid.size());
}

// The public call, PreparedCamera::unproject, on a list of pixels.
void CameraUnproject(benchmark::State& state) {
    const PreparedCamera camera(bench_case("wide").camera);
    camera.unprojector();  // built before timing
    const Points2<double> grid = pixel_grid<double>(camera.camera().size);
    std::vector<Vec2> pixels;
    for (std::size_t i = 0; i < grid.size(); i += 16) pixels.emplace_back(grid.x[i], grid.y[i]);
    for (auto _ : state) benchmark::DoNotOptimize(camera.unproject(pixels));
    report_per_point(state, pixels.size());
}

// Each batch benchmark on 1 and 2 threads, timed by the wall clock.
void on_threads(benchmark::internal::Benchmark* b) { b->Arg(1)->Arg(2)->UseRealTime(); }

template <UnprojectMethod method>
void register_unprojection(const std::string& name) {
    const std::string label = "Unproject/" + name + "/" + std::string(method_name(method));
    benchmark::RegisterBenchmark((label + "/double").c_str(), Unproject<double, method>, name)->Apply(on_threads);
    benchmark::RegisterBenchmark((label + "/float").c_str(), Unproject<float, method>, name)->Apply(on_threads);
}

template <UnprojectMethod method>
void register_image_rays(const std::string& label, const std::string& name, LensType type) {
    const std::string full = "ImageRays/" + label + "/" + std::string(method_name(method));
    benchmark::RegisterBenchmark((full + "/double").c_str(), ImageRays<double, method>, name, type)->Apply(on_threads);
    benchmark::RegisterBenchmark((full + "/float").c_str(), ImageRays<float, method>, name, type)->Apply(on_threads);
}

void register_benchmarks() {
    for (const std::string name : {"wide", "fisheye"}) {
        register_unprojection<UnprojectMethod::Exact>(name);
        register_unprojection<UnprojectMethod::Fast>(name);
        register_unprojection<UnprojectMethod::Lut>(name);
        benchmark::RegisterBenchmark(("Project/" + name + "/double").c_str(), Project<double>, name)->Apply(on_threads);
        benchmark::RegisterBenchmark(("Project/" + name + "/float").c_str(), Project<float>, name)->Apply(on_threads);
    }
    benchmark::RegisterBenchmark("UnprojectInterleaved/wide/exact/double", UnprojectInterleaved<UnprojectMethod::Exact>, "wide")
        ->Apply(on_threads);
    benchmark::RegisterBenchmark("UnprojectInterleaved/wide/fast/double", UnprojectInterleaved<UnprojectMethod::Fast>, "wide")
        ->Apply(on_threads);
    benchmark::RegisterBenchmark("CameraUnproject/wide", CameraUnproject)->UseRealTime();
    for (const int byte : {0, 0x3f}) {
        const std::string bytes = byte == 0 ? "/zeros" : "/non-zero";
        benchmark::RegisterBenchmark(("ImageMemset/double" + bytes).c_str(), ImageMemset<double>, byte)->UseRealTime();
        benchmark::RegisterBenchmark(("ImageMemset/float" + bytes).c_str(), ImageMemset<float>, byte)->UseRealTime();
    }
    register_image_rays<UnprojectMethod::Exact>("pinhole", "wide", LensType::Pinhole);
    register_image_rays<UnprojectMethod::Exact>("opencv8", "wide", LensType::OpenCv8);
    register_image_rays<UnprojectMethod::Fast>("opencv8", "wide", LensType::OpenCv8);
    register_image_rays<UnprojectMethod::Lut>("opencv8", "wide", LensType::OpenCv8);
    register_image_rays<UnprojectMethod::Exact>("fisheye", "fisheye", LensType::Fisheye);
}

}  // namespace

int main(int argc, char** argv) {
    register_benchmarks();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
