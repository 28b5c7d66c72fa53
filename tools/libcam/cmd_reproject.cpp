// libcam reproject SRC: every observation a calibration or reconstruction file holds,
// reprojected through libcam's projection of the cameras and poses the file's tool solved
// (reproject/reproject.hpp); the statistics, each number the file stored beside libcam's
// recomputation of it, the pixel-centre check, the worst observations; --json,
// --observations-out (one CSV row per observation) and --heatmap (the residual field).

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "json_output.hpp"
#include "libcam/reproject/reproject.hpp"
#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/observations.hpp"
#include "libcam/text/number_format.hpp"
#include "parse.hpp"

namespace libcam::cli {

namespace {

ReprojectionHeatmapWriter heatmap_writer = nullptr;

struct Flags {
    std::string source;
    std::string camera;
    std::string camera_file;
    std::string image_size;
    bool json = false;
    std::string observations_out;
    std::string heatmap;
    int worst = 10;
    int threads = 0;
};

// The index of the camera --camera names; a usage error naming the flag otherwise.
int camera_index(const ObservationSet& set, const std::string& selector) {
    try {
        return observed_camera_index(set, selector);
    } catch (const InvalidArgument& error) {
        throw UsageError(std::string("--camera: ") + error.what());
    }
}

// The observations of one camera's views. The file's own numbers are about every camera,
// so they go: a recomputation over one camera would not be theirs.
ObservationSet only_camera(ObservationSet set, int camera) {
    std::vector<Observation> kept;
    for (const Observation& o : set.observations) {
        if (set.views[static_cast<std::size_t>(o.view)].camera == camera) kept.push_back(o);
    }
    set.observations = std::move(kept);
    set.reported.clear();
    set.reported_per_view.clear();
    set.reported_per_point.clear();
    return set;
}

std::string pixel_convention(const ObservationSet& set) {
    if (set.pixel_offset == Vec2(0.5, 0.5)) return "the top-left pixel's centre at (0.5, 0.5), as the file has them";
    if (set.pixel_offset == Vec2::Zero()) return "the top-left pixel's centre at (0, 0), as the file has them";
    return "the file's own, offset (" + format_short(set.pixel_offset.x(), 6) + ", " +
           format_short(set.pixel_offset.y(), 6) + ") from OpenCV's";
}

std::string stats_line(const ResidualStats& r) {
    const ErrorStats& s = r.stats;
    if (s.count == 0) return "no observation counted";
    std::ostringstream out;
    out << "rms " << format_short(s.rms_px, 4) << "  mean " << format_short(r.mean_px, 4) << "  median "
        << format_short(s.median_px, 4) << "  p99 " << format_short(s.p99_px, 4) << "  max "
        << format_short(s.max_px, 4);
    if (r.weighted_rms_px) out << "  weighted rms " << format_short(*r.weighted_rms_px, 4);
    return out.str();
}

std::string vector_text(const Vec2& v, int digits = 3) {
    return "(" + format_short(v.x(), digits) + ", " + format_short(v.y(), digits) + ")";
}

// The largest number of views the text lists one by one; beyond it, the worst by RMS.
constexpr std::size_t kViewsListed = 20;

void print_views(std::ostream& out, const std::vector<GroupResiduals>& views) {
    std::vector<std::size_t> order(views.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    const bool all = views.size() <= kViewsListed;
    if (!all) {
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            return views[a].residuals.stats.rms_px > views[b].residuals.stats.rms_px;
        });
        order.resize(kViewsListed);
    }
    out << (all ? "per view" : "the " + std::to_string(kViewsListed) + " views of largest RMS (--json lists all " +
                                   std::to_string(views.size()) + ")")
        << ": count, then residual |d| in px\n";
    for (const std::size_t i : order) {
        out << "  " << views[i].name << "  " << views[i].residuals.stats.count << "  "
            << stats_line(views[i].residuals) << "\n";
    }
}

std::string format_text(const ObservationSet& set, const Reprojection& r, std::size_t worst) {
    const ReprojectionSummary& s = r.summary;
    std::ostringstream out;
    out << set.source << ": " << to_string(set.tool) << ", " << set.cameras.size() << " camera"
        << (set.cameras.size() == 1 ? "" : "s") << ", " << set.views.size() << " views, " << set.points.size()
        << " points, " << set.observations.size() << " observations\n";
    out << "pixels: " << pixel_convention(set) << "; residual d = projected - observed\n";
    out << "counted " << s.all.stats.count << " (not counted: " << s.outliers << " outliers, " << s.behind_camera
        << " behind the camera, " << s.outside_domain << " past the lens's valid domain, " << s.outside_image
        << " off the image)\n";
    out << "residual |d| px: " << stats_line(s.all) << "\n";
    out << "mean residual (x, y) px: " << vector_text(s.all.bias) << "\n";
    if (!s.reported.empty() || s.per_view_reported || s.per_point_reported) {
        out << "\nthe file's own numbers, recomputed by libcam:\n";
        for (const ReportedComparison& c : s.reported) {
            out << "  " << c.reported.key << ": stored " << format_number(c.reported.value) << ", recomputed "
                << format_number(c.recomputed) << "\n    (" << definition_of(c.reported.measure) << ")\n";
        }
        if (s.per_view_reported) {
            out << "  per view (RMS of each view): " << s.per_view_reported->compared
                << " compared, largest difference " << format_short(s.per_view_reported->max_abs_difference)
                << " px (" << s.per_view_reported->worst_item << ")\n";
        }
        if (s.per_point_reported) {
            out << "  per point (mean |d| over its track): " << s.per_point_reported->compared
                << " compared, largest difference " << format_short(s.per_point_reported->max_abs_difference)
                << " px (point " << s.per_point_reported->worst_item << ")\n";
        }
        if (s.reported_past_domain > 0) {
            out << "  by the tool's rule: every observation, the " << s.reported_past_domain
                << " past the lens's valid domain too, projected there by the model's formula as the tool itself "
                   "did (the statistics above set them apart)\n";
        }
    }
    const ConventionCheck& c = s.convention;
    out << "\npixel-centre check: the best constant shift of every projection is " << vector_text(c.best_shift_px)
        << " px; half a pixel " << vector_text(Vec2(std::copysign(0.5, c.best_shift_px.x()),
                                                    std::copysign(0.5, c.best_shift_px.y())), 2)
        << " would give rms " << format_short(c.rms_half_shift_px, 4) << " against " << format_short(c.rms_px, 4)
        << ": "
        << (c.suspect ? "SUSPECT: the observations fit the other pixel-centre convention markedly better"
                      : "no sign of the other pixel-centre convention")
        << "\n\n";
    if (set.cameras.size() > 1) {
        out << "per camera: count, then residual |d| in px\n";
        for (const GroupResiduals& g : s.per_camera) {
            out << "  " << g.name << "  " << g.residuals.stats.count << "  " << stats_line(g.residuals) << "\n";
        }
    }
    print_views(out, s.per_view);
    const std::vector<std::size_t> worst_indices = worst_observations(r.residuals, worst);
    if (!worst_indices.empty()) {
        out << "\nthe " << worst_indices.size() << " largest residuals (view, point, observed, projected, |d| px):\n";
        for (const std::size_t i : worst_indices) {
            const Observation& o = set.observations[i];
            out << "  " << set.views[static_cast<std::size_t>(o.view)].name << "  "
                << set.point_ids[static_cast<std::size_t>(o.point)] << "  "
                << vector_text(o.pixel + set.pixel_offset, 7) << "  "
                << vector_text(r.residuals[i].projected + set.pixel_offset, 7) << "  "
                << format_short(r.residuals[i].error_px, 4) << "\n";
        }
    }
    return out.str();
}

Json group_json(const GroupResiduals& g) {
    Json out;
    out["name"] = g.name;
    out["count"] = g.residuals.stats.count;
    const bool measured = g.residuals.stats.count > 0;
    out["rms_px"] = measured ? finite_or_null(g.residuals.stats.rms_px) : Json(nullptr);
    out["mean_px"] = measured ? finite_or_null(g.residuals.mean_px) : Json(nullptr);
    put_error_stats(out, g.residuals.stats, measured, {"median_px", "max_px"});
    if (g.residuals.weighted_rms_px) out["weighted_rms_px"] = finite_or_null(*g.residuals.weighted_rms_px);
    return out;
}

Json item_comparison_json(const PerItemComparison& c) {
    return Json{{"compared", c.compared}, {"max_abs_difference_px", finite_or_null(c.max_abs_difference)},
                {"worst", c.worst_item}};
}

std::string format_json(const ObservationSet& set, const Reprojection& r, std::size_t worst) {
    const ReprojectionSummary& s = r.summary;
    const bool measured = s.all.stats.count > 0;
    Json out;
    out["source"] = set.source;
    out["tool"] = std::string(to_string(set.tool));
    out["pixel_offset"] = {set.pixel_offset.x(), set.pixel_offset.y()};
    out["cameras"] = set.cameras.size();
    out["views"] = set.views.size();
    out["points"] = set.points.size();
    out["observations"] = set.observations.size();
    out["count"] = s.all.stats.count;
    out["rms_px"] = measured ? finite_or_null(s.all.stats.rms_px) : Json(nullptr);
    out["mean_px"] = measured ? finite_or_null(s.all.mean_px) : Json(nullptr);
    put_error_stats(out, s.all.stats, measured, {"median_px", "p99_px", "max_px"});
    out["bias_px"] = {s.all.bias.x(), s.all.bias.y()};
    if (s.all.weighted_rms_px) out["weighted_rms_px"] = finite_or_null(*s.all.weighted_rms_px);
    out["not_counted"] = {{"outliers", s.outliers},
                          {"behind_camera", s.behind_camera},
                          {"outside_domain", s.outside_domain},
                          {"outside_image", s.outside_image}};
    Json reported = Json::object();
    Json recomputed = Json::object();
    Json definitions = Json::object();
    for (const ReportedComparison& c : s.reported) {
        reported[c.reported.key] = finite_or_null(c.reported.value);
        recomputed[c.reported.key] = finite_or_null(c.recomputed);
        definitions[c.reported.key] = std::string(definition_of(c.reported.measure));
    }
    out["reported"] = reported;
    out["recomputed"] = recomputed;
    out["definitions"] = definitions;
    out["recomputed_past_domain"] = s.reported_past_domain;
    if (s.per_view_reported) out["per_view_reported"] = item_comparison_json(*s.per_view_reported);
    if (s.per_point_reported) out["per_point_reported"] = item_comparison_json(*s.per_point_reported);
    out["convention_check"] = {{"best_shift_px", {s.convention.best_shift_px.x(), s.convention.best_shift_px.y()}},
                               {"rms_px", finite_or_null(s.convention.rms_px)},
                               {"rms_half_shift_px", finite_or_null(s.convention.rms_half_shift_px)},
                               {"suspect", s.convention.suspect}};
    Json per_camera = Json::array();
    for (const GroupResiduals& g : s.per_camera) per_camera.push_back(group_json(g));
    out["per_camera"] = per_camera;
    Json per_view = Json::array();
    for (const GroupResiduals& g : s.per_view) per_view.push_back(group_json(g));
    out["per_view"] = per_view;
    Json worst_list = Json::array();
    for (const std::size_t i : worst_observations(r.residuals, worst)) {
        const Observation& o = set.observations[i];
        const Vec2 observed = o.pixel + set.pixel_offset;
        const Vec2 projected = r.residuals[i].projected + set.pixel_offset;
        worst_list.push_back({{"view", set.views[static_cast<std::size_t>(o.view)].name},
                              {"point", set.point_ids[static_cast<std::size_t>(o.point)]},
                              {"observed", {observed.x(), observed.y()}},
                              {"projected", {projected.x(), projected.y()}},
                              {"error_px", r.residuals[i].error_px}});
    }
    out["worst"] = worst_list;
    return out.dump(2) + "\n";
}

// A CSV field: quoted when it holds a comma, a quote or a line break (RFC 4180).
std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (const char c : text) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    return quoted + "\"";
}

