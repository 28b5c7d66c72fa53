// libcam fit SOURCE: the simplest lens model that reproduces a camera over a scene
// within a pixel tolerance, with what every candidate would cost.

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "camera_options.hpp"
#include "fit_observations.hpp"
#include "commands.hpp"
#include "json_output.hpp"
#include "libcam/convert/blender_camera.hpp"
#include "libcam/convert/look_at_convert.hpp"
#include "libcam/error.hpp"
#include "libcam/fit/fit.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/report/fit_heatmap.hpp"
#include "libcam/text/number_format.hpp"
#include "parse.hpp"
#include "progress.hpp"

namespace libcam::cli {

namespace {


struct FitFlags {
    std::string source;
    std::string radius;
    std::string center;
    std::string roi;
    std::string max_angle;
    std::string tolerance = "1";
    bool with_rotation = false;
    std::string depth;
    std::string grid;
    std::string models;
    FileSelection selection;
    bool json = false;
    std::string output;
    std::string to;
    std::string heatmap;
    std::string observations;
    int folds = 5;
    double margin = 0.05;
    std::string progress;
};

void add_flags(CLI::App& command, FitFlags& flags) {
    auto* source = command.add_option("source", flags.source,
                                      "Camera file (any format libcam reads: libcam info lists its cameras)");
    auto* observations = command.add_option(
        "--observations", flags.observations,
        "Instead of a camera: a calibration's or reconstruction's observations (what libcam reproject reads); "
        "each model is fitted to them, intrinsics and every view's pose, and judged on views held out of the fit");
    source->excludes(observations);
    command.add_option("--folds", flags.folds, "With --observations: the views are dealt into this many folds")
        ->capture_default_str()
        ->check(CLI::Range(2, 1000))
        ->needs(observations);
    command.add_option("--margin", flags.margin,
                       "With --observations: the chosen model's held-out RMS may exceed the best one's by this "
                       "fraction")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 10.0))
        ->needs(observations);
    flags.selection.add_to(command);
    auto* radius = command.add_option("--radius", flags.radius, "Scene: a circle of this radius in pixels ...");
    command.add_option("--center", flags.center, "... around this pixel x,y (default: the image centre)")->needs(radius);
    auto* roi = command.add_option("--roi", flags.roi, "Scene: the rectangle x0,y0,x1,y1 (OpenCV pixels)");
    auto* angle = command.add_option("--max-angle", flags.max_angle,
                                     "Scene: the pixels whose ray is within DEG of the optical axis");
    radius->excludes(roi)->excludes(angle);
    roi->excludes(angle);
    command.add_option("--tolerance", flags.tolerance, "Largest reprojection error allowed in the scene, pixels")
        ->capture_default_str();
    auto* rotation = command.add_flag("--with-rotation", flags.with_rotation,
                                      "The fitted camera may rotate (and, with --depth, shift its centre), as "
                                      "mrcal-convert-lensmodel's fit; default: a fit on rays alone");
    command.add_option("--depth", flags.depth, "NEAR,FAR: points at these distances along each ray")->needs(rotation);
    command.add_option("--grid", flags.grid,
                       "Fitting lattice COLSxROWS over the image's pixel centres (mrcal's --gridn); default: "
                       "sized to the scene. The error is checked on a lattice 4x denser");
    command.add_option("--model", flags.models,
                       "Fit only these models, comma-separated, simplest first (default: LOOK_AT, the graphics camera "
                       "with one focal length and a centred principal point, then PINHOLE, OPENCV4, "
                       "OPENCV5, OPENCV8, OPENCV12, and FISHEYE, STEREOGRAPHIC for wide scenes). Also on request: "
                       "DOUBLE_SPHERE, UCM, EUCM, MEI, EQUISOLID, the thin-prism fisheyes, and Blender's "
                       "FISHEYE_LENS_POLYNOMIAL (square pixels, sensor 36 mm wide)");
    command.add_flag("--json", flags.json, "Print JSON");
    add_progress_option(&command, flags.progress, "after the fit's first second");
    command.add_option("-o,--output", flags.output, "Write the chosen camera to this file (written atomically)");
    command.add_option("--to", flags.to,
                       "Format for -o (default: from the extension, else json): " + written_formats_help());
    command.add_option("--heatmap", flags.heatmap, "Write the chosen model's error over the image as a PNG");
}

