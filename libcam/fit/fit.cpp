#include "libcam/fit/fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "libcam/error.hpp"
#include "libcam/fit/least_squares.hpp"
#include "libcam/lens/lens_models.hpp"

namespace libcam {

namespace detail {

// Can the candidate's model express every camera of `lens` exactly (up to skew)? The
// table says which models nest (lens_contains).
bool contains_model(const Candidate& candidate, LensType lens) {
    return !candidate.look_at && lens_contains(candidate.lens, lens);
}

// How many of a candidate's parameters belong to K: f for FOV, cx cy at a sensor's
// fixed scale, fx fy cx cy otherwise.
std::size_t core_count(const Candidate& candidate) {
    if (candidate.look_at) return 1;
    return candidate.sensor_width_mm > 0.0 ? 2 : 4;
}

// The camera that `params` describe, in the source camera's frame moved by `motion`.
Camera camera_from_params(const Candidate& candidate, const ImageSize& size, const std::vector<double>& params,
                          const Pose& motion) {
    Camera camera;
    camera.size = size;
    camera.pose = motion;
    if (candidate.look_at) {
        camera.intrinsics = {params[0], params[0], size.centre_x(), size.centre_y(), 0.0};
        camera.lens = {LensType::Pinhole, {}};
        return camera;
    }
    const std::size_t core = core_count(candidate);
    if (core == 2) {
        const double f = candidate.sensor_pixels_per_mm(size.width);
        camera.intrinsics = {f, f, params[0], params[1], 0.0};
    } else {
        camera.intrinsics = {params[0], params[1], params[2], params[3], 0.0};
    }
    std::vector<double> coefficients(static_cast<std::size_t>(candidate.held_coefficients), 0.0);
    coefficients.insert(coefficients.end(), params.begin() + static_cast<long>(core), params.end());
    camera.lens = {candidate.lens, std::move(coefficients)};
    return camera;
}

Camera camera_from_state(const Candidate& candidate, const ImageSize& size, const detail::LeastSquaresState& state) {
    return camera_from_params(candidate, size, state.params, Pose::from_rvec(state.rotation, state.shift));
}

// `base` as a start for `candidate`, with its motion (pose) and the coefficients it
// has (the candidate's further ones 0): exact when the candidate contains base's model.
// A candidate that does not contain base's model starts from the model's own start
// (fit_start, lens_models.hpp) with base's K.
detail::LeastSquaresState start_from(const Candidate& candidate, const Camera& base) {
    detail::LeastSquaresState start;
    const Intrinsics& k = base.intrinsics;
    start.rotation = base.pose.rvec();
    start.shift = base.pose.t;
    const double focal = std::sqrt(k.fx * k.fy);
    if (candidate.look_at) {
        start.params = {focal};
        return start;
    }
    const bool sensor_scale = candidate.sensor_width_mm > 0.0;
    start.params = sensor_scale ? std::vector<double>{k.cx, k.cy} : std::vector<double>{k.fx, k.fy, k.cx, k.cy};
    // At a sensor's scale m is in millimetres: one of them is (pixels per mm / focal) radians
    // near the axis of base's camera.
    const double radians_per_unit = sensor_scale ? candidate.sensor_pixels_per_mm(base.size.width) / focal : 1.0;
    std::vector<double> coefficients;
    if (contains_model(candidate, base.lens.type)) {
        coefficients = base.lens.coefficients;
        coefficients.resize(static_cast<std::size_t>(lens_info(candidate.lens).num_coefficients), 0.0);
        if (sensor_scale) {
            // r in base's millimetres is radians_per_unit times r in the candidate's.
            double power = 1.0;
            for (double& c : coefficients) {
                c *= power;
                power *= radians_per_unit;
            }
        }
    } else {
        coefficients = visit_lens_model<double>(candidate.lens, [&]<class Model>() { return fit_start<Model>(radians_per_unit); });
    }
    start.params.insert(start.params.end(), coefficients.begin() + candidate.held_coefficients, coefficients.end());
    return start;
}

}  // namespace detail

using detail::camera_from_params;
using detail::contains_model;
using detail::start_from;
using detail::core_count;
using detail::camera_from_state;

namespace {

// A fit whose RMS error is below this fraction of the tolerance stops: its largest
// error, a few times its RMS, is far inside the tolerance, so no decision can change.
constexpr double kNegligibleFraction = 1e-3;

// Where a candidate's fit starts, the better result kept: the previous candidate's
// solution when the candidate contains that model (the look-at camera is a PINHOLE), so it
// never fits worse than the simpler model; and the source, exactly when the candidate
// contains the source's model, else its K undistorted. Both are needed: over wide
// scenes a simpler model's solution can lie in a poor basin for the richer one (a
// pinhole fitted to a 70 degree field has a focal length far from the lens's).
std::vector<detail::LeastSquaresState> starts_for(const Candidate& candidate, const Camera& source,
                                                  const FittedModel* previous) {
    std::vector<detail::LeastSquaresState> starts;
    if (previous != nullptr && contains_model(candidate, previous->camera.lens.type)) {
        starts.push_back(start_from(candidate, previous->camera));
    }
    Camera source_in_own_frame = source;
    source_in_own_frame.pose = Pose{};
    starts.push_back(start_from(candidate, source_in_own_frame));
    return starts;
}

// The observations the starting camera projects (the solver needs every residual at
// the start); the others this model cannot represent at all.
std::vector<FitSample> representable(const Camera& start, const std::vector<FitSample>& observations) {
    const std::vector<double> errors = reprojection_errors(start, observations);
    std::vector<FitSample> kept;
    for (std::size_t i = 0; i < observations.size(); ++i) {
        if (std::isfinite(errors[i])) kept.push_back(observations[i]);
    }
    return kept;
}

// One solve from one start, and how good it is: fewer observations left out first,
// then a smaller RMS error.
struct Attempt {
    detail::LeastSquaresState state;
    std::size_t unrepresentable = 0;
    double rms_px = std::numeric_limits<double>::infinity();

