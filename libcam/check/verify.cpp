#include "libcam/check/verify.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <utility>

#include "libcam/camera/parallel.hpp"
#include "libcam/error.hpp"
#include "libcam/geometry/pixel_grid.hpp"
#include "libcam/interop/mrcal.hpp"
#include "libcam/interop/opencv.hpp"

namespace libcam {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// libcam's own target for everything it computes.
constexpr double kExactPx = 1e-9;
// mrcal_unproject stops its solver short of full precision (1.9e-8 px measured on a
// real wide lens, 6016x4016 OPENCV8), so libcam is held to agree with it to this much.
constexpr double kMrcalAgreementPx = 1e-6;

constexpr std::string_view kCheckNames[] = {
    verify_check::project_opencv,           verify_check::project_mrcal,
    verify_check::unproject_libcam,         verify_check::unproject_libcam_opencv,
    verify_check::unproject_libcam_mrcal,   verify_check::unproject_mrcal,
    verify_check::mrcal_vs_libcam,          verify_check::undistort_opencv_default,
    verify_check::undistort_opencv_100,     verify_check::round_trip,
};

// ---------------------------------------------------------------------------------
// What every check runs on.

// The grid, libcam's ray through each pixel, and points at every depth along each ray
// with libcam's projection of them.
struct Samples {
    Samples(PreparedCamera prepared, int thread_count) : camera(std::move(prepared)), threads(thread_count) {}

    PreparedCamera camera;  // every libcam projection and unprojection goes through it
    int threads = 1;        // each library's calls are split over this many
    std::vector<Vec2> pixels;
    std::vector<Unprojection> rays;
    std::vector<std::size_t> with_ray;  // indices of the pixels libcam has a ray through
    std::vector<Vec3> points;
    std::vector<std::size_t> point_pixel;  // the grid pixel each point lies on
    std::vector<Projection> projected;     // libcam's projection of each point

