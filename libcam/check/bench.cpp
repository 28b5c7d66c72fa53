#include "libcam/check/bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <functional>
#include <limits>
#include <optional>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>

#include "libcam/camera/projector.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/error.hpp"
#include "libcam/geometry/pixel_grid.hpp"
#include "libcam/interop/mrcal.hpp"
#include "libcam/interop/opencv.hpp"
#include "libcam/lens/lens_models.hpp"
#include "libcam/remap/remap_map.hpp"

namespace libcam {

namespace {

using Clock = std::chrono::steady_clock;

// What one candidate's last run produced, for its error statistics.
struct Outcome {
    std::vector<double> errors_px;  // one per point with a result
    std::size_t total = 0;          // points attempted
    // Maps only: the largest distance from libcam's exact double map where both give a
    // source, and the points where one gives a source and the other not.
    std::optional<double> max_from_exact_px;
    std::size_t defined_differently = 0;
};

struct Contender {
    BenchRow row;
    std::size_t points = 0;             // per run, for the time per point
    std::function<void()> run;          // the timed work
    std::function<Outcome()> outcome;   // read right after the last run; empty: no error statistics
};

// ---------------------------------------------------------------------------------
// Timing and statistics.

// The median time of the repetitions, by error_stats's nearest-rank rule.
double median_of(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    return nearest_rank_quantile(values, 0.5);
}

// Now, in seconds, by `clock` (BenchClock).
double seconds_now(BenchClock clock) {
    if (clock == BenchClock::ThreadCpu) {
        timespec now{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
        return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
    }
    return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

// Every candidate run once to warm up (page faults, caches), then `repeat` rounds in
// which each runs once, so that a slow spell of the machine spreads over all of them.
// Candidates share output buffers: each outcome is read right after its last run.
std::vector<BenchRow> measure(std::vector<Contender>& candidates, const BenchSettings& settings) {
    const int repeat = settings.repeat;
    for (Contender& c : candidates) c.run();
    std::vector<std::vector<double>> seconds(candidates.size());
    for (int round = 0; round < repeat; ++round) {
        for (std::size_t i = 0; i < candidates.size(); ++i) {
            Contender& c = candidates[i];
            const double start = seconds_now(settings.clock);
            c.run();
            seconds[i].push_back(seconds_now(settings.clock) - start);
            if (round + 1 == repeat && c.outcome) {
                const Outcome outcome = c.outcome();
                c.row.error = error_stats(outcome.errors_px);
                c.row.invalid_fraction =
                    outcome.total ? 1.0 - static_cast<double>(outcome.errors_px.size()) / static_cast<double>(outcome.total) : 0.0;
                c.row.max_from_exact_px = outcome.max_from_exact_px;
                if (outcome.total) c.row.defined_differently = double(outcome.defined_differently) / double(outcome.total);
            }
        }
    }
    std::vector<BenchRow> rows;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        candidates[i].row.ns_per_point = median_of(seconds[i]) * 1e9 / static_cast<double>(std::max<std::size_t>(candidates[i].points, 1));
        rows.push_back(candidates[i].row);
    }
    return rows;
}

// ---------------------------------------------------------------------------------
// The points: a grid of pixels, and the rays through them.

// Camera points for the projection rows: the rays of the grid's pixels that have one,
// by the full solver in long double, and the pixel each came from.
struct RayPoints {
    std::vector<Vec3> points;
    std::vector<Vec2> pixels;
};

RayPoints rays_of(const Camera& camera, const std::vector<Vec2>& grid) {
    RayPoints out;
    visit_lens_model<long double>(camera.lens.type, [&]<class Model>() {
        const auto lens = Model::parameters(camera.lens.coefficients);
        for (const Vec2& pixel : grid) {
            const Eigen::Matrix<long double, 2, 1> m =
                camera.intrinsics.normalized_from_pixel(Eigen::Matrix<long double, 2, 1>(pixel.cast<long double>()));
            Eigen::Matrix<long double, 3, 1> ray;
            if (!Model::unproject(lens, m, ray)) continue;
            out.points.push_back(ray.cast<double>());
            out.pixels.push_back(pixel);
        }
    });
    return out;
}

// How far each direction's projection (libcam's, which the tests check against OpenCV
// and mrcal) lands from its pixel; a direction flagged, not finite or outside the lens's
// domain counts as no result.
Outcome reprojection_outcome(const Camera& camera, const std::vector<Vec2>& pixels, const std::vector<Vec3>& directions,
                             const std::vector<char>& has_result) {
    std::vector<Vec3> usable(directions.size(), Vec3::UnitZ());
    for (std::size_t i = 0; i < directions.size(); ++i) {
        if (has_result[i] && directions[i].allFinite()) usable[i] = directions[i];
    }
    const std::vector<Projection> projected = PreparedCamera(camera).project_camera_points(usable);
    Outcome outcome;
    outcome.total = pixels.size();
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        if (has_result[i] && directions[i].allFinite() && projected[i].valid) {
            outcome.errors_px.push_back((projected[i].pixel - pixels[i]).norm());
        }
    }
    return outcome;
}

Outcome pixel_outcome(const std::vector<Vec2>& expected, const std::vector<Vec2>& pixels, const std::vector<char>& has_result) {
    Outcome outcome;
    outcome.total = expected.size();
    for (std::size_t i = 0; i < expected.size(); ++i) {
        if (has_result[i] && pixels[i].allFinite()) outcome.errors_px.push_back((pixels[i] - expected[i]).norm());
    }
    return outcome;
}

// The pixels as the scalar type holds them: the float rows are measured against the
// pixel they were given (the grid rounded to float), not against a pixel they never saw.
template <class Scalar>
std::vector<Vec2> as_given(const Points2<Scalar>& pixels) {
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < pixels.size(); ++i) out.emplace_back(double(pixels.x[i]), double(pixels.y[i]));
    return out;
}

template <class Scalar>
std::vector<Vec3> as_vec3(const Points3<Scalar>& points) {
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < points.size(); ++i) out.emplace_back(double(points.x[i]), double(points.y[i]), double(points.z[i]));
    return out;
}