Scene scene_from(const FitFlags& flags, const ImageSize& size) {
    if (!flags.radius.empty()) {
        const Vec2 center = flags.center.empty() ? Vec2(size.centre_x(), size.centre_y()) : parse_vec2("--center", flags.center);
        return Scene::circle(parse_number("--radius", flags.radius), center);
    }
    if (!flags.roi.empty()) {
        const std::vector<double> corners = parse_numbers("--roi", flags.roi, 4);
        return Scene::rectangle({corners[0], corners[1]}, {corners[2], corners[3]});
    }
    if (!flags.max_angle.empty()) return Scene::field_angle(parse_number("--max-angle", flags.max_angle));
    return Scene::whole_image();
}

Lattice lattice_from(const std::string& text) {
    const ImageSize counts = parse_size("--grid", text);
    if (counts.width < 2 || counts.height < 2) {
        throw UsageError("--grid: expected at least 2x2 lattice points, got '" + text + "'");
    }
    return {counts.width, counts.height};
}

// Prints progress on stderr: a line when a candidate starts, and one a second while a long
// one runs. By default only once the fit has run for a second (a quick fit prints
// nothing); --progress always from the start, never not at all.
class ProgressPrinter {
public:
    explicit ProgressPrinter(ProgressMode mode) : mode_(mode) {}

    void operator()(const FitProgress& progress) {
        if (mode_ == ProgressMode::Never) return;
        const auto now = Clock::now();
        if (mode_ == ProgressMode::Auto && now - start_ < std::chrono::seconds(1)) return;
        if (progress.candidate_index == last_candidate_ && now - last_line_ < std::chrono::seconds(1)) return;
        last_candidate_ = progress.candidate_index;
        last_line_ = now;
        std::cerr << "libcam fit: " << progress.model << " (" << progress.candidate_index + 1 << " of "
                  << progress.candidate_count << "), iteration " << progress.iteration << ", "
                  << std::fixed << std::setprecision(1) << std::chrono::duration<double>(now - start_).count()
                  << " s\n" << std::defaultfloat;
    }

private:
    using Clock = std::chrono::steady_clock;
    ProgressMode mode_;
    Clock::time_point start_ = Clock::now();
    Clock::time_point last_line_;
    int last_candidate_ = -1;
};

// Three significant digits; "-" for a largest error that is infinite (the model leaves
// part of the scene unprojected: the covers column says so).
std::string short_number(double value) { return std::isinf(value) ? "-" : format_short(value); }

std::string motion_text(const FitOptions& options) {
    switch (options.motion) {
        case CameraMotion::None: return "on rays alone (the camera keeps its pose)";
        case CameraMotion::Rotation: return "the camera may rotate; rays alone";
        case CameraMotion::RotationAndShift: break;
    }
    std::string depths;
    for (const double d : options.depths) depths += (depths.empty() ? "" : ", ") + format_number(d);
    return "the camera may rotate and shift; points at depths " + depths;
}

std::string vec_text(const Vec3& v) {
    return format_number(v.x() + 0.0) + "," + format_number(v.y() + 0.0) + "," + format_number(v.z() + 0.0);
}

// The chosen look-at camera as a renderer takes it: fov on each axis, size, and the flags
// that make it again with `libcam convert`.
std::string fov_text(const Camera& camera) {
    const LookAtCamera fov = to_look_at_camera(camera, FovAxis::Horizontal);
    const FovDescription description = describe_fov(camera);
    const auto ten_digits = [](double value) { return format_short(value, 10); };
    std::ostringstream out;
    out << "  look-at camera: fov horizontal " << ten_digits(description.fov_deg.horizontal) << " deg, vertical "
        << ten_digits(description.fov_deg.vertical) << " deg, diagonal " << ten_digits(description.fov_deg.diagonal)
        << " deg; size " << camera.size.width << "x" << camera.size.height << "; f " << ten_digits(camera.intrinsics.fx)
        << " px\n";
    out << "  as flags: --fov " << format_number(fov.fov_deg) << " --fov-axis horizontal --size " << camera.size.width << "x"
        << camera.size.height << " --eye " << vec_text(fov.eye) << " --gaze " << vec_text(fov.gaze) << " --up "
        << vec_text(fov.up) << "\n";
    return out.str();
}

