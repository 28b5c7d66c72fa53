// libcam uncertainty FILE: how far a calibration can be trusted at each pixel, mrcal's
// projection uncertainty (libcam/uncertainty/), from the observations the file holds.

#include <cmath>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "fit_observations.hpp"
#include "json_output.hpp"
#include "libcam/error.hpp"
#include "libcam/io/observations.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/uncertainty/uncertainty_map.hpp"
#include "parse.hpp"
#include "uncertainty_output.hpp"

namespace libcam::cli {

namespace {

// mrcal-show-projection-uncertainty's default grid: 60 points across.
constexpr long kGridColumns = 60;

struct Flags {
    std::string source;
    std::string camera;
    std::vector<std::string> at;
    double distance = kAtInfinity;
    bool grid = false;
    bool json = false;
    std::string heatmap;
};

void add_flags(CLI::App& command, Flags& flags) {
    command.add_option("file", flags.source,
                       "A calibration with its observations: mrcal's .cameramodel with optimization_inputs, OpenCV's "
                       "calibration output with image_points and extrinsic_parameters, or libcam calibrate "
                       "--observations-out's file")
        ->required();
    command.add_option("--camera", flags.camera, "Which camera of a file that holds several (name or position)");
    command.add_option("--at", flags.at, "Pixels x,y (OpenCV's) where sigma is reported; repeat for more");
    command.add_option("--distance", flags.distance,
                       "The point's distance along each pixel's ray, in the board's unit (default: infinity)")
        ->check(CLI::PositiveNumber);
    command.add_flag("--grid", flags.grid,
                     "Also print sigma at every point of the 60-wide grid the summary is measured on");
    command.add_flag("--json", flags.json, "Print JSON");
    command.add_option("--heatmap", flags.heatmap,
                       "Write a PNG of sigma over the image (log colour scale, contours at 0.1 and 1 px) with the "
                       "observed corners");
}

std::string text_report(const ObservationSet& set, int camera, const ProjectionUncertainty& uncertainty,
                        const SolvedCalibration& solved, double distance, const UncertaintySummary& summary,
                        const std::vector<Vec2>& at, const std::vector<double>& at_sigma, const UncertaintyMap* grid) {
    std::ostringstream out;
    out << set.source << ": camera " << set.cameras[static_cast<std::size_t>(camera)].name << ", "
        << lens_text(uncertainty.camera()) << "\n";
    out << solved.views.size() << " views, ";
    if (!solved.others.empty()) {
        // A solve of several cameras: its uncertainty is the whole solve's.
        out << "in a solve of " << solved.others.size() + 1 << " cameras sharing " << solved.frames.size()
            << " board poses, ";
    }
    out << uncertainty.observations() << " observations; the noise the fit's residuals imply: "
        << format_short(uncertainty.observed_pixel_uncertainty_px(), 4) << " px\n";
    out << "projection uncertainty (worst direction, " << distance_words(distance) << "):\n";
    out << summary_lines(summary) << at_lines(at, at_sigma);
    out << "intrinsics (value +- standard deviation):\n" << parameter_lines(uncertainty.parameters());
    if (grid != nullptr) {
        out << "grid (x y sigma_px):\n";
        for (std::size_t i = 0; i < grid->pixels.size(); ++i) {
            out << format_short(grid->pixels[i].x(), 6) << " " << format_short(grid->pixels[i].y(), 6) << " "
                << format_short(grid->sigma_px[i], 4) << "\n";
        }
    }
    return out.str();
}

std::string json_report(const ObservationSet& set, int camera, const ProjectionUncertainty& uncertainty,
                        const SolvedCalibration& solved, double distance, const UncertaintySummary& summary,
                        const std::vector<Vec2>& at, const std::vector<double>& at_sigma, const UncertaintyMap* grid) {
    Json out;
    out["source"] = set.source;
    out["camera"] = set.cameras[static_cast<std::size_t>(camera)].name;
    out["model"] = std::string(lens_info(uncertainty.camera().lens.type).name);
    out["views"] = solved.views.size();
    out["observations"] = uncertainty.observations();
    out["distance"] = finite_or_null(distance);
    out["observed_pixel_uncertainty_px"] = uncertainty.observed_pixel_uncertainty_px();
    out["at"] = at_json(at, at_sigma);
    out["worst_observed_sigma_px"] = finite_or_null(summary.worst_observed_px);
    out["share_below_0_1_px"] = summary.share_below_0_1;
    out["share_below_1_px"] = summary.share_below_1;
    out["parameters"] = parameters_json(uncertainty.parameters());
    if (grid != nullptr) {
        Json sigma = Json::array();
        for (const double s : grid->sigma_px) sigma.push_back(finite_or_null(s));
        out["grid"] = {{"columns", grid->columns}, {"rows", grid->rows}, {"sigma_px", sigma}};
    }
    return out.dump(2) + "\n";
}

int camera_of(const ObservationSet& set, const std::string& selector) {
    if (selector.empty()) {
        // Each camera's .cameramodel of an mrcal solve of several holds the whole solve and says which it is.
        if (set.own_camera >= 0) return set.own_camera;
        if (set.cameras.size() > 1) {
            throw UsageError("--camera: " + set.source + " holds " + std::to_string(set.cameras.size()) +
                             " cameras: say which one");
        }
        return 0;
    }
    try {
        return observed_camera_index(set, selector);
    } catch (const InvalidArgument& error) {
        throw UsageError(std::string("--camera: ") + error.what());
    }
}

int run(const Flags& flags) {
    const ObservationSet set = read_observations(flags.source);
    const int camera = camera_of(set, flags.camera);
    const std::vector<Vec2> at = at_pixels(flags.at, set.cameras[static_cast<std::size_t>(camera)].camera.size);
    const SolvedCalibration solved = solved_calibration(set, camera);
    std::unique_ptr<ProjectionUncertainty> uncertainty;
    try {
        uncertainty = std::make_unique<ProjectionUncertainty>(solved);
    } catch (const InvalidArgument& error) {
        throw Error(flags.source + ": " + error.what());
    }
    const std::vector<double> at_sigma = uncertainty->sigma_px(at, flags.distance);
    const UncertaintyMap map = uncertainty_map(*uncertainty, kGridColumns, flags.distance);
    const UncertaintySummary summary = summarize(map, observed_region(solved));
    if (!flags.heatmap.empty()) {
        write_uncertainty_heatmap(flags.heatmap, map, solved,
                                  std::string(lens_info(uncertainty->camera().lens.type).name) + ", " +
                                      distance_words(flags.distance) + ": worst observed " +
                                      format_short(summary.worst_observed_px, 3) + " px");
    }
    const UncertaintyMap* grid = flags.grid ? &map : nullptr;
    emit(flags.json ? json_report(set, camera, *uncertainty, solved, flags.distance, summary, at, at_sigma, grid)
                    : text_report(set, camera, *uncertainty, solved, flags.distance, summary, at, at_sigma, grid),
         "");
    return 0;
}

}  // namespace

Runner add_uncertainty(CLI::App& app) {
    CLI::App* command = add_command(app, "uncertainty");
    auto flags = std::make_shared<Flags>();
    add_flags(*command, *flags);
    return [flags] { return run(*flags); };
}

}  // namespace libcam::cli
