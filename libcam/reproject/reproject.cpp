#include "libcam/reproject/reproject.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "libcam/camera/parallel.hpp"
#include "libcam/lens/lens_models.hpp"

namespace libcam {

std::string_view to_string(ResidualStatus status) {
    switch (status) {
        case ResidualStatus::Counted: return "counted";
        case ResidualStatus::Outlier: return "outlier";
        case ResidualStatus::BehindCamera: return "behind the camera";
        case ResidualStatus::OutsideDomain: return "past the lens's valid domain";
        case ResidualStatus::OutsideImage: return "off the image";
    }
    return "?";
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Whether an OpenCV pixel lies on the image: within half a pixel of the outer centres.
bool on_image(const Vec2& pixel, const ImageSize& size) {
    return pixel.x() >= -0.5 && pixel.y() >= -0.5 && pixel.x() <= size.width - 0.5 && pixel.y() <= size.height - 0.5;
}

// The pixel of a camera point by the lens model's formula with no bound on its valid
// domain (its coefficients as they are, the valid radius infinite): what a tool that
// evaluates the formula as it stands computes past the fold. NaN where even the formula
// gives no finite pixel (behind the camera, a rational model's pole).
Vec2 formula_pixel(const Camera& camera, const Vec3& camera_point) {
    return visit_lens_model<double>(camera.lens.type, [&]<class Model>() {
        typename Model::Parameters unbounded = Model::parameters(camera.lens.coefficients);
        unbounded.valid_radius = kInfinity;
        Vec2 normalized;
        if (!Model::project(unbounded, camera_point, normalized)) return Vec2(kNaN, kNaN);
        const Vec2 pixel = camera.intrinsics.pixel_from_normalized(normalized);
        return pixel.allFinite() ? pixel : Vec2(kNaN, kNaN);
    });
}

ObservationResidual residual_of(const ObservationSet& set, const std::vector<PreparedCamera>& cameras,
                                const Observation& observation) {
    const ObservedView& view = set.views[static_cast<std::size_t>(observation.view)];
    const PreparedCamera& camera = cameras[static_cast<std::size_t>(view.camera)];
    const Vec3 camera_point = view.pose.camera_from_world(set.points[static_cast<std::size_t>(observation.point)]);
    const Projection projection = camera.project_camera_point(camera_point);
    ObservationResidual out;
    if (!projection.valid) {
        out.projected = Vec2(kNaN, kNaN);
        out.residual = Vec2(kNaN, kNaN);
        out.error_px = kInfinity;
        out.status = camera_point.z() <= 0.0 ? ResidualStatus::BehindCamera : ResidualStatus::OutsideDomain;
        if (out.status == ResidualStatus::OutsideDomain) {
            out.past_domain_projected = formula_pixel(camera.camera(), camera_point);
        }
    } else {
        out.projected = projection.pixel;
        out.residual = projection.pixel - observation.pixel;
        out.error_px = out.residual.norm();
    }
    if (!observation.inlier) {
        out.status = ResidualStatus::Outlier;
    } else if (out.status == ResidualStatus::Counted && !on_image(observation.pixel, camera.camera().size)) {
        out.status = ResidualStatus::OutsideImage;
    }
    return out;
}

bool weighted(const ObservationSet& set) {
    return std::any_of(set.observations.begin(), set.observations.end(),
                       [](const Observation& o) { return o.weight != 1.0; });
}

// Recomputes a stored number by its definition, from the counted residuals; and the
// per-point means COLMAP stores, for the comparison point by point.
std::vector<double> per_point_mean_errors(const ObservationSet& set, const std::vector<ObservationResidual>& residuals) {
    std::vector<double> sum(set.points.size(), 0.0);
    std::vector<std::size_t> count(set.points.size(), 0);
    for (std::size_t i = 0; i < residuals.size(); ++i) {
        if (residuals[i].status != ResidualStatus::Counted) continue;
        const auto point = static_cast<std::size_t>(set.observations[i].point);
        sum[point] += residuals[i].error_px;
        ++count[point];
    }
    for (std::size_t p = 0; p < sum.size(); ++p) sum[p] = count[p] == 0 ? kNaN : sum[p] / static_cast<double>(count[p]);
    return sum;
}

// The mean of the per-point means, over the points that have one.
double mean_of_point_means(const std::vector<double>& point_means) {
    double sum = 0.0;
    std::size_t points = 0;
    for (const double mean : point_means) {
        if (std::isnan(mean)) continue;
        sum += mean;
        ++points;
    }
    return points == 0 ? kNaN : sum / static_cast<double>(points);
}

// `point_means`: per_point_mean_errors, computed once by the caller when some number needs it.
double recompute(const ResidualStats& all, const std::vector<double>& point_means, ReportedMeasure measure) {
    switch (measure) {
        case ReportedMeasure::RmsOverObservations: return all.stats.rms_px;
        case ReportedMeasure::MeanOfPointMeans: return mean_of_point_means(point_means);
    }
    return kNaN;
}

// The stored numbers against the recomputed ones; `name_of(i)` names the item where the
// difference is largest (called once: a model's points are many).
template <class NameOf>
PerItemComparison compare_items(const std::vector<double>& stored, const std::vector<double>& recomputed,
                                NameOf&& name_of) {
    PerItemComparison comparison;
    std::size_t worst = 0;
    for (std::size_t i = 0; i < stored.size(); ++i) {
        if (std::isnan(stored[i]) || std::isnan(recomputed[i])) continue;
        ++comparison.compared;
        const double difference = std::abs(stored[i] - recomputed[i]);
        if (comparison.compared == 1 || difference > comparison.max_abs_difference) {
            comparison.max_abs_difference = difference;
            worst = i;
        }
    }
    if (comparison.compared > 0) comparison.worst_item = name_of(worst);
    return comparison;
}

ConventionCheck convention_check(const std::vector<ObservationResidual>& residuals, const ResidualStats& all) {
    ConventionCheck check;
    if (all.stats.count == 0) return check;
    check.best_shift_px = -all.bias;
    check.rms_px = all.stats.rms_px;
    // The half-pixel shift on each axis nearest the best one: where a file written in the
    // other convention puts its projections.
    const Vec2 half(std::copysign(0.5, check.best_shift_px.x()), std::copysign(0.5, check.best_shift_px.y()));
    double sum_squares = 0.0;
    for (std::size_t i = 0; i < residuals.size(); ++i) {
        if (residuals[i].status == ResidualStatus::Counted) sum_squares += (residuals[i].residual + half).squaredNorm();
    }
    check.rms_half_shift_px = std::sqrt(sum_squares / static_cast<double>(all.stats.count));
    // Suspect only when the best shift is itself near the half pixel on both axes and the
    // half-pixel shift takes away at least a third of the RMS: noise and a calibration's
    // own small bias do neither.
    const bool near_half = (check.best_shift_px - half).cwiseAbs().maxCoeff() < 0.2;
    check.suspect = near_half && check.rms_half_shift_px < (2.0 / 3.0) * check.rms_px;
    return check;
}

// The sums one group's statistics are made of: every statistic but the quantiles, defined
// once for a whole set (residual_stats) and for its views and cameras (group_stats).
struct ResidualSums {
    Vec2 residual = Vec2::Zero();
    double error = 0.0;
    double weighted_squares = 0.0;

    void add(const ObservationResidual& r, double weight) {
        residual += r.residual;
        error += r.error_px;
        weighted_squares += weight * weight * r.error_px * r.error_px;
    }
    // The statistics of the group whose errors (reordered here) these sums are.
    ResidualStats finish(std::span<double> errors, bool set_weighted) const {
        ResidualStats out;
        const std::size_t n = errors.size();
        out.stats = error_stats_in_place(errors);
        if (n == 0) return out;
        out.mean_px = error / static_cast<double>(n);
        out.bias = residual / static_cast<double>(n);
        if (set_weighted) out.weighted_rms_px = std::sqrt(weighted_squares / static_cast<double>(n));
        return out;
    }
};

// residual_stats, told whether the set is weighted: reproject asks that once, not once
// per view over every observation (a model of 2000 views and a million observations).
ResidualStats stats_of(const ObservationSet& set, const std::vector<ObservationResidual>& residuals,
                       const std::vector<std::size_t>& indices, bool set_weighted) {
    std::vector<double> errors;
    errors.reserve(indices.empty() ? residuals.size() : indices.size());
    ResidualSums sums;
    const auto add = [&](std::size_t i) {
        if (residuals[i].status != ResidualStatus::Counted) return;
        errors.push_back(residuals[i].error_px);
        sums.add(residuals[i], set.observations[i].weight);
    };
    if (indices.empty()) {
        for (std::size_t i = 0; i < residuals.size(); ++i) add(i);
    } else {
        for (const std::size_t i : indices) add(i);
    }
    return sums.finish(errors, set_weighted);
}

// The statistics of the counted residuals of each of `groups` groups (a view, a camera),
// `group_of(observation)` naming each observation's: one pass, the errors of each group
// laid side by side in one array (a million observations in thousands of views).
template <class GroupOf>
std::vector<ResidualStats> group_stats(const ObservationSet& set, const std::vector<ObservationResidual>& residuals,
                                       std::size_t groups, bool set_weighted, GroupOf&& group_of) {
    std::vector<std::size_t> start(groups + 1, 0);
    for (std::size_t i = 0; i < residuals.size(); ++i) {
        if (residuals[i].status == ResidualStatus::Counted) ++start[group_of(set.observations[i]) + 1];
    }
    for (std::size_t g = 0; g < groups; ++g) start[g + 1] += start[g];
    std::vector<double> errors(start[groups]);
    std::vector<std::size_t> filled(start.begin(), start.end() - 1);
    std::vector<ResidualSums> sums(groups);
    for (std::size_t i = 0; i < residuals.size(); ++i) {
        if (residuals[i].status != ResidualStatus::Counted) continue;
        const std::size_t g = group_of(set.observations[i]);
        errors[filled[g]++] = residuals[i].error_px;
        sums[g].add(residuals[i], set.observations[i].weight);
    }
    std::vector<ResidualStats> out;
    out.reserve(groups);
    for (std::size_t g = 0; g < groups; ++g) {
        out.push_back(sums[g].finish(std::span<double>(errors.data() + start[g], start[g + 1] - start[g]), set_weighted));
    }
    return out;
}

// The residuals by the tools' own rule for their stored numbers: those libcam counts,
// and the inliers past the valid domain with the formula's pixel there, counted too
// (`added` of them).
std::vector<ObservationResidual> by_tools_rule(const ObservationSet& set, std::vector<ObservationResidual> residuals,
                                               std::size_t& added) {
    added = 0;
    for (std::size_t i = 0; i < residuals.size(); ++i) {
        ObservationResidual& r = residuals[i];
        if (r.status != ResidualStatus::OutsideDomain || !r.past_domain_projected.allFinite()) continue;
        r.projected = r.past_domain_projected;
        r.residual = r.projected - set.observations[i].pixel;
        r.error_px = r.residual.norm();
        r.status = ResidualStatus::Counted;
        ++added;
    }
    return residuals;
}

// The numbers the file stored against libcam's recomputation of them by the tool's rule
// (by_tools_rule), into `summary` (whose `all` and `outside_domain` are filled).
void compare_stored_numbers(const ObservationSet& set, const std::vector<ObservationResidual>& residuals,
                            bool set_weighted, ReprojectionSummary& summary) {
    const bool stored_any = !set.reported.empty() || !set.reported_per_view.empty() || !set.reported_per_point.empty();
    if (!stored_any) return;
    // The same residuals where nothing is past the valid domain.
    const std::vector<ObservationResidual> tools_residuals =
        summary.outside_domain == 0 ? std::vector<ObservationResidual>{}
                                    : by_tools_rule(set, residuals, summary.reported_past_domain);
    const std::vector<ObservationResidual>& counted = summary.outside_domain == 0 ? residuals : tools_residuals;
    const ResidualStats tools_all =
        summary.reported_past_domain == 0 ? summary.all : stats_of(set, counted, {}, set_weighted);
    const bool needs_point_means =
        !set.reported_per_point.empty() ||
        std::any_of(set.reported.begin(), set.reported.end(),
                    [](const ReportedNumber& n) { return n.measure == ReportedMeasure::MeanOfPointMeans; });
    const std::vector<double> point_means =
        needs_point_means ? per_point_mean_errors(set, counted) : std::vector<double>{};
    for (const ReportedNumber& number : set.reported) {
        summary.reported.push_back({number, recompute(tools_all, point_means, number.measure)});
    }
    if (!set.reported_per_view.empty()) {
        const auto view_of = [](const Observation& o) { return static_cast<std::size_t>(o.view); };
        const std::vector<ResidualStats> views = group_stats(set, counted, set.views.size(), set_weighted, view_of);
        std::vector<double> view_rms;
        for (const ResidualStats& view : views) view_rms.push_back(view.stats.count == 0 ? kNaN : view.stats.rms_px);
        summary.per_view_reported =
            compare_items(set.reported_per_view, view_rms, [&](std::size_t v) { return set.views[v].name; });
    }
    if (!set.reported_per_point.empty()) {
        summary.per_point_reported = compare_items(set.reported_per_point, point_means,
                                                   [&](std::size_t p) { return std::to_string(set.point_ids[p]); });
    }
}

}  // namespace

ResidualStats residual_stats(const ObservationSet& set, const std::vector<ObservationResidual>& residuals,
                             const std::vector<std::size_t>& indices) {
    return stats_of(set, residuals, indices, weighted(set));
}

std::vector<std::size_t> worst_observations(const std::vector<ObservationResidual>& residuals, std::size_t n) {
    // Larger error first; among equal errors, the earlier observation.
    const auto larger = [&](std::size_t a, std::size_t b) {
        return residuals[a].error_px > residuals[b].error_px || (residuals[a].error_px == residuals[b].error_px && a < b);
    };
    // The n largest kept in a heap whose top is the smallest of them: one pass, n entries.
    std::vector<std::size_t> kept;
    if (n == 0) return kept;
    kept.reserve(n + 1);
    for (std::size_t i = 0; i < residuals.size(); ++i) {
        if (residuals[i].status != ResidualStatus::Counted) continue;
        if (kept.size() == n && !larger(i, kept.front())) continue;
        kept.push_back(i);
        std::push_heap(kept.begin(), kept.end(), larger);
        if (kept.size() > n) {
            std::pop_heap(kept.begin(), kept.end(), larger);
            kept.pop_back();
        }
    }
    std::sort_heap(kept.begin(), kept.end(), larger);
    return kept;
}

Reprojection reproject(const ObservationSet& set, int threads) {
    std::vector<PreparedCamera> cameras;
    cameras.reserve(set.cameras.size());
    for (const ObservedCamera& camera : set.cameras) {
        Camera at_origin = camera.camera;
        at_origin.pose = Pose{};
        cameras.emplace_back(at_origin);
    }
    Reprojection out;
    out.residuals.resize(set.observations.size());
    parallel_chunks(set.observations.size(), worker_count(threads), 4096, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) out.residuals[i] = residual_of(set, cameras, set.observations[i]);
    });

    ReprojectionSummary& summary = out.summary;
    for (const ObservationResidual& r : out.residuals) {
        switch (r.status) {
            case ResidualStatus::Counted: break;
            case ResidualStatus::Outlier: ++summary.outliers; break;
            case ResidualStatus::BehindCamera: ++summary.behind_camera; break;
            case ResidualStatus::OutsideDomain: ++summary.outside_domain; break;
            case ResidualStatus::OutsideImage: ++summary.outside_image; break;
        }
    }
    const bool set_weighted = weighted(set);
    summary.all = stats_of(set, out.residuals, {}, set_weighted);

    std::vector<std::size_t> camera_of_view(set.views.size());
    for (std::size_t v = 0; v < set.views.size(); ++v) camera_of_view[v] = static_cast<std::size_t>(set.views[v].camera);
    std::vector<ResidualStats> per_view = group_stats(set, out.residuals, set.views.size(), set_weighted,
                                                      [&](const Observation& o) { return static_cast<std::size_t>(o.view); });
    // A model of one camera has the statistics of all for it.
    std::vector<ResidualStats> per_camera =
        set.cameras.size() == 1
            ? std::vector<ResidualStats>{summary.all}
            : group_stats(set, out.residuals, set.cameras.size(), set_weighted,
                          [&](const Observation& o) { return camera_of_view[static_cast<std::size_t>(o.view)]; });
    for (std::size_t v = 0; v < set.views.size(); ++v) {
        summary.per_view.push_back({set.views[v].name, std::move(per_view[v])});
    }
    for (std::size_t c = 0; c < set.cameras.size(); ++c) {
        summary.per_camera.push_back({set.cameras[c].name, std::move(per_camera[c])});
    }
    summary.convention = convention_check(out.residuals, summary.all);
    compare_stored_numbers(set, out.residuals, set_weighted, summary);
    return out;
}

}  // namespace libcam