// A fitted Blender camera (FISHEYE_LENS_POLYNOMIAL) as Blender's settings. Its
// fisheye_fov is twice the scene's largest angle: Blender renders black past it, where
// the polynomial was not fitted to the lens.
BlenderCamera blender_of(const Camera& camera, const FitReport& report) {
    BlenderCamera blender = blender_from_camera(camera);
    blender.fisheye_fov = std::min(blender.fisheye_fov, 2 * radians_from_degrees(report.largest_angle_deg));
    return blender;
}

std::string blender_text(const Camera& camera, const FitReport& report) {
    const BlenderCamera blender = blender_of(camera, report);
    std::ostringstream out;
    out << "  Blender: FISHEYE_LENS_POLYNOMIAL, resolution " << blender.size.width << "x" << blender.size.height
        << ", sensor fit horizontal, sensor width " << format_number(blender.sensor_width_mm) << " mm, shift_x "
        << format_number(blender.shift_x) << ", shift_y " << format_number(blender.shift_y) << ", fisheye_fov "
        << format_number(degrees_from_radians(blender.fisheye_fov)) << " deg\n";
    out << "  fisheye_polynomial_k0..k4: ";
    for (std::size_t i = 0; i < blender.fisheye_polynomial.size(); ++i) {
        out << (i == 0 ? "" : " ") << format_number(blender.fisheye_polynomial[i]);
    }
    out << "\n";
    return out.str();
}

Json blender_json(const Camera& camera, const FitReport& report) {
    const BlenderCamera blender = blender_of(camera, report);
    return {{"type", "FISHEYE_LENS_POLYNOMIAL"},
            {"resolution", {blender.size.width, blender.size.height}},
            {"sensor_fit", "HORIZONTAL"},
            {"sensor_width", blender.sensor_width_mm},
            {"shift_x", blender.shift_x},
            {"shift_y", blender.shift_y},
            {"fisheye_fov", blender.fisheye_fov},
            {"fisheye_polynomial", blender.fisheye_polynomial}};
}

// What was fitted: the source, the scene and its samples, the motion, the tolerance.
std::string format_setup(const std::string& source_name, const Camera& source, const Scene& scene,
                         const FitOptions& options, const FitReport& report) {
    std::ostringstream out;
    out << "source     " << source_name << ": " << lens_info(source.lens.type).name << ", " << source.size.width << "x"
        << source.size.height << "\n";
    out << "scene      " << scene.describe(source.size) << "; rays up to " << short_number(report.largest_angle_deg)
        << " deg from the optical axis\n";
    out << "samples    " << report.sampling.fit.pixels.size() << " pixels to fit (" << report.sampling.fit.boundary_count
        << " on the boundary), " << report.sampling.check.pixels.size() << " to check the error on; "
        << report.sampling.check.skipped << " scene pixels have no ray through the source (skipped)\n";
    out << "fit        " << motion_text(options) << "\n";
    out << "tolerance  " << format_number(options.tolerance_px) << " px\n";
    return out.str();
}

std::string format_candidates(const FitReport& report) {
    int name_width = 15;  // "STEREOGRAPHIC" and a gap; wider for a longer name asked for
    for (const CandidateReport& entry : report.candidates) {
        name_width = std::max(name_width, static_cast<int>(entry.fit.candidate.name.size()) + 2);
    }
    std::ostringstream out;
    out << std::left << std::setw(name_width) << "model" << std::right << std::setw(7) << "params" << std::setw(12) << "rms_px"
        << std::setw(12) << "max_px" << std::setw(8) << "covers" << std::setw(6) << "pass" << "\n";
    for (const CandidateReport& entry : report.candidates) {
        out << std::left << std::setw(name_width) << entry.fit.candidate.name << std::right << std::setw(7)
            << entry.fit.candidate.num_params() << std::setw(12) << short_number(entry.rms_px) << std::setw(12)
            << short_number(entry.max_px) << std::setw(8) << (entry.covers_scene ? "yes" : "no") << std::setw(6)
            << (entry.pass ? "yes" : "no") << "\n";
    }
    out << "(rms over the fitting samples, max over the check samples; " << report.fit_observations << " and "
        << report.check_observations << " observations)\n";
    return out.str();
}

