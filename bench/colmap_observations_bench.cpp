// Times reading a COLMAP model's observations and reprojecting them, to set beside
// `colmap model_analyzer --path MODEL` on the same model (bench/make_colmap_model.py writes
// a large one):
//
//   libcam_colmap_bench MODEL [REPEATS] [THREADS]
//
// Prints the best and median wall time of each step over REPEATS runs (default 5), and
// the counts and recomputed mean, so that a run on a wrong model shows.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/io/observations.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

void print_times(const char* step, std::vector<double> times) {
    std::sort(times.begin(), times.end());
    std::printf("%-22s best %.3f s, median %.3f s\n", step, times.front(), times[times.size() / 2]);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s MODEL [REPEATS] [THREADS]\n", argv[0]);
        return 2;
    }
    const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
    const int threads = argc > 3 ? std::max(1, std::atoi(argv[3])) : 1;
    std::vector<double> read_times, reproject_times, total_times;
    try {
        for (int i = 0; i < repeats; ++i) {
            const Clock::time_point start = Clock::now();
            const libcam::ObservationSet set = libcam::read_observations(argv[1]);
            read_times.push_back(seconds_since(start));
            const Clock::time_point projected = Clock::now();
            const libcam::Reprojection r = libcam::reproject(set, threads);
            reproject_times.push_back(seconds_since(projected));
            total_times.push_back(seconds_since(start));
            if (i == 0) {
                std::printf("%zu views, %zu points, %zu observations, %zu counted, mean of point means %.6f px\n",
                            set.views.size(), set.points.size(), set.observations.size(), r.summary.all.stats.count,
                            r.summary.reported.empty() ? 0.0 : r.summary.reported[0].recomputed);
            }
        }
    } catch (const libcam::Error& error) {
        std::fprintf(stderr, "%s\n", error.what());
        return 1;
    }
    print_times("read_observations", read_times);
    print_times("reproject", reproject_times);
    print_times("read + reproject", total_times);
    return 0;
}
