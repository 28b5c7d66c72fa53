#include "libcam/fit/observation_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "libcam/error.hpp"
#include "libcam/fit/least_squares.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

namespace {

using detail::ViewsState;

std::vector<std::vector<FitSample>> samples_of_views(const std::vector<FitView>& views,
                                                      const std::vector<std::size_t>& which) {
    std::vector<std::vector<FitSample>> out;
    for (const std::size_t v : which) out.push_back(views[v].observations);
    return out;
}

ViewsState start_state(const std::vector<double>& params, const std::vector<Pose>& poses,
                       const std::vector<std::size_t>& which) {
    ViewsState state;
    state.params = params;
    for (const std::size_t v : which) {
        state.rotations.push_back(poses[v].rvec());
        state.shifts.push_back(poses[v].t);
    }
    return state;
}

// The sum of squared residuals of the views `which`, and their count, under a fitted state.
struct SquaredError {
    double sum = 0.0;
    std::size_t count = 0;
};
SquaredError squared_error(const Candidate& candidate, const ImageSize& size, const std::vector<FitView>& views,
                           const std::vector<std::size_t>& which, const ViewsState& state) {
    SquaredError out;
    for (std::size_t i = 0; i < which.size(); ++i) {
        const Camera camera = detail::camera_from_params(candidate, size, state.params,
                                                         Pose::from_rvec(state.rotations[i], state.shifts[i]));
        const PreparedCamera prepared(camera);
        for (const FitSample& o : views[which[i]].observations) {
            const Projection p = prepared.project(o.point);
            out.sum += p.valid ? (p.pixel - o.pixel).squaredNorm() : std::numeric_limits<double>::infinity();
            ++out.count;
        }
    }
    return out;
}

std::vector<std::size_t> all_views(std::size_t n) {
    std::vector<std::size_t> out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = i;
    return out;
}

// Parameters whose fold-to-fold spread exceeds their size: the data do not pin them down.
std::vector<std::string> undetermined(const Candidate& candidate, const std::vector<double>& params,
                                      const std::vector<std::vector<double>>& per_fold) {
    std::vector<std::string> flags;
    if (per_fold.size() < 2) return flags;
    const std::vector<std::string> names = parameter_names(candidate);
    for (std::size_t p = 0; p < params.size(); ++p) {
        double low = per_fold[0][p], high = per_fold[0][p];
        for (const std::vector<double>& fold : per_fold) {
            low = std::min(low, fold[p]);
            high = std::max(high, fold[p]);
        }
        if (high - low > std::abs(params[p])) {
            flags.push_back(names[p] + " = " + format_short(params[p], 4) + " ranges from " + format_short(low, 4) +
                            " to " + format_short(high, 4) + " over the folds: the data do not determine it");
        }
    }
    return flags;
}

// The fit on every view from the best of `starts` (each: intrinsics and every view's pose).
// A start that leaves an observation outside the model's domain is skipped (the solver
// needs every residual at its start).
ViewsState fit_every_view(const Candidate& candidate, const ImageSize& size, const std::vector<FitView>& views,
                          const std::vector<ViewsState>& starts) {
    const std::vector<std::size_t> every = all_views(views.size());
    std::optional<ViewsState> best;
    double best_sum = std::numeric_limits<double>::infinity();
    std::string failure = "no start projects every observation";
    for (const ViewsState& from : starts) {
        if (!std::isfinite(squared_error(candidate, size, views, every, from).sum)) continue;
        try {
            ViewsState solved = detail::solve_views(candidate, size, samples_of_views(views, every), from, false);
            const double sum = squared_error(candidate, size, views, every, solved).sum;
            if (sum < best_sum) {
                best_sum = sum;
                best = std::move(solved);
            }
        } catch (const InvalidArgument& error) {
            failure = error.what();
        }
    }
    if (!best) throw InvalidArgument(failure);
    return *best;
}

struct CrossValidation {
    SquaredError heldout;
    std::vector<std::vector<double>> per_fold;  // each fold's fitted intrinsics
    std::size_t unreached = 0;  // held-out views the model fitted without them cannot project
    // The best fold's intrinsics with every view's pose under them (its training views'
    // and its held-out views'): a start for the fit on every view, and its total error.
    std::optional<ViewsState> best_fold;
    double best_fold_sum = std::numeric_limits<double>::infinity();
};

CrossValidation cross_validate(const Candidate& candidate, const ImageSize& size, const std::vector<FitView>& views,
                               const ViewsState& full, const std::vector<int>& fold_of, int folds) {
    CrossValidation out;
    for (int fold = 0; fold < folds; ++fold) {
        std::vector<std::size_t> train, test;
        for (std::size_t v = 0; v < views.size(); ++v) (fold_of[v] == fold ? test : train).push_back(v);
        ViewsState from_full;
        from_full.params = full.params;
        for (const std::size_t v : train) {
            from_full.rotations.push_back(full.rotations[v]);
            from_full.shifts.push_back(full.shifts[v]);
        }
        const ViewsState trained = detail::solve_views(candidate, size, samples_of_views(views, train), from_full, false);
        out.per_fold.push_back(trained.params);
        ViewsState complete = full;  // this fold's intrinsics and every view's pose under them
        complete.params = trained.params;
        for (std::size_t i = 0; i < train.size(); ++i) {
            complete.rotations[train[i]] = trained.rotations[i];
            complete.shifts[train[i]] = trained.shifts[i];
        }
        double fold_sum = squared_error(candidate, size, views, train, trained).sum;
        for (const std::size_t v : test) {
            // The held-out view's pose alone, with the intrinsics fitted without it (from its
            // pose in the fit on every view, a start near the answer: nothing of the view
            // enters the intrinsics it is measured with). Where that model cannot even
            // project the view (it folds over there), the view counts as infinitely wrong.
            ViewsState posed{trained.params, {full.rotations[v]}, {full.shifts[v]}, 0};
            SquaredError e = squared_error(candidate, size, views, {v}, posed);
            if (std::isfinite(e.sum)) {
                posed = detail::solve_views(candidate, size, samples_of_views(views, {v}), posed, true);
                e = squared_error(candidate, size, views, {v}, posed);
                complete.rotations[v] = posed.rotations[0];
                complete.shifts[v] = posed.shifts[0];
            } else {
                ++out.unreached;
            }
            out.heldout.sum += e.sum;
            out.heldout.count += e.count;
            fold_sum += e.sum;
        }
        if (fold_sum < out.best_fold_sum) {
            out.best_fold_sum = fold_sum;
            out.best_fold = std::move(complete);
        }
    }
    return out;
}

ObservationCandidate fit_candidate(const Candidate& candidate, const Camera& start, const std::vector<FitView>& views,
                                   const std::vector<Pose>& start_poses, const ObservationCandidate* previous,
                                   const std::vector<FitSample>& observed_rays, const std::vector<int>& fold_of,
                                   int folds) {
    ObservationCandidate out;
    out.candidate = candidate;
    const ImageSize& size = start.size;
    const std::vector<std::size_t> every = all_views(views.size());
    // From the simpler candidate's solution where this model contains it (never worse
    // than it); from the candidate fitted to the file's own camera over the observed
    // pixels (libcam fit's fit on rays: near the answer whatever the file's model, where
    // the file's K undistorted is far from it over a wide lens); and from the file's own
    // camera. The poses start with the intrinsics they were solved with.
    Camera own = start;
    own.pose = Pose{};
    std::vector<ViewsState> starts;
    if (previous != nullptr && previous->fitted && detail::contains_model(candidate, previous->camera.lens.type)) {
        starts.push_back(start_state(detail::start_from(candidate, previous->camera).params, previous->poses, every));
    }
    try {
        const std::vector<FittedModel> to_file = fit_candidates(own, observed_rays, {candidate});
        if (!to_file.empty()) {
            starts.push_back(start_state(detail::start_from(candidate, to_file.front().camera).params, start_poses, every));
        }
    } catch (const InvalidArgument&) {
        // The candidate cannot take the file's camera's rays: the other starts remain.
    }
    starts.push_back(start_state(detail::start_from(candidate, own).params, start_poses, every));
    ViewsState full = fit_every_view(candidate, size, views, starts);
    CrossValidation validation = cross_validate(candidate, size, views, full, fold_of, folds);
    // A fold that found intrinsics fitting every view better than the fit on every view
    // did (a poorer basin it started in, over a wide lens) is where that fit starts again,
    // once.
    const double full_sum = squared_error(candidate, size, views, every, full).sum;
    if (validation.best_fold && validation.best_fold_sum < 0.99 * full_sum) {
        full = fit_every_view(candidate, size, views, {full, *validation.best_fold});
        validation = cross_validate(candidate, size, views, full, fold_of, folds);
    }

    out.params = full.params;
    out.camera = detail::camera_from_params(candidate, size, full.params, Pose{});
    for (std::size_t v = 0; v < views.size(); ++v) out.poses.push_back(Pose::from_rvec(full.rotations[v], full.shifts[v]));
    const SquaredError training = squared_error(candidate, size, views, every, full);
    out.rms_px = std::sqrt(training.sum / static_cast<double>(training.count));
    out.heldout_rms_px = std::sqrt(validation.heldout.sum / static_cast<double>(validation.heldout.count));
    out.heldout_count = validation.heldout.count;
    out.flags = undetermined(candidate, out.params, validation.per_fold);
    if (validation.unreached > 0) {
        out.flags.push_back(std::to_string(validation.unreached) +
                            " held-out views fall where the model fitted without them folds over: it does not "
                            "generalise to them");
    }
    out.fitted = true;
    return out;
}

// Views that repeat another (the same points, each seen within kRepeatPx): a board left
// still while frames were taken. Such views go into one fold together, else a held-out
// view would have its twin among the training views and could not show an overfit.
constexpr double kRepeatPx = 2.0;

bool repeats(const FitView& a, const FitView& b) {
    if (a.observations.size() != b.observations.size()) return false;
    double sum = 0.0;
    for (std::size_t i = 0; i < a.observations.size(); ++i) {
        if (a.observations[i].point != b.observations[i].point) return false;
        sum += (a.observations[i].pixel - b.observations[i].pixel).norm();
    }
    return sum < kRepeatPx * static_cast<double>(a.observations.size());
}

// Each view's group of repeats (the index of its first member), by union of pairs.
std::vector<std::size_t> repeat_groups(const std::vector<FitView>& views) {
    std::vector<std::size_t> group(views.size());
    for (std::size_t v = 0; v < views.size(); ++v) {
        group[v] = v;
        for (std::size_t u = 0; u < v; ++u) {
            if (group[u] == u && repeats(views[u], views[v])) {
                group[v] = u;
                break;
            }
        }
    }
    return group;
}

// The rays of the file's camera a candidate's start is fitted to: enough to pin down 16
// parameters over the image, few enough to cost little beside the fit itself.
constexpr std::size_t kRaySamples = 2000;

// The simplest candidate within the margin of the best held-out RMS, and why.
void choose(ObservationFitReport& report) {
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < report.candidates.size(); ++i) {
        const ObservationCandidate& c = report.candidates[i];
        if (c.fitted && std::isfinite(c.heldout_rms_px) &&
            (!best || c.heldout_rms_px < report.candidates[*best].heldout_rms_px)) {
            best = i;
        }
    }
    if (!best) {
        report.reason = "no candidate could be fitted";
        return;
    }
    const double limit = report.candidates[*best].heldout_rms_px * (1.0 + report.margin);
    for (std::size_t i = 0; i < report.candidates.size(); ++i) {
        const ObservationCandidate& c = report.candidates[i];
        if (!c.fitted || !(c.heldout_rms_px <= limit)) continue;
        report.chosen = i;
        const ObservationCandidate& top = report.candidates[*best];
        report.reason = std::string(c.candidate.name) + ": the simplest model whose held-out RMS (" +
                        format_short(c.heldout_rms_px, 4) + " px) is within " + format_short(100.0 * report.margin) +
                        "% of the best (" + std::string(top.candidate.name) + ", " +
                        format_short(top.heldout_rms_px, 4) + " px)";
        return;
    }
}

}  // namespace