std::string format_choice(const Camera& source, const FitOptions& options, const FitReport& report) {
    const CandidateReport& chosen = report.candidates[*report.chosen];
    const int params = chosen.fit.candidate.num_params();
    std::ostringstream out;
    out << "chosen: " << chosen.fit.candidate.name << " (" << params << (params == 1 ? " parameter" : " parameters")
        << "), max error " << short_number(chosen.max_px) << " px <= " << format_number(options.tolerance_px) << " px\n";
    if (chosen.fit.candidate.look_at) out << fov_text(camera_in_world(chosen.fit, source));
    if (chosen.fit.candidate.lens == LensType::LensPolynomial) out << blender_text(chosen.fit.camera, report);
    return out.str();
}

std::string format_table(const std::string& source_name, const Camera& source, const Scene& scene,
                         const FitOptions& options, const FitReport& report) {
    return format_setup(source_name, source, scene, options, report) + "\n" + format_candidates(report) + "\n" +
           format_choice(source, options, report);
}

Json chosen_json(const CandidateReport& chosen, const Camera& source, const FitOptions& options, const FitReport& report) {
    Json out = {{"model", chosen.fit.candidate.name},
                          {"params", chosen.fit.params},
                          {"rms_px", finite_or_null(chosen.rms_px)},
                          {"max_px", finite_or_null(chosen.max_px)}};
    if (options.motion != CameraMotion::None) {
        const Pose& motion = chosen.fit.camera.pose;
        out["motion"] = {{"rvec", {motion.rvec().x(), motion.rvec().y(), motion.rvec().z()}},
                         {"shift", {motion.t.x(), motion.t.y(), motion.t.z()}}};
    }
    if (chosen.fit.candidate.look_at) {
        const FovDescription fov = describe_fov(camera_in_world(chosen.fit, source));
        out["fov_deg"] = {{"horizontal", fov.fov_deg.horizontal},
                          {"vertical", fov.fov_deg.vertical},
                          {"diagonal", fov.fov_deg.diagonal}};
        out["image_size"] = {source.size.width, source.size.height};
    }
    if (chosen.fit.candidate.lens == LensType::LensPolynomial) out["blender"] = blender_json(chosen.fit.camera, report);
    return out;
}

std::string format_json(const Camera& source, const Scene& scene, const FitOptions& options, const FitReport& report) {
    Json out;
    out["chosen"] = chosen_json(report.candidates[*report.chosen], source, options, report);
    out["candidates"] = Json::array();
    for (const CandidateReport& entry : report.candidates) {
        out["candidates"].push_back({{"model", entry.fit.candidate.name},
                                     {"n_params", entry.fit.candidate.num_params()},
                                     {"rms_px", finite_or_null(entry.rms_px)},
                                     {"max_px", finite_or_null(entry.max_px)},
                                     {"covers_scene", entry.covers_scene},
                                     {"pass", entry.pass}});
    }
    out["tolerance_px"] = options.tolerance_px;
    out["scene"] = {{"description", scene.describe(source.size)},
                    {"fit_pixels", report.sampling.fit.pixels.size()},
                    {"check_pixels", report.sampling.check.pixels.size()},
                    {"skipped_pixels", report.sampling.check.skipped},
                    {"largest_angle_deg", report.largest_angle_deg}};
    return out.dump(2) + "\n";
}

