#include "libcam/calibrate/calibration_json.hpp"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

namespace libcam {

namespace {

using Json = nlohmann::ordered_json;

// JSON has no infinity or NaN: a value without a finite number is null.
Json finite_or_null(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

Json vec_json(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

Json outliers_json(const Calibration& c) {
    Json out = {{"corners", c.outliers},
                {"noise_px", c.noise_px},
                {"fits", c.rounds},
                {"stopped_at_limit", c.rounds_capped},
                {"images", Json::array()}};
    for (const CalibrationView& view : c.views) {
        if (!view.outlier_ids.empty()) out["images"].push_back({{"image", view.image}, {"corners", view.outlier_ids}});
    }
    return out;
}

// Each candidate, and its projection uncertainty where it was fitted.
Json candidates_json(const Calibration& c) {
    Json out = Json::array();
    for (std::size_t i = 0; i < c.fit.candidates.size(); ++i) {
        const ObservationCandidate& candidate = c.fit.candidates[i];
        Json entry{{"model", std::string(candidate.candidate.name)}, {"fitted", candidate.fitted}};
        if (!candidate.fitted) {
            entry["failure"] = candidate.failure;
            out.push_back(entry);
            continue;
        }
        entry["params"] = free_directions(candidate.candidate).cols();  // the free ones: fx = fy counts once
        entry["rms_px"] = finite_or_null(candidate.rms_px);
        entry["heldout_rms_px"] = finite_or_null(candidate.heldout_rms_px);
        entry["flags"] = candidate.flags;
        const CandidateUncertainty& u = c.uncertainty[i];
        if (!u.computed) {
            entry["uncertainty"] = {{"failure", u.failure}};
        } else {
            Json parameters = Json::array();
            for (const ParameterSpread& p : u.parameters) {
                parameters.push_back({{"name", p.name}, {"value", p.value}, {"stdev", finite_or_null(p.stdev)}});
            }
            entry["uncertainty"] = {{"noise_px", u.noise_px},
                                    {"centre_sigma_px", finite_or_null(u.centre_px)},
                                    {"worst_observed_sigma_px", finite_or_null(u.worst_observed_px)},
                                    {"parameters", parameters}};
        }
        out.push_back(entry);
    }
    return out;
}

}  // namespace

std::vector<double> chosen_sigma_px(const Calibration& c, const std::vector<Vec2>& pixels) {
    if (!c.uncertainty[*c.fit.chosen].computed) return std::vector<double>(pixels.size(), std::numeric_limits<double>::quiet_NaN());
    return ProjectionUncertainty(c.solved(*c.fit.chosen)).sigma_px(pixels);
}

std::string calibration_json(const Calibration& c, const std::vector<Vec2>& at, const std::vector<double>& at_sigma_px) {
    const ObservationCandidate& chosen = c.chosen();
    const Intrinsics& k = chosen.camera.intrinsics;
    Json out;
    out["images"] = c.images;
    out["used"] = c.views.size();
    out["rejected"] = Json::array();
    for (const RejectedImage& r : c.rejected) out["rejected"].push_back({{"image", r.image}, {"why", r.why}});
    out["corners"] = c.corners();
    out["board"] = c.board.text();
    out["held"] = c.held.text();
    out["outliers"] = outliers_json(c);
    out["chosen"] = {{"model", std::string(chosen.candidate.name)},
                     {"image_size", {c.size.width, c.size.height}},
                     {"K", {{k.fx, k.skew, k.cx}, {0.0, k.fy, k.cy}, {0.0, 0.0, 1.0}}},
                     {"dist", chosen.camera.lens.coefficients},
                     {"rms_px", finite_or_null(chosen.rms_px)},
                     {"heldout_rms_px", finite_or_null(chosen.heldout_rms_px)},
                     {"reason", c.fit.reason}};
    out["candidates"] = candidates_json(c);
    out["views"] = Json::array();
    for (std::size_t v = 0; v < c.views.size(); ++v) {
        const Pose& pose = chosen.poses[v];
        out["views"].push_back({{"image", c.views[v].image},
                                {"corners", c.views[v].ids.size()},
                                {"rms_px", finite_or_null(c.view_rms_px(v))},
                                {"rvec", vec_json(pose.rvec())},
                                {"tvec", vec_json(pose.t)}});
    }
    out["uncertainty"] = Json::array();
    for (std::size_t i = 0; i < at.size(); ++i) {
        out["uncertainty"].push_back({{"pixel", {at[i].x(), at[i].y()}}, {"sigma_px", finite_or_null(at_sigma_px[i])}});
    }
    return out.dump(2) + "\n";
}

}  // namespace libcam