    bool better_than(const Attempt& other) const {
        return unrepresentable < other.unrepresentable ||
               (unrepresentable == other.unrepresentable && rms_px < other.rms_px);
    }
};

// A start whose model cannot reach every observation (a pinhole start of a model that
// sees wider) is fitted to those it reaches, and again from that solution while it
// reaches more: a few rounds at most.
constexpr int kMaxWideningRounds = 8;

Attempt attempt(const Candidate& candidate, const Camera& source, const std::vector<FitSample>& observations,
                detail::LeastSquaresState start, const SolveOptions& options, const detail::IterationHook& hook) {
    Camera start_camera = camera_from_state(candidate, source.size, start);
    std::vector<FitSample> kept = representable(start_camera, observations);
    Attempt result{std::move(start), observations.size() - kept.size()};
    if (kept.empty()) return result;
    for (int round = 1;; ++round) {
        // A guard the start cannot project could never be met; the check reports it.
        SolveOptions guarded = options;
        guarded.must_project = representable(start_camera, options.must_project);
        result.state =
            detail::solve_least_squares(candidate, source.size, kept, result.state, guarded, hook);
        const Camera solved = camera_from_state(candidate, source.size, result.state);
        std::vector<FitSample> reached = representable(solved, observations);
        if (reached.size() <= kept.size() || round == kMaxWideningRounds) {
            result.unrepresentable = observations.size() - kept.size();
            result.rms_px = measure(solved, kept).stats.rms_px;
            return result;
        }
        kept = std::move(reached);
        start_camera = solved;
    }
}

FittedModel fit_one(const Candidate& candidate, const Camera& source, const std::vector<FitSample>& observations,
                    const FittedModel* previous, const SolveOptions& options, const detail::IterationHook& hook) {
    std::optional<Attempt> best;
    for (detail::LeastSquaresState& start : starts_for(candidate, source, previous)) {
        Attempt next = attempt(candidate, source, observations, std::move(start), options, hook);
        if (!best || next.better_than(*best)) best = std::move(next);
    }
    FittedModel fitted;
    fitted.candidate = candidate;
    fitted.unrepresentable = best->unrepresentable;
    fitted.params = best->state.params;
    fitted.iterations = best->state.iterations;
    fitted.camera = camera_from_state(candidate, source.size, best->state);
    return fitted;
}

ScenePixels boundary_of(const ScenePixels& pixels) {
    ScenePixels boundary;
    boundary.pixels.assign(pixels.pixels.begin(), pixels.pixels.begin() + static_cast<long>(pixels.boundary_count));
    boundary.directions.assign(pixels.directions.begin(), pixels.directions.begin() + static_cast<long>(pixels.boundary_count));
    boundary.boundary_count = pixels.boundary_count;
    return boundary;
}

double largest_angle_deg(const ScenePixels& pixels) {
    double largest = 0.0;
    for (const Vec3& direction : pixels.directions) largest = std::max(largest, angle_between(direction, Vec3::UnitZ()));
    return degrees_from_radians(largest);
}

void validate_options(const FitOptions& options) {
    require_finite("tolerance", options.tolerance_px);
    if (!(options.tolerance_px > 0.0)) {
        throw InvalidArgument("tolerance: must be > 0 px, got " + format_number(options.tolerance_px));
    }
    for (const double depth : options.depths) {
        require_finite("depth", depth);
        if (!(depth > 0.0)) throw InvalidArgument("depth: must be > 0, got " + format_number(depth));
    }
    if (options.motion == CameraMotion::RotationAndShift && options.depths.empty()) {
        throw InvalidArgument("depths: a fit that may shift the camera needs points at finite depths");
    }
}

// The candidate with the fewest parameters that passes; among equals, the smaller error.
std::optional<std::size_t> choose(const std::vector<CandidateReport>& reports) {
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < reports.size(); ++i) {
        if (!reports[i].pass) continue;
        if (!best) {
            best = i;
            continue;
        }
        const CandidateReport& current = reports[*best];
        const int params = reports[i].fit.candidate.num_params(), best_params = current.fit.candidate.num_params();
        if (params < best_params || (params == best_params && reports[i].max_px < current.max_px)) best = i;
    }
    return best;
}

}  // namespace