ObservationFitReport fit_observations(const Camera& start, const std::vector<FitView>& views,
                                      const ObservationFitOptions& options) {
    if (views.size() < 2) {
        throw InvalidArgument("fit --observations: " + std::to_string(views.size()) +
                              " views: cross-validation needs at least two");
    }
    start.validate();
    ObservationFitReport report;
    report.views = views.size();
    for (const FitView& view : views) report.observations += view.observations.size();
    // Folds dealt by group of repeated views, in turn.
    const std::vector<std::size_t> group = repeat_groups(views);
    std::vector<std::size_t> groups;
    for (std::size_t v = 0; v < views.size(); ++v) {
        if (group[v] == v) groups.push_back(v);
    }
    if (groups.size() < 2) {
        throw InvalidArgument("fit --observations: the " + std::to_string(views.size()) +
                              " views are one pose repeated (each within " + format_short(kRepeatPx) +
                              " px of the first): views held out would be seen in training, so nothing can be "
                              "judged; a calibration needs views of the board in different poses");
    }
    report.repeated_views = views.size() - groups.size();
    report.folds = std::clamp(options.folds, 2, static_cast<int>(groups.size()));
    std::vector<int> fold_of(views.size());
    for (std::size_t v = 0; v < views.size(); ++v) {
        const auto position = static_cast<std::size_t>(std::find(groups.begin(), groups.end(), group[v]) - groups.begin());
        fold_of[v] = static_cast<int>(position % static_cast<std::size_t>(report.folds));
    }
    report.margin = options.margin;

    // The observed pixels' rays through the file's own camera (at most kRaySamples of
    // them, evenly through the observations), and the widest of their angles.
    const PreparedCamera prepared(Camera{start.size, start.intrinsics, start.lens, Pose{}});
    std::vector<FitSample> observed_rays;
    double widest = 0.0;
    const std::size_t stride = std::max<std::size_t>(1, report.observations / kRaySamples);
    std::size_t index = 0;
    for (const FitView& view : views) {
        for (const FitSample& o : view.observations) {
            if (index++ % stride != 0) continue;
            const Unprojection u = prepared.unproject(o.pixel);
            if (!u.valid) continue;
            const Vec3 ray = u.direction.normalized();
            widest = std::max(widest, std::acos(std::clamp(ray.z(), -1.0, 1.0)));
            observed_rays.push_back({ray, o.pixel});
        }
    }
    std::vector<Candidate> candidates = options.candidates;
    if (candidates.empty()) candidates = candidates_for(widest * 180.0 / 3.14159265358979323846);
    std::vector<Pose> start_poses;
    for (const FitView& view : views) start_poses.push_back(view.pose);
    for (const Candidate& candidate : candidates) {
        const ObservationCandidate* previous = report.candidates.empty() ? nullptr : &report.candidates.back();
        try {
            report.candidates.push_back(
                fit_candidate(candidate, start, views, start_poses, previous, observed_rays, fold_of, report.folds));
        } catch (const Error& error) {
            ObservationCandidate failed;
            failed.candidate = candidate;
            failed.failure = error.what();
            report.candidates.push_back(std::move(failed));
        }
    }
    choose(report);
    return report;
}