    std::vector<Vec2> pixels_with_ray() const {
        std::vector<Vec2> out;
        for (std::size_t i : with_ray) out.push_back(pixels[i]);
        return out;
    }
    std::vector<Vec3> libcam_rays() const {
        std::vector<Vec3> out;
        for (std::size_t i : with_ray) out.push_back(rays[i].direction);
        return out;
    }
};

// f(part) for consecutive parts of `inputs`, on `threads` threads, concatenated: each
// library maps every point on its own, so the result is the same for any split.
template <class Output, class Input, class Map>
std::vector<Output> in_parts(int threads, const std::vector<Input>& inputs, Map map) {
    constexpr std::size_t kSmallestPart = 4096;
    std::vector<Output> outputs(inputs.size());
    parallel_chunks(inputs.size(), threads, kSmallestPart, [&](std::size_t begin, std::size_t end) {
        const std::vector<Input> part(inputs.begin() + static_cast<std::ptrdiff_t>(begin),
                                      inputs.begin() + static_cast<std::ptrdiff_t>(end));
        const std::vector<Output> mapped = map(part);
        std::copy(mapped.begin(), mapped.end(), outputs.begin() + static_cast<std::ptrdiff_t>(begin));
    });
    return outputs;
}

// libcam's projections of camera-frame points, on `threads` threads.
std::vector<Projection> libcam_projections(const PreparedCamera& camera, const std::vector<Vec3>& points, int threads) {
    return in_parts<Projection>(threads, points,
                                [&](const std::vector<Vec3>& part) { return camera.project_camera_points(part); });
}

Samples make_samples(const Camera& camera, const VerifyOptions& options) {
    Samples s(PreparedCamera(camera), worker_count(options.threads));
    s.pixels = PixelGrid{options.grid_columns, options.grid_rows}.pixels(camera.size);
    s.rays = s.camera.unproject(s.pixels, s.threads);
    s.with_ray.reserve(s.pixels.size());
    s.points.reserve(s.pixels.size() * options.depths.size());
    s.point_pixel.reserve(s.points.capacity());
    for (std::size_t i = 0; i < s.pixels.size(); ++i) {
        if (!s.rays[i].valid) continue;
        s.with_ray.push_back(i);
        const Vec3 unit = s.rays[i].direction.normalized();
        for (double depth : options.depths) {
            s.points.push_back(depth * unit);
            s.point_pixel.push_back(i);
        }
    }
    s.projected = libcam_projections(s.camera, s.points, s.threads);
    return s;
}

// ---------------------------------------------------------------------------------
// The libraries, on libcam's types.

// Why a library cannot check this camera (the table says which library has the model);
// nullopt when it can.
std::optional<std::string> opencv_lacks(const Camera& camera) {
    if (camera.intrinsics.skew != 0.0 && lens_info(camera.lens.type).opencv != OpenCvFunction::Omnidir) {
        return "cv::projectPoints and cv::undistortPoints ignore K's skew";
    }
    if (lens_info(camera.lens.type).opencv == OpenCvFunction::None) {
        return "lens: OpenCV has no model " + std::string(lens_info(camera.lens.type).name);
    }
    return std::nullopt;
}

std::optional<std::string> mrcal_lacks(const Camera& camera) {
    if (lens_info(camera.lens.type).mrcal.empty()) {
        return "lens: model " + std::string(lens_info(camera.lens.type).name) + " has no mrcal equivalent";
    }
    if (camera.intrinsics.skew != 0.0) {
        return "K: skew " + format_number(camera.intrinsics.skew) + " cannot be stored in mrcal's model (fx, fy, cx, cy only)";
    }
    return std::nullopt;
}

OpenCvFunction opencv_function(const Camera& camera) { return lens_info(camera.lens.type).opencv; }
bool is_fisheye(const Camera& camera) { return opencv_function(camera) == OpenCvFunction::Fisheye; }
bool is_omnidir(const Camera& camera) { return opencv_function(camera) == OpenCvFunction::Omnidir; }

std::string opencv_project_name(const Camera& camera) {
    if (is_omnidir(camera)) return "cv::omnidir::projectPoints";
    return is_fisheye(camera) ? "cv::fisheye::projectPoints" : "cv::projectPoints";
}

std::string opencv_undistort_name(const Camera& camera) {
    if (is_omnidir(camera)) return "cv::omnidir::undistortPoints";
    return is_fisheye(camera) ? "cv::fisheye::undistortPoints" : "cv::undistortPoints";
}

// Whether OpenCV's projection of a point libcam projects can be compared with libcam's:
// cv::projectPoints mirrors points behind the camera into the image and
// cv::fisheye::projectPoints folds them forward; cv::omnidir's unified model evaluates
// the same formula everywhere, and libcam's domain leaves out where it does not hold.
bool opencv_projects_as_libcam(const Camera& camera, const Vec3& point) {
    return is_omnidir(camera) || point.z() > 0.0;
}

// Whether OpenCV's undistortion can give a pixel's ray: each gives (x, y) for the ray
// (x, y, 1), which has no direction behind the camera.
bool opencv_undistorts_to(const Vec3& ray) { return ray.z() > 0.0; }

std::vector<Vec2> opencv_project(const Camera& camera, const std::vector<Vec3>& points, int threads) {
    return in_parts<Vec2>(threads, points, [&](const std::vector<Vec3>& part) { return opencv_project_points(camera, part); });
}

std::vector<Vec2> mrcal_project(const Camera& camera, const std::vector<Vec3>& points, int threads) {
    return in_parts<Vec2>(threads, points, [&](const std::vector<Vec3>& part) { return mrcal_project_points(camera, part); });
}

std::vector<Vec3> mrcal_unproject(const Camera& camera, const std::vector<Vec2>& pixels, int threads) {
    return in_parts<Vec3>(threads, pixels, [&](const std::vector<Vec2>& part) { return mrcal_unproject_pixels(camera, part); });
}

// Rays (x, y, 1) by cv::undistortPoints (cv::fisheye::undistortPoints for FISHEYE,
// cv::omnidir::undistortPoints for UCM and MEI: its fixed 20 iterations, no stopping rule
// to set), at the function's default stopping rule when `criteria` is empty.
std::vector<Vec3> opencv_undistort_part(const Camera& camera, const std::vector<Vec2>& pixels,
                                        const std::optional<cv::TermCriteria>& criteria) {
    if (pixels.empty()) return {};
    std::vector<cv::Point2d> in, out;
    for (const Vec2& p : pixels) in.emplace_back(p.x(), p.y());
    opencv_undistort(OpenCvCamera(camera), in, out, criteria);
    std::vector<Vec3> rays;
    for (const cv::Point2d& q : out) rays.emplace_back(q.x, q.y, 1.0);
    return rays;
}

std::vector<Vec3> opencv_undistort(const Camera& camera, const std::vector<Vec2>& pixels,
                                   const std::optional<cv::TermCriteria>& criteria, int threads) {
    return in_parts<Vec3>(threads, pixels,
                          [&](const std::vector<Vec2>& part) { return opencv_undistort_part(camera, part, criteria); });
}

// libcam's pixels of camera-frame points; NaN for a point outside the lens's domain.
std::vector<Vec2> libcam_project(const PreparedCamera& camera, const std::vector<Vec3>& points, int threads) {
    std::vector<Vec2> out;
    out.reserve(points.size());
    for (const Projection& p : libcam_projections(camera, points, threads)) {
        out.push_back(p.valid ? p.pixel : Vec2(kNaN, kNaN));
    }
    return out;
}

// ---------------------------------------------------------------------------------
// Errors and statistics.

// Errors as they are measured, with the grid pixel each belongs to.
class ErrorField {
public:
    explicit ErrorField(std::size_t pixel_count) : worst_(pixel_count, kNaN) {}