std::string HeldParameters::text() const {
    std::string out = square_pixels ? "fx = fy" : "";
    for (const std::string& name : zero_coefficients) out += (out.empty() ? "" : ", ") + name + " = 0";
    return out;
}

int Candidate::num_params() const {
    if (look_at) return 1;
    return static_cast<int>(core_count(*this)) + lens_info(lens).num_coefficients - held_coefficients;
}

namespace {
const Candidate kLookAtCandidate{"LOOK_AT", LensType::Pinhole, true};
// The look-at candidate's name before it was LOOK_AT, taken for one more release ("FOV"
// also names Devernay and Faugeras' lens model, which libcam fit does not fit).
constexpr std::string_view kLookAtOldName = "FOV";

Candidate candidate_of(const LensInfo& info) {
    return {info.name, info.type, false, info.fit_sensor_width_mm, info.fit_held_coefficients};
}
}  // namespace

std::vector<Candidate> candidates_for(double largest_angle_deg) {
    // The look-at camera first (one parameter), then the table's candidates in its order,
    // simplest first.
    std::vector<Candidate> list = {kLookAtCandidate};
    for (const LensInfo& info : lens_models()) {
        const bool wide = largest_angle_deg >= kWideSceneAngleDeg;
        if (info.fit == FitCandidate::Always || (info.fit == FitCandidate::WideScenes && wide)) {
            list.push_back(candidate_of(info));
        }
    }
    return list;
}

std::string candidate_names() {
    std::string names(kLookAtCandidate.name);
    for (const LensInfo& info : lens_models()) {
        if (info.fit != FitCandidate::No) names += ", " + std::string(info.name);
    }
    return names;
}

Candidate candidate_named(std::string_view name) {
    if (name == kLookAtCandidate.name || name == kLookAtOldName) return kLookAtCandidate;
    for (const LensInfo& info : lens_models()) {
        if (info.name == name && info.fit != FitCandidate::No) return candidate_of(info);
    }
    const bool known = std::any_of(lens_models().begin(), lens_models().end(),
                                   [&](const LensInfo& info) { return info.name == name; });
    throw InvalidArgument("model: " + std::string(known ? "libcam fit cannot fit " : "unknown model ") + "'" +
                          std::string(name) + "'; it fits " + candidate_names());
}