// A number with every digit a double needs to come back; empty where there is none.
std::string csv_number(double value) { return std::isfinite(value) ? format_number(value) : std::string(); }

std::string observations_csv(const ObservationSet& set, const Reprojection& r) {
    std::string out = "view,point,observed_x,observed_y,projected_x,projected_y,error_px,inlier\n";
    out.reserve(out.size() + 96 * set.observations.size());
    for (std::size_t i = 0; i < set.observations.size(); ++i) {
        const Observation& o = set.observations[i];
        const ObservationResidual& residual = r.residuals[i];
        const Vec2 observed = o.pixel + set.pixel_offset;
        const Vec2 projected = residual.projected + set.pixel_offset;
        out += csv_field(set.views[static_cast<std::size_t>(o.view)].name);
        out += ',' + std::to_string(set.point_ids[static_cast<std::size_t>(o.point)]);
        out += ',' + csv_number(observed.x()) + ',' + csv_number(observed.y());
        out += ',' + csv_number(projected.x()) + ',' + csv_number(projected.y());
        out += ',' + csv_number(residual.error_px);
        out += o.inlier ? ",1\n" : ",0\n";
    }
    return out;
}

}  // namespace

void set_reprojection_heatmap_writer(ReprojectionHeatmapWriter writer) { heatmap_writer = writer; }