    // A NaN error (the library gave no finite answer) counts as infinitely wrong.
    void add(std::size_t pixel, double error_px) {
        if (std::isnan(error_px)) error_px = kInf;
        samples_.push_back(error_px);
        worst_[pixel] = std::isnan(worst_[pixel]) ? error_px : std::max(worst_[pixel], error_px);
    }

    VerifyCheck finish(VerifyCheck check) && {
        check.stats = error_stats(std::move(samples_));
        check.pixel_error_px = std::move(worst_);
        return check;
    }

private:
    std::vector<double> samples_;
    std::vector<double> worst_;
};

VerifyCheck new_check(std::string_view name, std::string library, std::optional<double> tolerance_px) {
    VerifyCheck check;
    check.name = std::string(name);
    check.library = std::move(library);
    check.tolerance_px = tolerance_px;
    return check;
}

VerifyCheck skip(VerifyCheck check, const std::string& why) {
    check.skipped_because = why;
    return check;
}

// "3 points behind the camera not compared"; empty when the count is zero.
std::string count_note(std::size_t count, const std::string& what) {
    return count == 0 ? std::string() : std::to_string(count) + " " + what;
}

// |reprojected - pixel| per pixel.
ErrorField reprojection_errors(std::size_t pixel_count, const std::vector<std::size_t>& pixel_index,
                               const std::vector<Vec2>& pixels, const std::vector<Vec2>& reprojected) {
    ErrorField errors(pixel_count);
    for (std::size_t k = 0; k < pixel_index.size(); ++k) {
        errors.add(pixel_index[k], (reprojected[k] - pixels[k]).norm());
    }
    return errors;
}

// ---------------------------------------------------------------------------------
// The checks.

// libcam's projection of the sample points against another library's, on the points
// `compare` accepts.
template <class Accept, class Project>
VerifyCheck compare_projection(VerifyCheck check, const Samples& s, Accept compare, Project project_theirs,
                               const std::string& left_out) {
    std::vector<std::size_t> compared;
    std::vector<Vec3> points;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        if (!s.projected[i].valid || !compare(s.points[i])) continue;
        compared.push_back(i);
        points.push_back(s.points[i]);
    }
    const std::vector<Vec2> theirs = project_theirs(points);
    ErrorField errors(s.pixels.size());
    for (std::size_t k = 0; k < compared.size(); ++k) {
        errors.add(s.point_pixel[compared[k]], (theirs[k] - s.projected[compared[k]].pixel).norm());
    }
    check.note = count_note(s.points.size() - compared.size(), "points not compared (" + left_out + ")");
    return std::move(errors).finish(std::move(check));
}

VerifyCheck check_project_opencv(const Camera& camera, const Samples& s, const std::optional<std::string>& lacks) {
    VerifyCheck check = new_check(verify_check::project_opencv, opencv_project_name(camera), kExactPx);
    if (lacks) return skip(std::move(check), *lacks);
    return compare_projection(
        std::move(check), s, [&](const Vec3& p) { return opencv_projects_as_libcam(camera, p); },
        [&](const std::vector<Vec3>& points) { return opencv_project(camera, points, s.threads); },
        "behind the camera, or outside libcam's domain");
}

VerifyCheck check_project_mrcal(const Camera& camera, const Samples& s, const std::optional<std::string>& lacks) {
    VerifyCheck check = new_check(verify_check::project_mrcal, "mrcal_project", kExactPx);
    if (lacks) return skip(std::move(check), *lacks);
    return compare_projection(
        std::move(check), s, [](const Vec3&) { return true; },
        [&](const std::vector<Vec3>& points) { return mrcal_project(camera, points, s.threads); },
        "outside libcam's domain");
}