std::vector<FitSample> observations_of(const ScenePixels& pixels, const std::vector<double>& depths) {
    std::vector<FitSample> observations;
    const std::vector<double> unit = {1.0};
    for (const double depth : depths.empty() ? unit : depths) {
        for (std::size_t i = 0; i < pixels.pixels.size(); ++i) {
            observations.push_back({pixels.directions[i] * depth, pixels.pixels[i]});
        }
    }
    return observations;
}

Camera camera_in_world(const FittedModel& fitted, const Camera& source) {
    // world -> source camera -> fitted camera: R = R_fit R_src, t = R_fit t_src + t_fit.
    Camera camera = fitted.camera;
    camera.pose = fitted.camera.pose.after(source.pose);
    return camera;
}

std::vector<FittedModel> fit_candidates(const Camera& source, const std::vector<FitSample>& observations,
                                        const std::vector<Candidate>& candidates, const SolveOptions& options) {
    if (observations.empty()) throw InvalidArgument("fit: no observations to fit");
    std::vector<FittedModel> fitted;
    fitted.reserve(candidates.size());
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        const auto hook = [&](int iteration) {
            if (options.progress) {
                options.progress({candidates[i].name, static_cast<int>(i), static_cast<int>(candidates.size()), iteration});
            }
        };
        fitted.push_back(fit_one(candidates[i], source, observations, fitted.empty() ? nullptr : &fitted.back(), options, hook));
    }
    return fitted;
}

std::vector<double> reprojection_errors(const Camera& fitted, const std::vector<FitSample>& observations) {
    std::vector<Vec3> moved;
    moved.reserve(observations.size());
    for (const FitSample& observation : observations) moved.push_back(fitted.pose.camera_from_world(observation.point));
    const std::vector<Projection> projections = PreparedCamera(fitted).project_camera_points(moved);
    std::vector<double> errors(observations.size(), std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < observations.size(); ++i) {
        if (projections[i].valid) errors[i] = (projections[i].pixel - observations[i].pixel).norm();
    }
    return errors;
}

ModelError measure(const Camera& fitted, const std::vector<FitSample>& observations) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::vector<double> projected = reprojection_errors(fitted, observations);
    ModelError error;
    error.unprojected = static_cast<std::size_t>(std::erase_if(projected, [](double e) { return std::isinf(e); }));
    error.stats = error_stats(std::move(projected));
    if (error.stats.count == 0) error.stats.rms_px = kInf;
    if (!error.covers()) error.stats.max_px = kInf;
    return error;
}

FitReport fit_scene(const Camera& source, const Scene& scene, const FitOptions& options) {
    validate_options(options);
    FitReport report;
    report.sampling = sample_scene(PreparedCamera(source), scene, options.lattice);
    const std::vector<FitSample> fit_set = observations_of(report.sampling.fit, options.depths);
    const std::vector<FitSample> check_set = observations_of(report.sampling.check, options.depths);
    report.fit_observations = fit_set.size();
    report.check_observations = check_set.size();
    report.largest_angle_deg = largest_angle_deg(report.sampling.check);

    const SolveOptions solve{options.motion, kNegligibleFraction * options.tolerance_px, options.progress,
                             observations_of(boundary_of(report.sampling.check), options.depths)};
    const std::vector<FittedModel> fitted = fit_candidates(
        source, fit_set, options.candidates.empty() ? candidates_for(report.largest_angle_deg) : options.candidates,
        solve);
    for (const FittedModel& model : fitted) {
        CandidateReport entry;
        entry.fit = model;
        entry.rms_px = measure(model.camera, fit_set).stats.rms_px;
        const ModelError check = measure(model.camera, check_set);
        entry.max_px = check.stats.max_px;
        entry.covers_scene = check.covers() && model.unrepresentable == 0;
        entry.pass = entry.covers_scene && entry.max_px <= options.tolerance_px;
        report.candidates.push_back(entry);
    }
    report.chosen = choose(report.candidates);
    return report;
}

}  // namespace libcam