template <class Scalar>
const char* scalar_name() {
    return sizeof(Scalar) == sizeof(float) ? "float" : "double";
}

// Which reference library has the lens's model: the table says.
bool opencv_has(const Lens& lens) { return lens_info(lens.type).opencv != OpenCvFunction::None; }
bool mrcal_has(const Lens& lens) { return !lens_info(lens.type).mrcal.empty(); }

// ---------------------------------------------------------------------------------
// The candidates. Each builder adds its rows; the buffers they write live in the
// Workspace, which outlives the measurement.

struct Workspace {
    Points3<double> directions_double;  // the grid's rays
    Points3<float> directions_float;
    ValidFlags unprojected_valid;
    Points2<double> pixels_double;  // the rays' pixels
    std::vector<double> interleaved_pixels;
    std::vector<double> interleaved_directions;
    Points2<float> pixels_float;
    ValidFlags projected_valid;
    std::vector<Unprojection> unprojections;
    std::vector<Projection> projections;
    cv::Mat cv_unprojected, cv_projected;
    std::vector<double> mrcal_unprojected, mrcal_projected;
    Points3<double> frame_double;  // every pixel's ray
    Points3<float> frame_float;
    ValidFlags frame_valid;
    RemapMap map;     // the last libcam map built
    RemapMapFloat map_float;
    cv::Mat cv_map, cv_map_y;  // the last OpenCV map built: CV_32FC2, or x and y as CV_32F
};

// The camera measured, by name.
struct BenchCase {
    const std::string& name;
    const Camera& camera;
};

struct Setup {
    BenchCase bench_case;
    const BenchSettings& settings;
    std::string model;
    std::vector<Vec2> grid;
    RayPoints rays;
};

// What a libcam batch row runs with: each instruction set of BenchSettings::simd_targets
// at one thread, the one in use at more.
struct RunOn {
    int threads;
    SimdTarget instruction_set;
};

std::vector<RunOn> runs_of(const Setup& setup) {
    std::vector<RunOn> runs;
    for (int threads : setup.settings.threads) {
        if (threads == 1 && !setup.settings.simd_targets.empty()) {
            for (SimdTarget target : setup.settings.simd_targets) runs.push_back({threads, target});
        } else {
            runs.push_back({threads, simd_target()});
        }
    }
    return runs;
}

// Forces the row's instruction set for one timed call.
class SimdTargetFor {
public:
    explicit SimdTargetFor(SimdTarget target) { set_simd_target(target); }
    ~SimdTargetFor() { set_simd_target(std::nullopt); }
    SimdTargetFor(const SimdTargetFor&) = delete;
    SimdTargetFor& operator=(const SimdTargetFor&) = delete;
};

BenchRow row(const Setup& setup, const char* op, const char* library, std::string method, const char* scalar, int threads = 1) {
    BenchRow r;
    r.camera = setup.bench_case.name;
    r.op = op;
    r.library = library;
    r.method = std::move(method);
    r.scalar = scalar;
    r.model = setup.model;
    r.threads = threads;
    return r;
}

// A libcam batch row, run with `on`'s threads and instruction set.
BenchRow row(const Setup& setup, const char* op, std::string method, const char* scalar, const RunOn& on) {
    BenchRow r = row(setup, op, "libcam", std::move(method), scalar, on.threads);
    r.simd = simd_target_name(on.instruction_set);
    return r;
}

template <class Scalar>
void add_libcam_unprojection(std::vector<Contender>& out, const Setup& setup, const Unprojector<Scalar>& unprojector,
                             const Points2<Scalar>& pixels, Workspace& work, Points3<Scalar>& directions) {
    const std::vector<Vec2> given = as_given(pixels);
    for (UnprojectMethod method : kUnprojectMethods) {
        for (const RunOn on : runs_of(setup)) {
            Contender c{row(setup, "unproject", std::string(method_name(method)), scalar_name<Scalar>(), on),
                        pixels.size(), nullptr, nullptr};
            c.run = [&, method, on] {
                const SimdTargetFor forced(on.instruction_set);
                unprojector.unproject(pixels, method, directions, work.unprojected_valid, on.threads);
            };
            c.outcome = [&, given] {
                return reprojection_outcome(setup.bench_case.camera, given, as_vec3(directions),
                                            std::vector<char>(work.unprojected_valid.begin(), work.unprojected_valid.end()));
            };
            out.push_back(std::move(c));
        }
    }
}