// One line naming every candidate's largest error, for the failure message; for a
// splined source fitted on rays alone, the hint that its spline may turn the image.
std::string no_choice_message(const Camera& source, const FitOptions& options, const FitReport& report) {
    std::string errors;
    for (const CandidateReport& entry : report.candidates) {
        errors += (errors.empty() ? "" : ", ") + std::string(entry.fit.candidate.name) + " " +
                  (entry.covers_scene ? short_number(entry.max_px) + " px" : "does not cover the scene");
    }
    std::string message = "no candidate model meets the tolerance " + format_number(options.tolerance_px) +
                          " px over the scene (largest errors: " + errors + ")";
    if (source.lens.type == LensType::SplinedStereographic && options.motion == CameraMotion::None) {
        message += "; a splined model may also turn the image about its axis: try --with-rotation";
    }
    return message;
}

CameraFormat output_format(const FitFlags& flags) { return output_format_of(flags.to, flags.output); }

FitOptions options_from(const FitFlags& flags) {
    FitOptions options;
    options.tolerance_px = parse_number("--tolerance", flags.tolerance);
    if (!flags.depth.empty()) {
        const std::vector<double> range = parse_numbers("--depth", flags.depth, 2);
        if (!(range[0] > 0.0 && range[1] > range[0])) {
            throw InvalidArgument("--depth: expected 0 < NEAR < FAR, got '" + flags.depth + "'");
        }
        options.depths = range;
    }
    options.motion = !flags.with_rotation    ? CameraMotion::None
                     : options.depths.empty() ? CameraMotion::Rotation
                                              : CameraMotion::RotationAndShift;
    if (!flags.grid.empty()) options.lattice = lattice_from(flags.grid);
    options.candidates = candidates_from(flags.models);
    return options;
}

// Files first, so that a failure to write one leaves stdout empty.
void write_outputs(const FitFlags& flags, const Camera& source, const Scene& scene, const FitOptions& options,
                   const FitReport& report) {
    const CandidateReport& chosen = report.candidates[*report.chosen];
    if (!flags.output.empty()) {
        const Camera camera = camera_in_world(chosen.fit, source);
        WriteOptions write;
        if (chosen.fit.candidate.look_at) write.look_at_camera = to_look_at_camera(camera, FovAxis::Horizontal);
        write_camera_file(flags.output, camera, output_format(flags), write);
    }
    if (!flags.heatmap.empty()) write_png(flags.heatmap, fit_heatmap(source, scene, options, chosen));
}

}  // namespace

Runner add_fit(CLI::App& app) {
    CLI::App* command = add_command(app, "fit");
    auto flags = std::make_shared<FitFlags>();
    add_flags(*command, *flags);

    return [flags] {
        const ProgressMode progress_when = progress_mode(flags->progress);  // a bad value is a usage error before any work
        if (!flags->observations.empty()) {
            if (!flags->heatmap.empty()) throw UsageError("--heatmap: not with --observations (libcam reproject draws them)");
            ObservationFitFlags fit;
            fit.source = flags->observations;
            fit.camera = flags->selection.camera;
            fit.candidates = candidates_from(flags->models);
            fit.folds = flags->folds;
            fit.margin = flags->margin;
            fit.json = flags->json;
            fit.output = flags->output;
            if (!flags->to.empty()) output_format(*flags);  // a bad --to is a usage error before any work
            fit.to = flags->to;
            return run_fit_observations(fit);
        }
        if (flags->source.empty()) throw UsageError("a camera file, or --observations FILE, is required");
        FitOptions options = options_from(*flags);
        if (!flags->to.empty()) output_format(*flags);  // a bad --to is a usage error before any work
        const Camera source = flags->selection.read(flags->source).camera;
        const Scene scene = scene_from(*flags, source.size);
        ProgressPrinter printer(progress_when);
        options.progress = [&](const FitProgress& progress) { printer(progress); };
        const FitReport report = fit_scene(source, scene, options);
        if (!report.chosen) throw Error(no_choice_message(source, options, report));
        write_outputs(*flags, source, scene, options, report);
        emit(flags->json ? format_json(source, scene, options, report)
                         : format_table(flags->source, source, scene, options, report),
             "");
        return 0;
    };
}

}  // namespace libcam::cli
