// libcam dataset: a whole COLMAP reconstruction into pinhole cameras, its images
// undistorted and its observations moved (libcam/dataset/colmap_dataset.hpp).

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/error.hpp"
#include "libcam/dataset/colmap_dataset.hpp"
#include "libcam/text/number_format.hpp"
#include "parse.hpp"
#include "progress.hpp"

namespace libcam::cli {

namespace {

namespace fs = std::filesystem;

// Progress on stderr: images done, the rate and the time left. On a terminal one line,
// redrawn at most five times a second; elsewhere (a log, a pipe) nothing by default, and
// with --progress always a plain line at most once a second and one at the end.
class ProgressLine {
public:
    explicit ProgressLine(ProgressMode mode)
        : terminal_(isatty(STDERR_FILENO) == 1),
          shown_(mode == ProgressMode::Always || (mode == ProgressMode::Auto && terminal_)),
          start_(std::chrono::steady_clock::now()) {}
    ~ProgressLine() { finish(); }
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;

    void update(std::size_t done, std::size_t total) {
        if (!shown_) return;
        const auto now = std::chrono::steady_clock::now();
        const auto every = terminal_ ? std::chrono::milliseconds(200) : std::chrono::milliseconds(1000);
        if (done < total && now - last_ < every) return;
        last_ = now;
        const double seconds = std::chrono::duration<double>(now - start_).count();
        const double rate = seconds > 0 ? static_cast<double>(done) / seconds : 0.0;
        const double left = rate > 0 ? static_cast<double>(total - done) / rate : 0.0;
        std::fprintf(stderr, "%simages %zu of %zu, %.1f images/s, %.0f s left%s", terminal_ ? "\r\x1b[K" : "", done,
                     total, rate, left, terminal_ ? "" : "\n");
        std::fflush(stderr);
        drawn_ = terminal_;
    }
    // Ends the line, before the summary is printed.
    void finish() {
        if (drawn_) std::fputs("\n", stderr);
        drawn_ = false;
    }
    // A line of its own above the progress line.
    void say(const std::string& line) {
        if (drawn_) std::fputs("\r\x1b[K", stderr);
        std::cerr << line << "\n";
    }

private:
    bool terminal_;
    bool shown_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point start_, last_{};
};

struct DatasetFlags {
    std::string source;
    std::string output;
    std::string images;
    std::string camera = "valid";
    std::string size;
    std::string interpolation = "cubic";
    int jpeg_quality = kDefaultJpegQuality;
    int threads = 0;
    bool text = false;
    bool no_images = false;
    bool json = false;
    bool masks = false;
    std::string to = "colmap";
    std::string progress;
};

std::string summary_text(const DatasetSummary& s, double seconds, bool with_images) {
    std::string out = "model: " + s.model_out.string() + (s.finished ? "" : " (not written yet: the run is unfinished)") + "\n";
    for (const DatasetCamera& camera : s.cameras) {
        const Intrinsics& k = camera.camera.intrinsics;
        const std::string view = camera.views > 1 ? " view " + std::to_string(camera.view) + " of " +
                                                        std::to_string(camera.views) + " (yaw " + format_short(camera.yaw_deg, 3) +
                                                        " deg, pitch " + format_short(camera.pitch_deg, 3) + " deg)"
                                                  : "";
        const std::string from = camera.views > 1 || camera.id != camera.source_id ? " (source camera " + std::to_string(camera.source_id) + ")" : "";
        out += "camera " + std::to_string(camera.id) + from + view + ": " + camera.source_model + " " +
               std::to_string(camera.source.size.width) + "x" + std::to_string(camera.source.size.height) +
               " -> PINHOLE " + std::to_string(camera.camera.size.width) + "x" + std::to_string(camera.camera.size.height) +
               " fx " + format_short(k.fx, 8) + " fy " + format_short(k.fy, 8) + " cx " + format_short(k.cx, 8) + " cy " +
               format_short(k.cy, 8) + " (OpenCV's pixels), " + std::to_string(camera.images) + " images, " +
               std::to_string(camera.observations) + " observations" +
               (camera.view == 0 ? ": " + camera.why : std::string()) + "\n";
    }
    out += "observations: " + std::to_string(s.observations_kept) + " of " + std::to_string(s.observations_in) +
           " kept (" + std::to_string(s.observations_in - s.observations_kept) + " land off their new image" +
           (s.model_images_out != s.images_in ? "; each counted once, however many views hold it" : "") + ")\n";
    out += "points: " + std::to_string(s.points_kept) + " of " + std::to_string(s.points_in) + " kept\n";
    if (with_images) {
        out += "images: " + std::to_string(s.images_written + s.images_kept) + " of " + std::to_string(s.model_images_out) +
               (s.finished ? " in the output (" : " made, not yet in the output (") + std::to_string(s.images_written) +
               " written, " + std::to_string(s.images_kept) + " already there, " + std::to_string(s.images_failed) +
               " failed)\n";
        if (s.model_images_out != s.images_in) out += "images: " + std::to_string(s.model_images_out) +
                                                      " in the model, the views of " + std::to_string(s.images_in) + "\n";
    }
    out += "time: " + format_short(seconds, 3) + " s\n";
    return out;
}

int run_dataset(const DatasetFlags& flags) {
    if (flags.threads < 0) throw UsageError("--threads: expected 0 (one per core) or more");
    if (flags.no_images && !flags.images.empty()) throw UsageError("--images: not with --no-images");
    DatasetOptions options;
    options.model = flags.source;
    options.output = flags.output;
    try {
        set_dataset_camera(options, flags.camera,
                           flags.size.empty() ? std::nullopt : std::optional<ImageSize>(parse_size("--size", flags.size)));
    } catch (const InvalidArgument& error) {
        throw UsageError(std::string("--") + error.what());
    }
    options.threads = worker_count(flags.threads);
    options.text = flags.text;
    if (flags.jpeg_quality < 1 || flags.jpeg_quality > 100) {
        throw UsageError("--jpeg-quality: expected 1 to 100, got " + std::to_string(flags.jpeg_quality));
    }
    options.jpeg_quality = flags.jpeg_quality;
    options.masks = flags.masks;
    if (flags.masks && flags.no_images) throw UsageError("--masks: not with --no-images");
    if (flags.to == "nerf") {
        options.to = DatasetFormat::Nerf;
        if (flags.text) throw UsageError("--text: not with --to nerf (transforms.json is text)");
    } else if (flags.to != "colmap") {
        throw UsageError("--to: expected colmap or nerf, got '" + flags.to + "'");
    }
    try {
        options.interpolation = interpolation_from_string(flags.interpolation);
    } catch (const InvalidArgument& error) {
        throw UsageError(std::string("--") + error.what());
    }
    if (!flags.no_images) options.images = flags.images.empty() ? default_dataset_images(flags.source) : fs::path(flags.images);
    if (!options.images.empty() && !fs::is_directory(options.images)) {
        throw FileError(options.images.string() + ": no such images folder (give --images, or --no-images)");
    }
    auto progress = std::make_shared<ProgressLine>(progress_mode(flags.progress));
    options.on_image_error = [progress](const std::string& line) { progress->say("libcam: error: " + line); };
    options.on_progress = [progress](std::size_t done, std::size_t total) { progress->update(done, total); };
    const auto start = std::chrono::steady_clock::now();
    const DatasetSummary summary = make_pinhole_dataset(options);
    progress->finish();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    emit(flags.json ? dataset_summary_json(summary, seconds) : summary_text(summary, seconds, !flags.no_images), "");
    if (summary.finished) return 0;
    progress->say("libcam: error: " + std::to_string(summary.images_failed) + " of " +
                  std::to_string(summary.model_images_out) + " images failed: " + options.output.string() +
                  " is as it was; this run's work is kept in " + staging_folder(options.output).string() +
                  ", and running the same command again finishes it");
    return 1;
}

}  // namespace

Runner add_dataset(CLI::App& app) {
    CLI::App* command = add_command(app, "dataset");
    auto flags = std::make_shared<DatasetFlags>();
    command->add_option("SRC", flags->source,
                        "A COLMAP model folder (cameras, images, points3D; .bin or .txt), or NeRF's transforms.json "
                        "(its frames' cameras and poses; no points)")
        ->required();
    command->add_option("-o,--output", flags->output,
                        "The folder to write: sparse/0/ (the model; --to nerf: transforms.json) and images/, made "
                        "in OUT/.libcam-dataset-partial and moved in when every image is there (a failed run leaves "
                        "OUT as it was; the same command again finishes it)")
        ->required();
    command->add_option("--to", flags->to,
                        "colmap: OUT/sparse/0 (a transforms.json's cameras deduplicated, an empty points3D); nerf: "
                        "OUT/transforms.json (nerfstudio's and instant-ngp's layout, file_path images/<name>, the "
                        "source's applied_transform kept) and, from a COLMAP model with points, OUT/sparse_pc.ply")
        ->capture_default_str();
    command->add_option("--images", flags->images,
                        "The source images (default: images beside the model's grandparent: X/images for X/sparse/0; "
                        "for a transforms.json its folder, or its images/ when every file_path is under it)");
    command->add_option("--camera", flags->camera,
                        "Each new pinhole: valid (every pixel has a source: no black borders), all (keeps every "
                        "source pixel), fov:DEG (this horizontal field of view) or views (a lens wider than one "
                        "pinhole holds well split into several pinhole views, each its own camera and images "
                        "<stem>_view<k><ext>, together holding every pixel's ray)")
        ->capture_default_str();
    command->add_option("--size", flags->size, "The new cameras' image size WIDTHxHEIGHT (default: each source's)");
    command->add_option("--interpolation", flags->interpolation, "nearest, linear, cubic or lanczos (cv::remap)")
        ->capture_default_str();
    command->add_option("--jpeg-quality", flags->jpeg_quality, "The quality of the images written as JPEG, 1 to 100")
        ->capture_default_str();
    command->add_option("--threads", flags->threads, "Images worked on at once, and threads per map (0: one per core)")
        ->capture_default_str();
    command->add_flag("--text", flags->text, "Write the model as text (cameras.txt, ...) instead of binary");
    command->add_flag("--no-images", flags->no_images, "Write the model alone");
    command->add_flag("--masks", flags->masks,
                      "Also write masks/<image name>.png: 255 where the pixel has a source pixel, 0 where it is black");
    add_progress_option(command, flags->progress, "a line redrawn on a terminal, nothing in a log or a pipe");
    command->add_flag("--json", flags->json,
                      "Print {\"observations_in\", \"observations_kept\", \"images_in\", \"images_out\", \"cameras\", "
                      "\"time_s\", ...}");
    return [flags] { return run_dataset(*flags); };
}

}  // namespace libcam::cli