// Unprojector::unproject_interleaved, exact: pixels and directions as numpy's (N, 2) and
// (N, 3) arrays (the Python module's layout).
void add_interleaved_unprojection(std::vector<Contender>& out, const Setup& setup, const Unprojector<double>& unprojector,
                                  const std::vector<double>& pixels, Workspace& work) {
    const std::size_t n = pixels.size() / 2;
    for (const RunOn on : runs_of(setup)) {
        Contender c{row(setup, "unproject", "interleaved-exact", "double", on), n, nullptr, nullptr};
        c.run = [&, on, n] {
            const SimdTargetFor forced(on.instruction_set);
            work.interleaved_directions.resize(3 * n);
            work.unprojected_valid.resize(n);
            unprojector.unproject_interleaved(pixels, UnprojectMethod::Exact, work.interleaved_directions,
                                              work.unprojected_valid, on.threads);
        };
        c.outcome = [&, n] {
            std::vector<Vec3> directions;
            for (std::size_t i = 0; i < n; ++i) {
                const double* d = work.interleaved_directions.data() + 3 * i;
                directions.emplace_back(d[0], d[1], d[2]);
            }
            return reprojection_outcome(setup.bench_case.camera, setup.grid, directions,
                                        std::vector<char>(work.unprojected_valid.begin(), work.unprojected_valid.end()));
        };
        out.push_back(std::move(c));
    }
}

// The public call: PreparedCamera::unproject on a list of pixels, as a user calls it
// (its engine built before timing, as the Unprojector rows' is).
void add_camera_unprojection(std::vector<Contender>& out, const Setup& setup, const PreparedCamera& camera,
                             Workspace& work) {
    work.unprojections.resize(setup.grid.size());  // reused by every run, as the other rows' outputs
    for (int threads : setup.settings.threads) {
        Contender c{row(setup, "unproject", "libcam", "camera", "double", threads), setup.grid.size(), nullptr, nullptr};
        c.row.simd = simd_target_name(simd_target());
        c.run = [&, threads] { camera.unproject(setup.grid, work.unprojections, threads); };
        c.outcome = [&] {
            std::vector<Vec3> directions;
            std::vector<char> valid;
            for (const Unprojection& u : work.unprojections) {
                directions.push_back(u.direction);
                valid.push_back(u.valid);
            }
            return reprojection_outcome(setup.bench_case.camera, setup.grid, directions, valid);
        };
        out.push_back(std::move(c));
    }
}

cv::Mat as_cv_points(const std::vector<Vec2>& pixels) {
    cv::Mat out(static_cast<int>(pixels.size()), 1, CV_64FC2);
    for (std::size_t i = 0; i < pixels.size(); ++i) out.at<cv::Vec2d>(static_cast<int>(i)) = {pixels[i].x(), pixels[i].y()};
    return out;
}

// cv::undistortPoints (cv::fisheye::undistortPoints for FISHEYE) at its default and at
// 100 iterations with eps 1e-14; cv::omnidir::undistortPoints (UCM, MEI) at its one fixed
// rule (20 iterations). Each gives (x, y) for the ray (x, y, 1).
void add_opencv_unprojection(std::vector<Contender>& out, const Setup& setup, const cv::Mat& cv_pixels, Workspace& work) {
    const Camera& camera = setup.bench_case.camera;
    if (!opencv_has(camera.lens)) return;
    const OpenCvCamera opencv(camera);
    const cv::TermCriteria many(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-14);
    const bool omnidir = opencv.function == OpenCvFunction::Omnidir;
    for (const bool iterate : {false, true}) {
        if (omnidir && iterate) continue;  // one fixed rule
        const char* rule = omnidir ? "20it" : iterate ? "100it-eps1e-14" : "default";
        Contender c{row(setup, "unproject", "opencv", rule, "double"), setup.grid.size(), nullptr, nullptr};
        const std::optional<cv::TermCriteria> criteria = iterate ? std::optional(many) : std::nullopt;
        c.run = [&, opencv, criteria] { opencv_undistort(opencv, cv_pixels, work.cv_unprojected, criteria); };
        c.outcome = [&] {
            std::vector<Vec3> directions;
            for (int i = 0; i < work.cv_unprojected.rows; ++i) {
                const cv::Vec2d m = work.cv_unprojected.at<cv::Vec2d>(i);
                directions.emplace_back(m[0], m[1], 1.0);
            }
            return reprojection_outcome(camera, setup.grid, directions, std::vector<char>(directions.size(), 1));
        };
        out.push_back(std::move(c));
    }
}