// libcam's rays reprojected by libcam itself: the solver's own residual.
VerifyCheck check_unproject_libcam(const Samples& s) {
    VerifyCheck check = new_check(verify_check::unproject_libcam, "libcam, reprojected by libcam", kExactPx);
    return reprojection_errors(s.pixels.size(), s.with_ray, s.pixels_with_ray(),
                               libcam_project(s.camera, s.libcam_rays(), s.threads))
        .finish(std::move(check));
}

// libcam's rays reprojected by OpenCV, an implementation of the model independent of
// libcam's; rays past 90 degrees (FISHEYE) are beyond what cv::fisheye can project.
VerifyCheck check_unproject_libcam_opencv(const Camera& camera, const Samples& s,
                                          const std::optional<std::string>& lacks) {
    VerifyCheck check = new_check(verify_check::unproject_libcam_opencv,
                                  "libcam, reprojected by " + opencv_project_name(camera), kExactPx);
    if (lacks) return skip(std::move(check), *lacks);
    std::vector<std::size_t> in_front;
    std::vector<Vec2> pixels;
    std::vector<Vec3> rays;
    for (std::size_t i : s.with_ray) {
        if (!opencv_projects_as_libcam(camera, s.rays[i].direction)) continue;
        in_front.push_back(i);
        pixels.push_back(s.pixels[i]);
        rays.push_back(s.rays[i].direction);
    }
    VerifyCheck out = reprojection_errors(s.pixels.size(), in_front, pixels, opencv_project(camera, rays, s.threads))
                          .finish(std::move(check));
    out.note = count_note(s.with_ray.size() - in_front.size(), "rays behind the camera not compared");
    return out;
}

VerifyCheck check_unproject_libcam_mrcal(const Camera& camera, const Samples& s,
                                         const std::optional<std::string>& lacks) {
    VerifyCheck check = new_check(verify_check::unproject_libcam_mrcal, "libcam, reprojected by mrcal_project", kExactPx);
    if (lacks) return skip(std::move(check), *lacks);
    return reprojection_errors(s.pixels.size(), s.with_ray, s.pixels_with_ray(),
                               mrcal_project(camera, s.libcam_rays(), s.threads))
        .finish(std::move(check));
}

// mrcal_unproject: its own reprojection residual (through mrcal_project), and where its
// ray lands against libcam's, both projected by libcam. Pixels where mrcal gives no
// finite ray, or one outside libcam's domain (past the fold), are left out and counted.
std::vector<VerifyCheck> check_unproject_mrcal(const Camera& camera, const Samples& s,
                                               const std::optional<std::string>& lacks) {
    VerifyCheck residual = new_check(verify_check::unproject_mrcal, "mrcal_unproject, reprojected by mrcal_project",
                                     std::nullopt);
    VerifyCheck agreement = new_check(verify_check::mrcal_vs_libcam,
                                      "mrcal_unproject vs libcam, both reprojected by libcam", kMrcalAgreementPx);
    if (lacks) return {skip(std::move(residual), *lacks), skip(std::move(agreement), *lacks)};
    if (!mrcal_unprojects(camera.lens)) {
        const std::string reason = "lens: mrcal_unproject does not handle model " +
                                   std::string(lens_info(camera.lens.type).name) + " (mrcal has no gradients for it)";
        return {skip(std::move(residual), reason), skip(std::move(agreement), reason)};
    }

    const std::vector<Vec2> pixels = s.pixels_with_ray();
    const std::vector<Vec3> theirs = mrcal_unproject(camera, pixels, s.threads);
    const std::vector<Vec2> ours_reprojected = libcam_project(s.camera, s.libcam_rays(), s.threads);
    const std::vector<Vec2> theirs_by_mrcal = mrcal_project(camera, theirs, s.threads);
    const std::vector<Vec2> theirs_by_libcam = libcam_project(s.camera, theirs, s.threads);

    ErrorField residuals(s.pixels.size()), distances(s.pixels.size());
    std::size_t no_ray = 0, outside_domain = 0;
    for (std::size_t k = 0; k < pixels.size(); ++k) {
        if (!theirs[k].allFinite()) {
            ++no_ray;
            continue;
        }
        residuals.add(s.with_ray[k], (theirs_by_mrcal[k] - pixels[k]).norm());
        if (!theirs_by_libcam[k].allFinite()) {
            ++outside_domain;
            continue;
        }
        distances.add(s.with_ray[k], (theirs_by_libcam[k] - ours_reprojected[k]).norm());
    }
    residual = std::move(residuals).finish(std::move(residual));
    residual.note = count_note(no_ray, "pixels where mrcal_unproject gave no ray");
    agreement = std::move(distances).finish(std::move(agreement));
    agreement.note = count_note(no_ray + outside_domain, "pixels not compared (mrcal gave no ray, or one past the fold)");
    return {std::move(residual), std::move(agreement)};
}

