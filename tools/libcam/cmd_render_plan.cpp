// libcam render-plan LENS -o DIR: how to render with Blender through a lens it cannot
// draw: the camera to render with (libcam/remap/render_plan.hpp, or with --fit-blender
// Blender's polynomial fisheye fitted to the lens) and the map that turns the render into
// the lens's image.

#include <filesystem>
#include <iostream>

#include "camera_options.hpp"
#include "commands.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/error.hpp"
#include "libcam/fit/fit.hpp"
#include "libcam/interop/image_remap.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/remap/remap_map.hpp"
#include "libcam/remap/render_plan.hpp"
#include "libcam/text/number_format.hpp"
#include "parse.hpp"

namespace libcam::cli {

namespace {

namespace fs = std::filesystem;

struct RenderPlanFlags {
    FileSelection selection;
    std::string from;
    std::string output;
    bool fit_blender = false;
    std::string tolerance = "0.1";
    std::string map_format = "exr";
    int threads = worker_count(0);
};

// Blender's FISHEYE_LENS_POLYNOMIAL fitted to the lens over its whole image, when its
// worst error is within the tolerance: then the plan is to render with it directly.
std::optional<RenderPlan> fitted_polynomial(const Camera& lens, double tolerance_px) {
    FitOptions options;
    options.tolerance_px = tolerance_px;
    options.candidates = {candidate_named("FISHEYE_LENS_POLYNOMIAL")};
    const FitReport report = fit_scene(lens, Scene::whole_image(), options);
    const CandidateReport& fitted = report.candidates.front();
    const std::string error = fitted.covers_scene ? format_short(fitted.max_px, 3) + " px" : "no fit covering the image";
    if (!report.chosen) {
        std::cout << "fit: Blender's FISHEYE_LENS_POLYNOMIAL reproduces the lens within " << error
                  << ", not within the tolerance " << format_short(tolerance_px) << " px: planning a warp instead\n";
        return std::nullopt;
    }
    return RenderPlan{camera_in_world(fitted.fit, lens), false, {},
                      "Blender's FISHEYE_LENS_POLYNOMIAL fitted to the lens reproduces it within " + error +
                          " over its whole image (tolerance " + format_short(tolerance_px) + " px, rms " +
                          format_short(fitted.rms_px, 3) + " px): render with it, nothing to warp"};
}

int run_render_plan(const RenderPlanFlags& flags) {
    if (flags.output.empty()) throw UsageError("-o: give the folder to write the plan into");
    if (flags.map_format != "exr" && flags.map_format != "npy") {
        throw UsageError("--map-format: expected exr or npy, got '" + flags.map_format + "'");
    }
    if (flags.threads < 1) throw UsageError("--threads: expected 1 or more");
    const double tolerance = parse_number("--tolerance", flags.tolerance);
    if (!(tolerance > 0.0)) throw UsageError("--tolerance: expected a positive number of pixels, got '" + flags.tolerance + "'");

    const Camera lens_camera = flags.selection.read(flags.from).camera;
    const PreparedCamera lens(lens_camera);
    std::optional<RenderPlan> plan;
    if (flags.fit_blender) plan = fitted_polynomial(lens_camera, tolerance);
    if (!plan) plan = plan_render(lens, flags.threads);
    std::cout << "render camera: " << plan->why << "\n";

    const fs::path dir(flags.output);
    fs::create_directories(dir);
    const fs::path script = dir / "render.py", render_json = dir / "render.json", lens_json = dir / "lens.json";
    const fs::path map_file = dir / ("warp." + flags.map_format);
    write_camera_file(script, plan->render, CameraFormat::Blender);
    write_camera_file(render_json, plan->render, CameraFormat::Json);
    write_camera_file(lens_json, lens_camera, CameraFormat::Json);
    std::cout << "wrote " << script.string() << " (sets a Blender scene's camera and resolution: blender -b "
              << "scene.blend -P " << script.string() << " -o //render_ -F OPEN_EXR -f 1)\n"
              << "wrote " << render_json.string() << " (the render camera) and " << lens_json.string()
              << " (the lens)\n";
    // A warp map an earlier plan left in the folder (none now, or in the other format)
    // would be taken for this plan's: removed, and said.
    for (const char* format : {"exr", "npy"}) {
        const fs::path old_map = dir / (std::string("warp.") + format);
        if ((!plan->needs_warp || old_map != map_file) && fs::is_regular_file(old_map)) {
            fs::remove(old_map);
            std::cout << "removed " << old_map.string() << ", an earlier plan's warp map"
                      << (plan->needs_warp ? "" : " (this plan needs none)") << "\n";
        }
    }
    if (!plan->needs_warp) return 0;

    const RemapMap warp = build_remap_map(lens, PreparedCamera(plan->render),
                                          {Mat3::Identity(), UnprojectMethod::Exact, flags.threads});
    write_map_file(map_file, warp);
    std::cout << "wrote " << map_file.string() << " (for each lens pixel, the render pixel it samples; "
              << warp.with_source << " of " << warp.x.size() << " pixels have one)\n"
              << "then: libcam remap --from " << render_json.string() << " --to " << lens_json.string()
              << " RENDER.exr -o OUT_DIR\n";
    return 0;
}

}  // namespace

Runner add_render_plan(CLI::App& app) {
    CLI::App* command = add_command(app, "render-plan");
    auto flags = std::make_shared<RenderPlanFlags>();
    command->add_option("--from", flags->from, "The lens's camera file")->required();
    flags->selection.add_to(*command);
    command->add_option("-o,--output", flags->output,
                        "Folder for render.py (the Blender script), render.json, lens.json and the warp map")
        ->required();
    command->add_flag("--fit-blender", flags->fit_blender,
                      "First try Blender's FISHEYE_LENS_POLYNOMIAL fitted to the lens: render with it when its "
                      "worst error over the image is within --tolerance");
    command->add_option("--tolerance", flags->tolerance, "Pixels, for --fit-blender")->capture_default_str();
    command->add_option("--map-format", flags->map_format, "The warp map's file: exr or npy")->capture_default_str();
    command->add_option("--threads", flags->threads, "Threads that build the map")->capture_default_str();
    return [flags] { return run_render_plan(*flags); };
}

}  // namespace libcam::cli