std::vector<std::string> parameter_names(const Candidate& candidate) {
    if (candidate.look_at) return {"f"};
    std::vector<std::string> names;
    if (detail::core_count(candidate) == 4) names = {"fx", "fy"};
    names.insert(names.end(), {"cx", "cy"});
    const auto coefficients = lens_info(candidate.lens).coefficients.view();
    for (std::size_t i = static_cast<std::size_t>(candidate.held_coefficients); i < coefficients.size(); ++i) {
        names.emplace_back(coefficients[i]);
    }
    return names;
}

Eigen::MatrixXd free_directions(const Candidate& candidate) {
    const std::vector<std::string> names = parameter_names(candidate);
    const auto count = static_cast<Eigen::Index>(names.size());
    const HeldParameters& held = candidate.held;
    const auto held_at_zero = [&](const std::string& name) {
        return std::find(held.zero_coefficients.begin(), held.zero_coefficients.end(), name) !=
               held.zero_coefficients.end();
    };
    const bool tie_focal = held.square_pixels && count >= 2 && names[0] == "fx" && names[1] == "fy";
    std::vector<Eigen::VectorXd> columns;
    for (Eigen::Index i = 0; i < count; ++i) {
        const std::string& name = names[static_cast<std::size_t>(i)];
        if (tie_focal && i == 1) continue;
        // The coefficients after K's: a held name among K's own ("fx") is not a coefficient.
        if (i >= static_cast<Eigen::Index>(detail::core_count(candidate)) && held_at_zero(name)) continue;
        Eigen::VectorXd column = Eigen::VectorXd::Zero(count);
        column(i) = 1.0;
        if (tie_focal && i == 0) column(0) = column(1) = std::sqrt(0.5);
        columns.push_back(std::move(column));
    }
    Eigen::MatrixXd out(count, static_cast<Eigen::Index>(columns.size()));
    for (std::size_t c = 0; c < columns.size(); ++c) out.col(static_cast<Eigen::Index>(c)) = columns[c];
    return out;
}

CameraParameters parameters_of(const Camera& camera) {
    const std::string model(lens_info(camera.lens.type).name);
    CameraParameters out;
    try {
        out.candidate = candidate_named(model);
    } catch (const InvalidArgument&) {
        throw InvalidArgument("camera: libcam's fit does not take the " + model + " model, so it cannot differentiate it");
    }
    if (out.candidate.sensor_width_mm > 0.0 || out.candidate.held_coefficients > 0) {
        throw InvalidArgument("camera: the fit holds part of the " + model +
                              " model fixed (its sensor scale or leading coefficient), so it cannot take this camera's own");
    }
    if (camera.intrinsics.skew != 0.0) {
        throw InvalidArgument("camera: skew " + format_short(camera.intrinsics.skew) +
                              ": the fit's models have none, so it cannot differentiate this camera");
    }
    out.params = detail::start_from(out.candidate, camera).params;
    return out;
}

}  // namespace libcam