// cv::undistortPoints at a stopping rule: its rays reprojected by OpenCV's own
// projection, so the error is the solver's alone. A ray that is not finite counts as
// infinitely wrong.
VerifyCheck check_undistort(const Camera& camera, const Samples& s, std::string_view name, const std::string& how,
                            const std::optional<cv::TermCriteria>& criteria, const std::optional<std::string>& lacks) {
    VerifyCheck check = new_check(name, opencv_undistort_name(camera) + " (" + how + ")", std::nullopt);
    if (lacks) return skip(std::move(check), *lacks);
    const std::vector<Vec2> pixels = s.pixels_with_ray();
    std::vector<Vec3> rays = opencv_undistort(camera, pixels, criteria, s.threads);
    for (Vec3& ray : rays) {
        if (!ray.allFinite()) ray = Vec3::Constant(kNaN);
    }
    VerifyCheck out = reprojection_errors(s.pixels.size(), s.with_ray, pixels, opencv_project(camera, rays, s.threads))
                          .finish(std::move(check));
    const auto behind = static_cast<std::size_t>(std::count_if(
        s.with_ray.begin(), s.with_ray.end(), [&](std::size_t i) { return !opencv_undistorts_to(s.rays[i].direction); }));
    out.note = count_note(behind, "pixels see behind the camera, which its (x, y, 1) cannot express");
    return out;
}

std::vector<VerifyCheck> check_undistort_opencv(const Camera& camera, const Samples& s,
                                                const std::optional<std::string>& lacks) {
    if (is_omnidir(camera)) {
        const std::string fixed = "its fixed rule: 20 iterations";
        const std::optional<std::string> no_rule =
            lacks ? lacks : std::optional<std::string>("cv::omnidir::undistortPoints has no stopping rule to set");
        return {check_undistort(camera, s, verify_check::undistort_opencv_default, fixed, std::nullopt, lacks),
                check_undistort(camera, s, verify_check::undistort_opencv_100, "100 iterations", std::nullopt,
                                no_rule)};
    }
    if (is_fisheye(camera)) {
        // cv::fisheye's eps is on its Newton step, tested for free: it stops converged points.
        const cv::TermCriteria precise(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-14);
        return {check_undistort(camera, s, verify_check::undistort_opencv_default, "default: 10 iterations, eps 1e-8",
                                std::nullopt, lacks),
                check_undistort(camera, s, verify_check::undistort_opencv_100, "100 iterations, eps 1e-14", precise,
                                lacks)};
    }
    // cv::undistortPoints tests an eps by projecting the point again after every iteration,
    // which more than doubles its time, and a reprojection error as small as 1e-14 px is
    // never reached: the 100 iterations alone give the same rays (3e-11 px apart on the
    // wide lens) in 0.4 of the time.
    const cv::TermCriteria precise(cv::TermCriteria::COUNT, 100, 0.0);
    return {check_undistort(camera, s, verify_check::undistort_opencv_default, "default: 5 iterations", std::nullopt,
                            lacks),
            check_undistort(camera, s, verify_check::undistort_opencv_100, "100 iterations", precise, lacks)};
}

// unproject(project(P)) against P's own direction. An angle is what a round trip
// changes; times fx it reads as pixels near the image centre.
VerifyCheck check_round_trip(const Camera& camera, const Samples& s) {
    VerifyCheck check = new_check(verify_check::round_trip, "libcam, angle x fx", kExactPx);
    std::vector<std::size_t> projected;
    std::vector<Vec2> pixels;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        if (!s.projected[i].valid) continue;
        projected.push_back(i);
        pixels.push_back(s.projected[i].pixel);
    }
    const std::vector<Unprojection> rays = s.camera.unproject(pixels, s.threads);
    std::vector<double> error_px(projected.size());
    parallel_chunks(projected.size(), s.threads, 4096, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            const Vec3& point = s.points[projected[k]];
            error_px[k] = rays[k].valid ? angle_between(rays[k].direction, point) * camera.intrinsics.fx : kNaN;
        }
    });
    ErrorField errors(s.pixels.size());
    for (std::size_t k = 0; k < projected.size(); ++k) errors.add(s.point_pixel[projected[k]], error_px[k]);
    return std::move(errors).finish(std::move(check));
}