void add_mrcal_unprojection(std::vector<Contender>& out, const Setup& setup, const std::vector<double>& packed, Workspace& work) {
    const Camera& camera = setup.bench_case.camera;
    if (!mrcal_unprojects(camera.lens)) return;
    Contender c{row(setup, "unproject", "mrcal", "mrcal_unproject", "double"), setup.grid.size(), nullptr, nullptr};
    c.run = [&] {
        mrcal_unproject_packed(camera, packed, work.mrcal_unprojected);
    };
    c.outcome = [&] {
        std::vector<Vec3> directions;
        for (std::size_t i = 0; i < setup.grid.size(); ++i) {
            directions.emplace_back(work.mrcal_unprojected[3 * i], work.mrcal_unprojected[3 * i + 1],
                                    work.mrcal_unprojected[3 * i + 2]);
        }
        return reprojection_outcome(camera, setup.grid, directions, std::vector<char>(directions.size(), 1));
    };
    out.push_back(std::move(c));
}

template <class Scalar>
void add_libcam_projection(std::vector<Contender>& out, const Setup& setup, const Projector<Scalar>& projector,
                           const Points3<Scalar>& points, Workspace& work, Points2<Scalar>& pixels) {
    for (const RunOn on : runs_of(setup)) {
        Contender c{row(setup, "project", "batch", scalar_name<Scalar>(), on), points.size(), nullptr, nullptr};
        c.run = [&, on] {
            const SimdTargetFor forced(on.instruction_set);
            projector.project(points, pixels, work.projected_valid, on.threads);
        };
        c.outcome = [&] {
            return pixel_outcome(setup.rays.pixels, as_given(pixels),
                                 std::vector<char>(work.projected_valid.begin(), work.projected_valid.end()));
        };
        out.push_back(std::move(c));
    }
}

// Projector::project_interleaved: points and pixels as numpy's (N, 3) and (N, 2) arrays.
template <class Scalar>
void add_interleaved_projection(std::vector<Contender>& out, const Setup& setup, const Projector<Scalar>& projector,
                                const std::vector<Scalar>& points, Workspace& work, std::vector<Scalar>& pixels) {
    const std::size_t n = points.size() / 3;
    for (const RunOn on : runs_of(setup)) {
        Contender c{row(setup, "project", "interleaved", scalar_name<Scalar>(), on), n, nullptr, nullptr};
        c.run = [&, on, n] {
            const SimdTargetFor forced(on.instruction_set);
            pixels.resize(2 * n);
            work.projected_valid.resize(n);
            projector.project_interleaved(points, pixels, work.projected_valid, on.threads);
        };
        c.outcome = [&, n] {
            std::vector<Vec2> given;
            for (std::size_t i = 0; i < n; ++i) given.emplace_back(double(pixels[2 * i]), double(pixels[2 * i + 1]));
            return pixel_outcome(setup.rays.pixels, given,
                                 std::vector<char>(work.projected_valid.begin(), work.projected_valid.end()));
        };
        out.push_back(std::move(c));
    }
}

void add_camera_projection(std::vector<Contender>& out, const Setup& setup, const PreparedCamera& camera,
                           Workspace& work) {
    Contender c{row(setup, "project", "libcam", "camera", "double"), setup.rays.points.size(), nullptr, nullptr};
    c.row.simd = "scalar";  // one point at a time, no batch kernel
    c.run = [&] { work.projections = camera.project_camera_points(setup.rays.points); };
    c.outcome = [&] {
        std::vector<Vec2> pixels;
        std::vector<char> valid;
        for (const Projection& p : work.projections) {
            pixels.push_back(p.pixel);
            valid.push_back(p.valid);
        }
        return pixel_outcome(setup.rays.pixels, pixels, valid);
    };
    out.push_back(std::move(c));
}

void add_opencv_projection(std::vector<Contender>& out, const Setup& setup, const cv::Mat& cv_points, Workspace& work) {
    const Camera& camera = setup.bench_case.camera;
    if (!opencv_has(camera.lens)) return;
    const OpenCvCamera opencv(camera);
    const char* name = opencv.function == OpenCvFunction::Omnidir   ? "omnidir::projectPoints"
                       : opencv.function == OpenCvFunction::Fisheye ? "fisheye::projectPoints"
                                                                    : "projectPoints";
    Contender c{row(setup, "project", "opencv", name, "double"), setup.rays.points.size(), nullptr, nullptr};
    c.run = [&, opencv] { opencv_project(opencv, cv_points, work.cv_projected); };
    c.outcome = [&] {
        std::vector<Vec2> pixels;
        for (int i = 0; i < work.cv_projected.rows; ++i) {
            const cv::Vec2d q = work.cv_projected.at<cv::Vec2d>(i);
            pixels.emplace_back(q[0], q[1]);
        }
        return pixel_outcome(setup.rays.pixels, pixels, std::vector<char>(pixels.size(), 1));
    };
    out.push_back(std::move(c));
}

void add_mrcal_projection(std::vector<Contender>& out, const Setup& setup, const std::vector<double>& packed, Workspace& work) {
    const Camera& camera = setup.bench_case.camera;
    if (!mrcal_has(camera.lens)) return;
    const std::size_t n = setup.rays.points.size();
    Contender c{row(setup, "project", "mrcal", "mrcal_project", "double"), n, nullptr, nullptr};
    c.run = [&] { mrcal_project_packed(camera, packed, work.mrcal_projected); };
    c.outcome = [&, n] {
        std::vector<Vec2> pixels;
        for (std::size_t i = 0; i < n; ++i) pixels.emplace_back(work.mrcal_projected[2 * i], work.mrcal_projected[2 * i + 1]);
        return pixel_outcome(setup.rays.pixels, pixels, std::vector<char>(n, 1));
    };
    out.push_back(std::move(c));
}


