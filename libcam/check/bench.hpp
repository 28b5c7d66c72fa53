#pragma once
// `libcam bench`: the time per point and the accuracy of every way libcam, OpenCV and
// mrcal project and unproject, measured on the same pixels in one process.
//
// The pixels are a PixelGrid over the image (geometry/pixel_grid.hpp). The error of a
// result is the distance in pixels from its pixel to the projection of the result by
// libcam (which the tests check against OpenCV and mrcal); its statistics are
// stats/error_stats.hpp's.

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/camera/simd.hpp"
#include "libcam/stats/error_stats.hpp"

namespace libcam {

struct BenchRow {
    std::string camera;   // the camera's name
    std::string op;       // "unproject", "project", "rays_full_frame", "map"
    std::string library;  // "libcam", "opencv", "mrcal", "memset"
    std::string method;
    std::string scalar;  // "double", "float"
    std::string model;   // the lens model, e.g. "OPENCV8"
    int threads = 1;
    std::string simd = "-";           // the instruction set of libcam's batch kernels (camera/simd.hpp)
    double ns_per_point = 0;          // median over the repetitions
    std::optional<ErrorStats> error;  // none for the memset reference; count 0 when no point had a result
    double invalid_fraction = 0;      // points flagged, not finite, or whose ray cannot be projected back
    // Maps only: the time over OpenCV's undistortion map's (CV_32FC2; cv::fisheye's two
    // CV_32F maps) at the same thread count (NaN: no such OpenCV row); the largest distance
    // from libcam's exact double map where both give a source; the fraction of pixels
    // where one gives a source and the other not.
    double ratio = std::numeric_limits<double>::quiet_NaN();
    std::optional<double> max_from_exact_px;
    double defined_differently = 0;
};

// How each repetition is timed: by the wall clock, or by the CPU time of the thread that
// runs it, which other programs running on a busy machine do not lengthen (a call of a few
// milliseconds that waits one turn of the scheduler looks several times slower by the
// wall clock). The CPU time measures one-thread rows only: every row then runs on the
// calling thread (libcam's at one thread, OpenCV's set to one, mrcal's).
enum class BenchClock { Wall, ThreadCpu };

struct BenchSettings {
    int grid_x = 601, grid_y = 401;  // pixels across and down, corners included (each >= 2)
    int repeat = 5;                  // timed repetitions, interleaved across the candidates
    std::vector<int> threads{1, 2};  // thread counts for libcam's batch paths
    // The instruction sets libcam's batch rows run with at one thread, each forced in turn;
    // empty: the one in use (simd_target()). Rows at more threads use the one in use.
    std::vector<SimdTarget> simd_targets;
    bool full_frame = false;         // also every pixel's ray, and the memset reference
    // Instead of the rows above, the remap maps between the lens and a pinhole with its K
    // and size, both ways, and OpenCV's: every pixel of the image, no grid.
    bool maps = false;
    BenchClock clock = BenchClock::Wall;  // ThreadCpu needs threads == {1}
};

struct BenchResult {
    std::vector<BenchRow> rows;
    double table_build_ms_double = 0, table_build_ms_float = 0;  // Unprojector construction
};

// Measures every method on `camera`; `name` labels its rows. Throws InvalidArgument for
// the thread's CPU time with more than one thread.
BenchResult run_bench(const std::string& name, const Camera& camera, const BenchSettings& settings);

}  // namespace libcam