Runner add_reproject(CLI::App& app) {
    CLI::App* command = add_command(app, "reproject");
    auto flags = std::make_shared<Flags>();
    command
        ->add_option("SRC", flags->source,
                     "A file or folder of observations: OpenCV's calibration output (out_camera_data.yml or .xml), "
                     "a .cameramodel with mrcal's optimization_inputs, a COLMAP model folder, OpenSfM's "
                     "reconstruction.json, OpenMVG's sfm_data.json, AliceVision's cameras.sfm, VisualSfM's .nvm, Bundler's "
                     "bundle.out (with --image-size), or a .csv/.json table with --camera-file")
        ->required();
    command->add_option("--camera", flags->camera, "Only the views of this camera (its name in the file, or its position from 0)");
    command->add_option("--camera-file", flags->camera_file,
                        "For a table of observations: the camera file whose cameras its `camera` column names");
    command->add_option("--image-size", flags->image_size,
                        "The image size WIDTHxHEIGHT, for a file that stores none (VisualSfM's .nvm, Bundler's "
                        "bundle.out): every image of the file has it");
    command->add_flag("--json", flags->json,
                      "Print {\"count\", \"rms_px\", \"mean_px\", \"median_px\", \"p99_px\", \"max_px\", \"per_view\", "
                      "\"reported\", \"recomputed\", \"convention_check\", ...}");
    command->add_option("--observations-out", flags->observations_out,
                        "Write one CSV row per observation (outliers included): view,point,observed_x,observed_y,"
                        "projected_x,projected_y,error_px,inlier, in the file's own pixels");
    command->add_option("--heatmap", flags->heatmap,
                        "Write a PNG: the residual field over the image (arrows and magnitude per region) and each "
                        "view's RMS");
    command->add_option("--worst", flags->worst, "How many of the largest residuals to list")
        ->capture_default_str()
        ->check(CLI::Range(0, 1000000));
    command->add_option("--threads", flags->threads, "Threads that project (0: one per core)")
        ->capture_default_str()
        ->check(CLI::Range(0, 1024));

    return [flags] {
        ObservationReadOptions options{.camera_file = flags->camera_file};
        if (!flags->image_size.empty()) options.size = parse_size("--image-size", flags->image_size);
        ObservationSet set = read_observations(flags->source, options);
        if (!flags->camera.empty()) set = only_camera(std::move(set), camera_index(set, flags->camera));
        const Reprojection reprojection = reproject(set, flags->threads);
        const auto worst = static_cast<std::size_t>(flags->worst);
        // The files first: a failure to write one leaves nothing on stdout.
        if (!flags->observations_out.empty()) {
            write_file_atomically(flags->observations_out, observations_csv(set, reprojection));
        }
        if (!flags->heatmap.empty()) {
            if (heatmap_writer == nullptr) throw Error("--heatmap: drawn by the commands module, which is not loaded");
            heatmap_writer(flags->heatmap, set, reprojection);
        }
        emit(flags->json ? format_json(set, reprojection, worst) : format_text(set, reprojection, worst), "");
        return 0;
    };
}

}  // namespace libcam::cli
