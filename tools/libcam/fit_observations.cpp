#include "fit_observations.hpp"

#include <sstream>

#include "commands.hpp"
#include "json_output.hpp"
#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/fit/observation_fit.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/observations.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "parse.hpp"

namespace libcam::cli {

namespace {

int camera_of(const ObservationSet& set, const std::string& selector) {
    if (selector.empty()) {
        if (set.cameras.size() > 1) {
            std::string names;
            for (const ObservedCamera& c : set.cameras) names += (names.empty() ? "" : ", ") + c.name;
            throw UsageError("--camera: " + set.source + " holds " + std::to_string(set.cameras.size()) +
                             " cameras (" + names + "): say which to fit");
        }
        return 0;
    }
    try {
        return observed_camera_index(set, selector);
    } catch (const InvalidArgument& error) {
        throw UsageError(std::string("--camera: ") + error.what());
    }
}

// The views of one camera with the observations its tool counted: inliers that project
// through the file's own camera and lie on the image (the solver needs every residual at
// its start).
std::vector<FitView> fit_views(const ObservationSet& set, const Reprojection& reprojection, int camera) {
    std::vector<FitView> views(set.views.size());
    for (std::size_t v = 0; v < set.views.size(); ++v) {
        views[v].name = set.views[v].name;
        views[v].pose = set.views[v].pose;
    }
    for (std::size_t i = 0; i < set.observations.size(); ++i) {
        const Observation& o = set.observations[i];
        if (reprojection.residuals[i].status != ResidualStatus::Counted) continue;
        if (set.views[static_cast<std::size_t>(o.view)].camera != camera) continue;
        views[static_cast<std::size_t>(o.view)].observations.push_back(
            {set.points[static_cast<std::size_t>(o.point)], o.pixel});
    }
    std::erase_if(views, [](const FitView& view) { return view.observations.empty(); });
    return views;
}

std::string format_text(const ObservationSet& set, int camera, const ResidualStats& file_fit,
                        const ObservationFitReport& report) {
    const Camera& own = set.cameras[static_cast<std::size_t>(camera)].camera;
    std::ostringstream out;
    out << set.source << ": camera " << set.cameras[static_cast<std::size_t>(camera)].name << ", " << report.views
        << " views, " << report.observations << " observations, " << report.folds << " folds by view";
    if (report.repeated_views > 0) {
        out << " (" << report.repeated_views << " views repeat another within 2 px and are held out with it)";
    }
    out << "\n";
    out << "the file's own model: " << lens_text(own) << "; on these observations rms "
        << format_short(file_fit.stats.rms_px, 4) << " px\n\n";
    out << candidates_table(report) << "\n";
    if (!report.chosen) {
        out << "no choice: " << report.reason << "\n";
        return out.str();
    }
    const ObservationCandidate& chosen = report.candidates[*report.chosen];
    const Intrinsics& k = chosen.camera.intrinsics;
    out << "chosen: " << report.reason << "\n";
    out << "  K: fx " << format_short(k.fx, 8) << ", fy " << format_short(k.fy, 8) << ", cx " << format_short(k.cx, 8)
        << ", cy " << format_short(k.cy, 8) << " (OpenCV's pixels)\n";
    out << "  lens: " << lens_text(chosen.camera) << "\n";
    return out.str();
}

std::string format_json(const ObservationSet& set, int camera, const ResidualStats& file_fit,
                        const ObservationFitReport& report) {
    Json out;
    out["source"] = set.source;
    out["camera"] = set.cameras[static_cast<std::size_t>(camera)].name;
    out["views"] = report.views;
    out["observations"] = report.observations;
    out["folds"] = report.folds;
    out["repeated_views"] = report.repeated_views;
    out["margin"] = report.margin;
    const Camera& own = set.cameras[static_cast<std::size_t>(camera)].camera;
    out["file_model"] = {{"model", std::string(lens_info(own.lens.type).name)},
                         {"rms_px", finite_or_null(file_fit.stats.rms_px)}};
    out["candidates"] = candidates_json(report);
    out["reason"] = report.reason;
    if (report.chosen) {
        const ObservationCandidate& chosen = report.candidates[*report.chosen];
        const Intrinsics& k = chosen.camera.intrinsics;
        out["chosen"] = {{"model", std::string(chosen.candidate.name)},
                         {"heldout_rms_px", finite_or_null(chosen.heldout_rms_px)},
                         {"K", {{k.fx, k.skew, k.cx}, {0.0, k.fy, k.cy}, {0.0, 0.0, 1.0}}},
                         {"dist", chosen.camera.lens.coefficients}};
    } else {
        out["chosen"] = nullptr;
    }
    return out.dump(2) + "\n";
}

}  // namespace

// The model and its coefficients by name; a model of many (a splined one), by their count.
std::string lens_text(const Camera& camera) {
    std::string text = std::string(lens_info(camera.lens.type).name);
    if (camera.lens.coefficients.size() > 16) {
        return text + " (" + std::to_string(camera.lens.coefficients.size()) + " coefficients)";
    }
    const auto names = lens_info(camera.lens.type).coefficients.view();
    for (std::size_t i = 0; i < camera.lens.coefficients.size(); ++i) {
        text += " " + std::string(i < names.size() ? names[i] : "c") + " " + format_short(camera.lens.coefficients[i], 6);
    }
    return text;
}

std::vector<Candidate> candidates_from(const std::string& text) {
    std::vector<Candidate> candidates;
    if (text.empty()) return candidates;
    std::size_t begin = 0;
    while (begin <= text.size()) {
        const std::size_t end = std::min(text.find(',', begin), text.size());
        const std::string name = text.substr(begin, end - begin);
        try {
            candidates.push_back(candidate_named(name));
        } catch (const InvalidArgument&) {
            throw UsageError("--model: libcam fit cannot fit '" + name + "'; it fits " + candidate_names());
        }
        begin = end + 1;
    }
    return candidates;
}

CameraFormat output_format_of(const std::string& to, const std::string& output) {
    try {
        if (!to.empty()) return camera_format_from_string(to);
    } catch (const InvalidArgument& error) {
        throw UsageError(std::string("--to: ") + error.what());
    }
    return camera_format_from_path(output).value_or(CameraFormat::Json);
}

std::string candidates_table(const ObservationFitReport& report) {
    std::ostringstream out;
    out << "candidate                  params  rms px    held-out rms px\n";
    for (const ObservationCandidate& c : report.candidates) {
        std::string name(c.candidate.name);
        name.resize(std::max<std::size_t>(name.size(), 26), ' ');
        if (!c.fitted) {
            out << name << " not fitted: " << c.failure << "\n";
            continue;
        }
        std::string params = std::to_string(free_directions(c.candidate).cols());
        params.resize(8, ' ');
        std::string rms = format_short(c.rms_px, 4);
        rms.resize(10, ' ');
        out << name << " " << params << rms << format_short(c.heldout_rms_px, 4) << "\n";
        for (const std::string& flag : c.flags) out << "    " << flag << "\n";
    }
    return out.str();
}

Json candidates_json(const ObservationFitReport& report) {
    Json candidates = Json::array();
    for (const ObservationCandidate& c : report.candidates) {
        Json entry{{"model", std::string(c.candidate.name)}, {"fitted", c.fitted}};
        if (c.fitted) {
            entry["params"] = free_directions(c.candidate).cols();  // the free ones: fx = fy counts once
            entry["rms_px"] = finite_or_null(c.rms_px);
            entry["heldout_rms_px"] = finite_or_null(c.heldout_rms_px);
            entry["flags"] = c.flags;
        } else {
            entry["failure"] = c.failure;
        }
        candidates.push_back(entry);
    }
    return candidates;
}

int run_fit_observations(const ObservationFitFlags& flags) {
    const ObservationSet set = read_observations(flags.source);
    const int camera = camera_of(set, flags.camera);
    const Reprojection reprojection = reproject(set);
    std::vector<std::size_t> of_camera;
    for (std::size_t i = 0; i < set.observations.size(); ++i) {
        if (set.views[static_cast<std::size_t>(set.observations[i].view)].camera == camera) of_camera.push_back(i);
    }
    const ResidualStats file_fit = residual_stats(set, reprojection.residuals, of_camera);
    const std::vector<FitView> views = fit_views(set, reprojection, camera);
    ObservationFitOptions options;
    options.candidates = flags.candidates;
    options.folds = flags.folds;
    options.margin = flags.margin;
    const ObservationFitReport report = fit_observations(set.cameras[static_cast<std::size_t>(camera)].camera, views, options);
    if (report.chosen && !flags.output.empty()) {
        write_camera_file(flags.output, report.candidates[*report.chosen].camera, output_format_of(flags.to, flags.output));
    }
    emit(flags.json ? format_json(set, camera, file_fit, report) : format_text(set, camera, file_fit, report), "");
    return report.chosen ? 0 : 1;
}

}  // namespace libcam::cli