std::optional<OpenCvDefaultSummary> summarise_opencv_default(const VerifyCheck& check, const Samples& s) {
    if (check.skipped() || check.stats.count == 0) return std::nullopt;
    OpenCvDefaultSummary summary;
    summary.function = check.library;
    summary.median_px = check.stats.median_px;
    summary.max_px = check.stats.max_px;
    std::size_t over_0_1 = 0, over_1 = 0;
    double worst = -1.0;
    for (std::size_t i : s.with_ray) {
        const double error = check.pixel_error_px[i];
        over_0_1 += error > 0.1 ? 1 : 0;
        over_1 += error > 1.0 ? 1 : 0;
        if (error > worst) {
            worst = error;
            summary.worst_pixel = s.pixels[i];
        }
    }
    summary.fraction_over_0_1px = static_cast<double>(over_0_1) / static_cast<double>(s.with_ray.size());
    summary.fraction_over_1px = static_cast<double>(over_1) / static_cast<double>(s.with_ray.size());
    return summary;
}

}  // namespace

std::span<const std::string_view> verify_check_names() { return kCheckNames; }

void VerifyOptions::validate() const {
    for (const auto& [field, side] : {std::pair{"grid columns", grid_columns}, std::pair{"grid rows", grid_rows}}) {
        if (side < 2 || side > kMaxVerifyGridSide) {
            throw InvalidArgument(std::string(field) + ": must be in [2, " + std::to_string(kMaxVerifyGridSide) +
                                  "] (the grid includes both ends of each side), got " + std::to_string(side));
        }
    }
    if (depths.empty()) throw InvalidArgument("depths: need at least one");
    for (double depth : depths) {
        if (!(std::isfinite(depth) && depth > 0.0)) {
            throw InvalidArgument("depths: must be finite and positive, got " + format_number(depth));
        }
    }
    if (threads < 0 || threads > 1024) {
        throw InvalidArgument("threads: must be in [0, 1024] (0: every core), got " + std::to_string(threads));
    }
}

bool VerifyCheck::pass() const {
    if (skipped() || informational()) return true;
    return stats.max_px <= *tolerance_px;
}

bool VerifyReport::pass() const {
    return std::all_of(checks.begin(), checks.end(), [](const VerifyCheck& check) { return check.pass(); });
}

const VerifyCheck* VerifyReport::find(std::string_view name) const {
    const auto it = std::find_if(checks.begin(), checks.end(), [&](const VerifyCheck& c) { return c.name == name; });
    return it == checks.end() ? nullptr : &*it;
}

VerifyReport verify_camera(const Camera& camera, const VerifyOptions& options) {
    camera.validate();
    options.validate();
    const Samples samples = make_samples(camera, options);
    const std::optional<std::string> no_opencv = opencv_lacks(camera);
    const std::optional<std::string> no_mrcal = mrcal_lacks(camera);

    VerifyReport report;
    report.image_size = camera.size;
    report.lens_type = camera.lens.type;
    report.options = options;
    report.pixels = samples.pixels;
    report.pixel_valid.resize(samples.pixels.size(), false);
    for (std::size_t i : samples.with_ray) report.pixel_valid[i] = true;
    report.invalid_fraction = 1.0 - static_cast<double>(samples.with_ray.size()) / static_cast<double>(samples.pixels.size());

    report.checks.push_back(check_project_opencv(camera, samples, no_opencv));
    report.checks.push_back(check_project_mrcal(camera, samples, no_mrcal));
    report.checks.push_back(check_unproject_libcam(samples));
    report.checks.push_back(check_unproject_libcam_opencv(camera, samples, no_opencv));
    report.checks.push_back(check_unproject_libcam_mrcal(camera, samples, no_mrcal));
    for (VerifyCheck& check : check_unproject_mrcal(camera, samples, no_mrcal)) report.checks.push_back(std::move(check));
    for (VerifyCheck& check : check_undistort_opencv(camera, samples, no_opencv)) report.checks.push_back(std::move(check));
    report.checks.push_back(check_round_trip(camera, samples));

    report.opencv_default = summarise_opencv_default(*report.find(verify_check::undistort_opencv_default), samples);
    return report;
}

}  // namespace libcam