// Every pixel's ray (unproject_image), and the time to write the same bytes once.
template <class Scalar>
void add_full_frame(std::vector<Contender>& out, const Setup& setup, const Unprojector<Scalar>& unprojector,
                    Points3<Scalar>& directions, ValidFlags& valid) {
    const Camera& camera = unprojector.camera();
    const std::size_t width = static_cast<std::size_t>(camera.size.width);
    const std::size_t n = width * static_cast<std::size_t>(camera.size.height);
    const bool closed_form = unprojector.table().step == 0;
    const std::string model(lens_info(camera.lens.type).name);
    for (UnprojectMethod method : kUnprojectMethods) {
        if (closed_form && method != UnprojectMethod::Exact) continue;  // one closed form for every method
        for (const RunOn on : runs_of(setup)) {
            Contender c{row(setup, "rays_full_frame", closed_form ? "closed-form" : std::string(method_name(method)),
                            scalar_name<Scalar>(), on),
                        n, nullptr, nullptr};
            c.row.model = model;
            c.run = [&, method, on] {
                const SimdTargetFor forced(on.instruction_set);
                unprojector.unproject_image(method, directions, valid, on.threads);
            };
            // The accuracy on a sample of about 100,000 pixels spread over the frame.
            c.outcome = [&, width, n] {
                const std::size_t stride = std::max<std::size_t>(1, n / 100'000) | 1;  // odd: not aligned with rows
                std::vector<Vec2> pixels;
                std::vector<Vec3> rays;
                std::vector<char> has_result;
                for (std::size_t k = 0; k < n; k += stride) {
                    pixels.emplace_back(double(k % width), double(k / width));
                    rays.emplace_back(double(directions.x[k]), double(directions.y[k]), double(directions.z[k]));
                    has_result.push_back(valid[k]);
                }
                return reprojection_outcome(camera, pixels, rays, has_result);
            };
            out.push_back(std::move(c));
        }
    }
}

// The time to write the bytes of a frame's rays once: memset of the three coordinate
// arrays and the flags. Twice: with zeros, and with a byte that is not zero, as the rays'
// bytes are not (z is 1, every flag 1). On the machine of the README zeros are written
// 2.4 times as fast as any other byte, which would make zeros no reference for them.
template <class Scalar>
void add_memset(std::vector<Contender>& out, const Setup& setup, std::size_t n, Points3<Scalar>& directions,
                ValidFlags& valid) {
    for (const int byte : {0, 0x3f}) {
        Contender c{row(setup, "rays_full_frame", "memset", byte == 0 ? "zeros" : "non-zero-bytes", scalar_name<Scalar>()), n,
                    nullptr, nullptr};
        c.row.model = "-";
        c.run = [&, n, byte] {
            directions.resize(n);
            valid.resize(n);
            for (std::vector<Scalar>* v : {&directions.x, &directions.y, &directions.z}) std::memset(v->data(), byte, n * sizeof(Scalar));
            std::memset(valid.data(), byte, n);
        };
        out.push_back(std::move(c));
    }
}

std::vector<double> packed_pixels(const std::vector<Vec2>& pixels) {
    std::vector<double> out;
    for (const Vec2& p : pixels) out.insert(out.end(), {p.x(), p.y()});
    return out;
}

std::vector<double> packed_points(const std::vector<Vec3>& points) {
    std::vector<double> out;
    for (const Vec3& p : points) out.insert(out.end(), {p.x(), p.y(), p.z()});
    return out;
}

cv::Mat as_cv_points3(const std::vector<Vec3>& points) {
    cv::Mat out(static_cast<int>(points.size()), 1, CV_64FC3);
    for (std::size_t i = 0; i < points.size(); ++i) {
        out.at<cv::Vec3d>(static_cast<int>(i)) = {points[i].x(), points[i].y(), points[i].z()};
    }
    return out;
}

// Sets OpenCV's thread count for its lifetime, and restores the caller's after.
class OpenCvThreads {
public:
    explicit OpenCvThreads(int threads) : previous_(cv::getNumThreads()) { cv::setNumThreads(threads); }
    ~OpenCvThreads() { cv::setNumThreads(previous_); }
    OpenCvThreads(const OpenCvThreads&) = delete;
    OpenCvThreads& operator=(const OpenCvThreads&) = delete;

private:
    int previous_;
};

template <class T>
double milliseconds_to_build(std::optional<T>& target, const Camera& camera) {
    const Clock::time_point start = Clock::now();
    target.emplace(camera);
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The grid's rows: unprojection and projection by every library.
std::vector<BenchRow> grid_rows(const Setup& setup, const Unprojector<double>& unprojector_double,
                                const Unprojector<float>& unprojector_float, Workspace& work) {
    const Camera& camera = setup.bench_case.camera;
    const Points2<double> pixels_double = as_points2<double>(setup.grid);
    const Points2<float> pixels_float = as_points2<float>(setup.grid);
    const cv::Mat cv_pixels = as_cv_points(setup.grid);
    const std::vector<double> mrcal_pixels = packed_pixels(setup.grid);
    const Points3<double> points_double = as_points3<double>(setup.rays.points);
    const Points3<float> points_float = as_points3<float>(setup.rays.points);
    const cv::Mat cv_points = as_cv_points3(setup.rays.points);
    const std::vector<double> mrcal_points = packed_points(setup.rays.points);
    const std::vector<double>& interleaved_points = mrcal_points;  // x, y, z per point, as mrcal takes them
    work.mrcal_unprojected.resize(3 * setup.grid.size());
    work.mrcal_projected.resize(2 * setup.rays.points.size());
    const PreparedCamera prepared(camera);
    prepared.unprojector();  // built before timing
    const Projector<double> projector_double(prepared);
    const Projector<float> projector_float(prepared);

    std::vector<Contender> candidates;
    add_libcam_unprojection(candidates, setup, unprojector_double, pixels_double, work, work.directions_double);
    add_libcam_unprojection(candidates, setup, unprojector_float, pixels_float, work, work.directions_float);
    add_interleaved_unprojection(candidates, setup, unprojector_double, mrcal_pixels, work);  // x, y per pixel
    add_camera_unprojection(candidates, setup, prepared, work);
    add_opencv_unprojection(candidates, setup, cv_pixels, work);
    add_mrcal_unprojection(candidates, setup, mrcal_pixels, work);
    add_libcam_projection(candidates, setup, projector_double, points_double, work, work.pixels_double);
    add_libcam_projection(candidates, setup, projector_float, points_float, work, work.pixels_float);
    add_interleaved_projection(candidates, setup, projector_double, interleaved_points, work, work.interleaved_pixels);
    add_camera_projection(candidates, setup, prepared, work);
    add_opencv_projection(candidates, setup, cv_points, work);
    add_mrcal_projection(candidates, setup, mrcal_points, work);
    return measure(candidates, setup.settings);
}

// Every pixel's ray through the lens and through a pinhole with the same K.
std::vector<BenchRow> full_frame_rows(const Setup& setup, const Unprojector<double>& unprojector_double,
                                      const Unprojector<float>& unprojector_float, Workspace& work) {
    Camera pinhole = setup.bench_case.camera;
    pinhole.lens = Lens{};
    const Unprojector<double> pinhole_double(pinhole);
    const Unprojector<float> pinhole_float(pinhole);
    const std::size_t n = static_cast<std::size_t>(pinhole.size.width) * static_cast<std::size_t>(pinhole.size.height);
    std::vector<Contender> candidates;
    add_full_frame(candidates, setup, pinhole_double, work.frame_double, work.frame_valid);
    add_memset(candidates, setup, n, work.frame_double, work.frame_valid);
    add_full_frame(candidates, setup, pinhole_float, work.frame_float, work.frame_valid);
    add_memset(candidates, setup, n, work.frame_float, work.frame_valid);
    add_full_frame(candidates, setup, unprojector_double, work.frame_double, work.frame_valid);
    add_full_frame(candidates, setup, unprojector_float, work.frame_float, work.frame_valid);
    return measure(candidates, setup.settings);
}

// ---------------------------------------------------------------------------------
// Remap maps: every pixel of a target image and the source pixel that sees its ray.

// "32FC2" or "32F x2": how an OpenCV map of `type` holds a pixel's two coordinates.
std::string opencv_map_type_name(int type) { return type == CV_32FC2 ? "32FC2" : "32F x2"; }

// The target pixels a map is measured on: about 100,000, every stride-th of the image.
struct MapSample {
    std::size_t n = 0, width = 0, stride = 1;
    std::vector<std::size_t> indices;
};

MapSample map_sample(const ImageSize& size) {
    MapSample sample;
    sample.width = static_cast<std::size_t>(size.width);
    sample.n = sample.width * static_cast<std::size_t>(size.height);
    sample.stride = std::max<std::size_t>(1, sample.n / 100'000) | 1;  // odd: not aligned with rows
    for (std::size_t k = 0; k < sample.n; k += sample.stride) sample.indices.push_back(k);
    return sample;
}

// One direction of the maps: target and source, and libcam's exact double map at the
// sample, the reference the other maps are compared with (NaN: no source).
struct MapDirection {
    const PreparedCamera& target;
    const PreparedCamera& source;
    bool inverse;
    std::vector<Vec2> exact;
};

std::vector<Vec2> exact_at_sample(const MapDirection& direction, const MapSample& sample) {
    RemapOptions options;
    options.threads = 2;
    const RemapMap map = build_remap_map(direction.target, direction.source, options);
    std::vector<Vec2> exact;
    for (std::size_t k : sample.indices) exact.emplace_back(map.x[k], map.y[k]);
    return exact;
}

// How far each sampled target pixel is sent back by the source pixel its map gives: the
// source pixel unprojected (exact) and projected by the target, against the target
// pixel; a pixel without a source, or with one off the source image, counts as no
// result. And how far the map is from libcam's exact double map where both give a
// source, and at how many sampled pixels one gives a source and the other not.
template <class SourceOf>
Outcome map_outcome(const MapDirection& direction, const MapSample& sample, SourceOf source_of) {
    std::vector<Vec2> targets, sources;
    Outcome outcome;
    outcome.total = sample.indices.size();
    outcome.max_from_exact_px = 0;
    for (std::size_t i = 0; i < sample.indices.size(); ++i) {
        const std::size_t k = sample.indices[i];
        const Vec2 at = source_of(k);
        const bool has = at.allFinite() && on_image(at.x(), at.y(), direction.source.camera().size);
        const bool exact_has = direction.exact[i].allFinite();
        if (has != exact_has) ++outcome.defined_differently;
        if (has && exact_has) outcome.max_from_exact_px = std::max(*outcome.max_from_exact_px, (at - direction.exact[i]).norm());
        if (!has) continue;
        targets.emplace_back(double(k % sample.width), double(k / sample.width));
        sources.push_back(at);
    }
    const std::vector<Unprojection> rays = direction.source.unproject(sources);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (!rays[i].valid) continue;
        const Projection back = direction.target.project_camera_point(rays[i].direction);
        if (back.valid) outcome.errors_px.push_back((back.pixel - targets[i]).norm());
    }
    return outcome;
}

// libcam's map in Scalar for one direction, each method (a PINHOLE target's rays are the
// same for both: the undistorting direction has exact only), each allocated afresh as a
// user's first call would.
template <class Scalar>
void add_libcam_maps(std::vector<Contender>& out, const Setup& setup, const MapDirection& direction,
                     const MapSample& sample, BasicRemapMap<Scalar>& map) {
    const auto source_of = [&map](std::size_t k) { return Vec2(double(map.x[k]), double(map.y[k])); };
    for (UnprojectMethod method : {UnprojectMethod::Exact, UnprojectMethod::Fast}) {
        if (!direction.inverse && method != UnprojectMethod::Exact) continue;
        for (const RunOn on : runs_of(setup)) {
            const std::string name = std::string(direction.inverse ? "inverse-" : "") + std::string(method_name(method));
            Contender c{row(setup, "map", name, scalar_name<Scalar>(), on), sample.n, nullptr, nullptr};
            c.run = [&, method, on] {
                const SimdTargetFor forced(on.instruction_set);
                RemapOptions options;
                options.method = method;
                options.threads = on.threads;
                map = BasicRemapMap<Scalar>();  // freed first, as OpenCV's rows free theirs
                map = build_remap_map<Scalar>(direction.target, direction.source, options);
            };
            c.outcome = [&, source_of] { return map_outcome(direction, sample, source_of); };
            out.push_back(std::move(c));
        }
    }
}

// OpenCV's maps for the lenses OpenCV has them for: the undistortion map as one CV_32FC2
// and as two CV_32F maps (cv::fisheye's takes no CV_32FC2), the distortion map
// (initInverseRectificationMap) for the projectPoints models. OpenCV runs on as many
// threads as libcam in the same row.
void add_opencv_maps(std::vector<Contender>& out, const Setup& setup, const MapDirection& undistort,
                     const MapDirection& distort, const MapSample& sample, Workspace& work) {
    const Camera& camera = setup.bench_case.camera;
    const OpenCvFunction function = lens_info(camera.lens.type).opencv;
    if (function != OpenCvFunction::ProjectPoints && function != OpenCvFunction::Fisheye) return;
    const cv::Mat K = opencv_camera_matrix(camera.intrinsics);
    const cv::Mat D = opencv_distortion(camera.lens);
    const cv::Size size(static_cast<int>(camera.size.width), static_cast<int>(camera.size.height));
    struct OpenCvMap {
        std::string name;
        const MapDirection& direction;
        std::function<void()> build;
    };
    const auto fresh = [&work] {
        work.cv_map = cv::Mat();
        work.cv_map_y = cv::Mat();
    };
    std::vector<OpenCvMap> maps;
    if (function == OpenCvFunction::ProjectPoints) {
        for (const int type : {CV_32FC2, CV_32FC1}) {
            maps.push_back({std::string("initUndistortRectifyMap ") + opencv_map_type_name(type), undistort, [&work, fresh, K, D, size, type] {
                                fresh();
                                cv::initUndistortRectifyMap(K, D, cv::noArray(), K, size, type, work.cv_map,
                                                            type == CV_32FC2 ? cv::_OutputArray(cv::noArray()) : work.cv_map_y);
                            }});
        }
        maps.push_back({"initInverseRectificationMap 32FC2", distort, [&work, fresh, K, D, size] {
                            fresh();
                            cv::initInverseRectificationMap(K, D, cv::noArray(), K, size, CV_32FC2, work.cv_map, cv::noArray());
                        }});
    } else {
        maps.push_back({"fisheye::initUndistortRectifyMap 32F x2", undistort, [&work, fresh, K, D, size] {
                            fresh();
                            cv::fisheye::initUndistortRectifyMap(K, D, cv::Matx33d::eye(), K, size, CV_32F, work.cv_map,
                                                                 work.cv_map_y);
                        }});
    }
    const auto opencv_source = [&work](std::size_t k) {
        const int i = static_cast<int>(k);
        if (work.cv_map_y.empty()) return Vec2(work.cv_map.at<cv::Vec2f>(i)[0], work.cv_map.at<cv::Vec2f>(i)[1]);
        return Vec2(work.cv_map.at<float>(i), work.cv_map_y.at<float>(i));
    };
    for (const OpenCvMap& map : maps) {
        for (int threads : setup.settings.threads) {
            Contender c{row(setup, "map", "opencv", map.name, "float", threads), sample.n, nullptr, nullptr};
            c.run = [build = map.build, threads] {
                const OpenCvThreads using_threads(threads);
                build();
            };
            c.outcome = [&, opencv_source, direction = &map.direction] {
                // The map as one row of n pixels, whatever shape OpenCV gave it.
                work.cv_map = work.cv_map.reshape(0, 1);
                if (!work.cv_map_y.empty()) work.cv_map_y = work.cv_map_y.reshape(0, 1);
                return map_outcome(*direction, sample, opencv_source);
            };
            out.push_back(std::move(c));
        }
    }
}

// Each map row's time over that of OpenCV's undistortion map (CV_32FC2, or cv::fisheye's
// two CV_32F maps) at the same thread count.
void set_map_ratios(std::vector<BenchRow>& rows) {
    for (BenchRow& r : rows) {
        const auto reference = std::find_if(rows.begin(), rows.end(), [&](const BenchRow& o) {
            return o.library == "opencv" && o.threads == r.threads &&
                   (o.method == "initUndistortRectifyMap 32FC2" || o.method == "fisheye::initUndistortRectifyMap 32F x2");
        });
        if (reference != rows.end()) r.ratio = r.ns_per_point / reference->ns_per_point;
    }
}

// The maps between the lens and a pinhole with the same K and size, both ways.
std::vector<BenchRow> map_rows(const Setup& setup, Workspace& work) {
    Camera pinhole = setup.bench_case.camera;
    pinhole.lens = Lens{};
    const PreparedCamera lens(setup.bench_case.camera);
    const PreparedCamera prepared_pinhole(pinhole);
    lens.unprojector();  // tables built before timing, as in the other rows
    prepared_pinhole.unprojector();
    const MapSample sample = map_sample(setup.bench_case.camera.size);
    MapDirection undistort{prepared_pinhole, lens, false, {}};
    MapDirection distort{lens, prepared_pinhole, true, {}};
    undistort.exact = exact_at_sample(undistort, sample);
    distort.exact = exact_at_sample(distort, sample);
    std::vector<Contender> candidates;
    for (const MapDirection* direction : {&undistort, &distort}) {
        add_libcam_maps(candidates, setup, *direction, sample, work.map);
        add_libcam_maps(candidates, setup, *direction, sample, work.map_float);
    }
    add_opencv_maps(candidates, setup, undistort, distort, sample, work);
    std::vector<BenchRow> rows = measure(candidates, setup.settings);
    set_map_ratios(rows);
    work.map = RemapMap();
    work.map_float = RemapMapFloat();
    work.cv_map.release();
    work.cv_map_y.release();
    return rows;
}

}  // namespace

BenchResult run_bench(const std::string& name, const Camera& camera, const BenchSettings& settings) {
    camera.validate();
    const bool threads_one = std::all_of(settings.threads.begin(), settings.threads.end(), [](int t) { return t == 1; });
    if (settings.clock == BenchClock::ThreadCpu && !threads_one) {
        throw InvalidArgument("bench clock: a thread's CPU time measures one-thread rows only, not rows on more threads");
    }
    const PixelGrid grid_shape{settings.grid_x, settings.grid_y};
    grid_shape.validate("bench grid");
    const BenchCase bench_case{name, camera};
    // The map rows need no grid: their pixels are every pixel of the image.
    const std::vector<Vec2> grid = settings.maps ? std::vector<Vec2>{} : grid_shape.pixels(camera.size);
    const Setup setup{bench_case, settings, std::string(lens_info(camera.lens.type).name), grid, rays_of(camera, grid)};
    BenchResult result;
    std::optional<Unprojector<double>> unprojector_double;
    std::optional<Unprojector<float>> unprojector_float;
    result.table_build_ms_double = milliseconds_to_build(unprojector_double, camera);
    result.table_build_ms_float = milliseconds_to_build(unprojector_float, camera);
    Workspace work;
    // OpenCV's rows run on one thread, like libcam's 1-thread rows.
    const OpenCvThreads one_thread(1);
    if (settings.maps) {
        result.rows = map_rows(setup, work);
        return result;
    }
    result.rows = grid_rows(setup, *unprojector_double, *unprojector_float, work);
    if (settings.full_frame) {
        std::vector<BenchRow> frame = full_frame_rows(setup, *unprojector_double, *unprojector_float, work);
        result.rows.insert(result.rows.end(), frame.begin(), frame.end());
    }
    return result;
}

}  // namespace libcam
