// libcam calibrate IMAGES_OR_DIR... --board SPEC: a folder of board images to a
// calibration, the lens model chosen by views held out of the fit (libcam/calibrate/).

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <limits>
#include <memory>
#include <iostream>
#include <mutex>
#include <sstream>

#include "commands.hpp"
#include "fit_observations.hpp"
#include "json_output.hpp"
#include "libcam/calibrate/calibrate.hpp"
#include "libcam/calibrate/calibration_json.hpp"
#include "libcam/calibrate/mrcal_solve.hpp"
#include "libcam/calibrate/pair_list.hpp"
#include "libcam/calibrate/pair_output.hpp"
#include "libcam/calibrate/observations_output.hpp"
#include "libcam/calibrate/opencv_flags.hpp"
#include "libcam/error.hpp"
#include "libcam/interop/mrcal.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/io/camera_file.hpp"
#include "libcam/io/kalibr_rig.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/text/shown_value.hpp"
#include "libcam/uncertainty/uncertainty_map.hpp"
#include "camera_options.hpp"
#include "parse.hpp"
#include "progress.hpp"
#include "uncertainty_output.hpp"

namespace libcam::cli {

namespace {

// mrcal-show-projection-uncertainty's default grid: 60 points across.
constexpr long kHeatmapColumns = 60;

struct CalibrateFlags {
    std::vector<std::string> inputs;
    std::vector<std::string> left;
    std::vector<std::string> right;
    std::string pairs;
    std::string board;
    std::string models;
    std::string opencv_flags;
    std::string corners = "libcam";
    int folds = 5;
    double margin = 0.05;
    bool keep_outliers = false;
    bool json = false;
    std::string output;
    std::string to;
    std::string observations_out;
    std::vector<std::string> at;
    std::string heatmap;
    int threads = 0;
    std::string progress;
};

void add_flags(CLI::App& command, CalibrateFlags& flags) {
    command.add_option("images", flags.inputs, "Board images, or folders of them (their .jpg, .png, ... files)");
    command.add_option("--left", flags.left,
                       "A stereo pair: the left camera's board images (or folders), each with the right image of the "
                       "same board view at the same place in --right; -o then names a folder for the pair's files");
    command.add_option("--right", flags.right, "A stereo pair: the right camera's board images (or folders)");
    command.add_option("--pairs", flags.pairs,
                       "A stereo pair's image list as OpenCV's stereo_calib sample reads it (stereo_calib.xml: left "
                       "and right images in turn; names relative to the list's folder), instead of --left and --right");
    command.add_option("--board", flags.board,
                       "The board: chessboard:CxR:SQUARE (C x R inner corners, square side in metres) or "
                       "charuco:CxR:SQUARE:MARKER:DICT (C x R squares, marker side, OpenCV's dictionary, e.g. "
                       "DICT_5X5_100; laid out as OpenCV 4.6's CharucoBoard)")
        ->required();
    command.add_option("--model", flags.models,
                       "Fit these models, comma-separated, simplest first; auto (default): PINHOLE, OPENCV4, "
                       "OPENCV5, OPENCV8, FISHEYE, and STEREOGRAPHIC where the corners reach 45 degrees from the axis");
    command.add_option("--opencv-flags", flags.opencv_flags,
                       "Hold what OpenCV's calibrateCamera flags hold, to reproduce a calibration made with them: "
                       "FIX_ASPECT_RATIO (fx = fy), ZERO_TANGENT_DIST (p1 = p2 = 0), FIX_K1 ... FIX_K6 (that "
                       "coefficient at 0); OpenCV's names (CALIB_ optional), comma-separated, or the number its files "
                       "store (flags: 2)");
    command.add_option("--corners", flags.corners,
                       "How a chessboard's corners are found: libcam (default; findChessboardCornersSB, each corner "
                       "refined in a window within its own squares) or opencv-sample (as OpenCV's calibration sample: "
                       "findChessboardCorners, cornerSubPix in an 11x11 window), to reproduce its results")
        ->capture_default_str()
        ->check(CLI::IsMember({"libcam", "opencv-sample"}));
    command.add_option("--folds", flags.folds, "The views are dealt into this many folds for the held-out RMS")
        ->capture_default_str()
        ->check(CLI::Range(2, 1000));
    command.add_option("--margin", flags.margin,
                       "The chosen model's held-out RMS may exceed the best one's by this fraction")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 10.0));
    command.add_flag("--keep-outliers", flags.keep_outliers,
                     "Fit every corner found, none dropped as an outlier (as OpenCV's calibrateCamera takes them)");
    command.add_flag("--json", flags.json, "Print JSON");
    command.add_option("-o,--output", flags.output, "Write the chosen calibration to this file (written atomically)");
    command.add_option("--to", flags.to,
                       "Format for -o (default: from the extension, else json): " + written_formats_help());
    command.add_option("--observations-out", flags.observations_out,
                       "Write the corners and board poses as OpenCV's calibration sample does (YAML), for "
                       "libcam reproject and libcam fit --observations");
    command.add_option("--at", flags.at,
                       "Pixels x,y (OpenCV's) where the chosen model's projection uncertainty is reported (points at "
                       "infinity; for a pair, each camera's in the pair's solve); repeat for more");
    command.add_option("--heatmap", flags.heatmap,
                       "Write a PNG of the chosen model's projection uncertainty over the image, with the corners");
    command.add_option("--threads", flags.threads, "Images searched at once (default: one per processor)")
        ->check(CLI::Range(1, 1024));
    add_progress_option(&command, flags.progress, "after the first second");
}

bool is_image_name(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const char* known : {".jpg", ".jpeg", ".png", ".bmp", ".tif", ".tiff", ".pgm", ".ppm", ".pnm", ".webp"}) {
        if (extension == known) return true;
    }
    return false;
}

// The images named, a folder's images (sorted by name) in its place.
std::vector<std::filesystem::path> images_of(const std::vector<std::string>& inputs) {
    std::vector<std::filesystem::path> images;
    for (const std::string& input : inputs) {
        std::error_code error;
        if (!std::filesystem::is_directory(input, error)) {
            images.emplace_back(input);
            continue;
        }
        std::vector<std::filesystem::path> found;
        for (const auto& entry : std::filesystem::directory_iterator(input, error)) {
            if (entry.is_regular_file(error) && is_image_name(entry.path())) found.push_back(entry.path());
        }
        if (error) throw FileError(input + ": cannot list the folder: " + error.message());
        std::sort(found.begin(), found.end());
        if (found.empty()) throw FileError(input + ": the folder holds no images (.jpg, .png, .bmp, .tif, .pgm, ...)");
        images.insert(images.end(), found.begin(), found.end());
    }
    return images;
}

// Progress lines on stderr: auto prints once a second after the first second, always
// from the start, never not at all.
class ProgressPrinter {
public:
    explicit ProgressPrinter(ProgressMode mode) : mode_(mode) {}

    void found(std::size_t done, std::size_t total) {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (!due(done == total)) return;
        line("searched " + std::to_string(done) + " of " + std::to_string(total) + " images");
    }
    void stage(const std::string& what) {
        const std::lock_guard<std::mutex> lock(mutex_);
        if (mode_ == ProgressMode::Never || (mode_ == ProgressMode::Auto && elapsed() < 1.0)) return;
        line(what);
    }

private:
    using Clock = std::chrono::steady_clock;
    double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
    bool due(bool last) {
        if (mode_ == ProgressMode::Never) return false;
        if (mode_ == ProgressMode::Auto && elapsed() < 1.0) return false;
        const auto now = Clock::now();
        if (!last && now - last_line_ < std::chrono::seconds(1)) return false;
        last_line_ = now;
        return true;
    }
    void line(const std::string& what) {
        std::cerr << "libcam calibrate: " << what << ", " << std::fixed << std::setprecision(1) << elapsed() << " s\n"
                  << std::defaultfloat;
    }
    ProgressMode mode_;
    std::mutex mutex_;
    Clock::time_point start_ = Clock::now();
    Clock::time_point last_line_;
};

std::string view_name(const std::string& image) { return std::filesystem::path(image).filename().string(); }

// Where outliers were dropped: "left02.jpg (2), left05.jpg (1)".
std::string outlier_places(const Calibration& c) {
    std::string places;
    for (const CalibrationView& view : c.views) {
        if (view.outlier_ids.empty()) continue;
        places += (places.empty() ? "" : ", ") + view_name(view.image) + " (" + std::to_string(view.outlier_ids.size()) + ")";
    }
    return places;
}

// The worst sigma inside the region the corners covered, in pixels; a model that has no ray
// for some pixel there (a fitted lens folding over inside it) has no bound to give.
std::string worst_observed_text(double sigma_px, int digits) {
    return std::isnan(sigma_px) ? std::string("none (a pixel there has no ray)") : format_short(sigma_px, digits) + " px";
}

// Each candidate's projection uncertainty beside its held-out RMS.
std::string uncertainty_table(const Calibration& c) {
    std::ostringstream out;
    out << "projection uncertainty (worst direction, points at infinity), with the noise the residuals imply:\n"
        << "candidate                  held-out rms px  noise px  sigma centre px  worst observed px\n";
    for (std::size_t i = 0; i < c.fit.candidates.size(); ++i) {
        const ObservationCandidate& candidate = c.fit.candidates[i];
        if (!candidate.fitted) continue;
        std::string name(candidate.candidate.name);
        name.resize(std::max<std::size_t>(name.size(), 27), ' ');
        const CandidateUncertainty& u = c.uncertainty[i];
        if (!u.computed) {
            out << name << "not computed: " << u.failure << "\n";
            continue;
        }
        const auto cell = [](double value, std::size_t width) {
            std::string text = format_short(value, 4);
            text.resize(std::max(text.size() + 1, width), ' ');
            return text;
        };
        out << name << cell(candidate.heldout_rms_px, 17) << cell(u.noise_px, 10) << cell(u.centre_px, 17)
            << (std::isnan(u.worst_observed_px) ? std::string("no ray at some pixel") : format_short(u.worst_observed_px, 4))
            << "\n";
    }
    return out.str();
}

// The chosen model's uncertainty (points at infinity) at the --at pixels, or at the image
// centre when none is given.
struct ChosenUncertainty {
    std::vector<Vec2> pixels;
    std::vector<double> sigma_px;
};
ChosenUncertainty chosen_uncertainty(const Calibration& c, const std::vector<std::string>& at) {
    ChosenUncertainty out;
    out.pixels = at.empty() ? std::vector<Vec2>{Vec2(c.size.centre_x(), c.size.centre_y())} : at_pixels(at, c.size);
    out.sigma_px = chosen_sigma_px(c, out.pixels);
    return out;
}

std::string format_text(const Calibration& c, const ChosenUncertainty& at) {
    const ObservationCandidate& chosen = c.chosen();
    const Intrinsics& k = chosen.camera.intrinsics;
    std::ostringstream out;
    out << c.images << " images, " << c.views.size() << " used, " << c.rejected.size() << " rejected; " << c.corners()
        << " corners of " << c.board.text() << "\n";
    for (const RejectedImage& r : c.rejected) out << "  rejected " << r.image << ": " << r.why << "\n";
    if (c.outliers > 0) {
        out << c.outliers << " outlier corners dropped (beyond 5 sigma of the fit's noise, "
            << format_short(c.noise_px, 3) << " px per coordinate): " << outlier_places(c) << "\n";
    }
    if (c.rounds_capped) {
        out << "the outlier rounds stopped after " << c.rounds << " fits with corners still beyond the limit\n";
    }
    if (c.held.any()) out << "held in every model, as OpenCV's flags ask: " << c.held.text() << "\n";
    out << "\n" << candidates_table(c.fit) << "\n" << uncertainty_table(c) << "\n";
    out << "chosen: " << c.fit.reason << "\n";
    out << "  image size " << c.size.width << "x" << c.size.height << "\n";
    out << "  K: fx " << format_short(k.fx, 8) << ", fy " << format_short(k.fy, 8) << ", cx " << format_short(k.cx, 8)
        << ", cy " << format_short(k.cy, 8) << " (OpenCV's pixels)\n";
    out << "  lens: " << lens_text(chosen.camera) << "\n";
    out << "  rms " << format_short(chosen.rms_px, 4) << " px, held-out rms " << format_short(chosen.heldout_rms_px, 4)
        << " px\n";
    const CandidateUncertainty& u = c.uncertainty[*c.fit.chosen];
    if (u.computed) {
        out << "  projection uncertainty (worst direction, points at infinity): worst inside the region the corners "
               "covered "
            << worst_observed_text(u.worst_observed_px, 4) << "\n"
            << at_lines(at.pixels, at.sigma_px);
    } else {
        out << "  projection uncertainty: not computed: " << u.failure << "\n";
    }
    out << "\nview                      corners  rms px\n";
    for (std::size_t v = 0; v < c.views.size(); ++v) {
        std::string name = view_name(c.views[v].image);
        name.resize(std::max<std::size_t>(name.size(), 26), ' ');
        std::string corners = std::to_string(c.views[v].ids.size());
        corners.resize(9, ' ');
        out << name << corners << format_short(c.view_rms_px(v), 4) << "\n";
    }
    return out.str();
}

std::string format_json(const Calibration& c, const ChosenUncertainty& at) {
    return calibration_json(c, at.pixels, at.sigma_px);
}

CameraFormat output_format(const CalibrateFlags& flags) { return output_format_of(flags.to, flags.output); }

BoardSpec board_from(const std::string& text) {
    try {
        return parse_board_spec(text);
    } catch (const InvalidArgument& error) {
        throw UsageError(std::string("--board: ") + error.what());
    }
}

HeldParameters opencv_flags_from(const std::string& text) {
    try {
        return held_by_opencv_flags(text);
    } catch (const InvalidArgument& error) {
        throw UsageError(error.what());
    }
}

// The chosen model's uncertainty over the image, with the corners kept.
void write_heatmap(const std::string& path, const Calibration& c) {
    const SolvedCalibration solved = c.solved(*c.fit.chosen);
    std::unique_ptr<ProjectionUncertainty> uncertainty;
    try {
        uncertainty = std::make_unique<ProjectionUncertainty>(solved);
    } catch (const InvalidArgument& error) {
        throw Error(path + ": the projection uncertainty cannot be computed: " + error.what());
    }
    const UncertaintyMap map = uncertainty_map(*uncertainty, kHeatmapColumns, kAtInfinity);
    const UncertaintySummary summary = summarize(map, observed_region(solved));
    write_uncertainty_heatmap(path, map, solved,
                              std::string(c.chosen().candidate.name) + ", points at infinity: worst observed " +
                                  worst_observed_text(summary.worst_observed_px, 3));
}

// The solve's optimization_inputs for a .cameramodel, or why mrcal cannot hold it.
struct SolveText {
    std::string inputs;
    std::string why_not;
};
SolveText solve_text(const std::function<std::string()>& solve) {
    try {
        return {solve(), ""};
    } catch (const NotRepresentable& error) {
        return {"", error.what()};
    }
}

// Said on stderr once the model is written without its solve.
void say_without_solve(const std::string& file, const std::string& why_not) {
    std::cerr << "libcam calibrate: " << file << ": written without the solve (mrcal's optimization_inputs), so "
              << "neither libcam uncertainty nor mrcal's tools can take it: " << why_not << "\n";
}

// Files first, so that a failure to write one leaves stdout empty.
void write_outputs(const CalibrateFlags& flags, const Calibration& c) {
    if (!flags.output.empty()) {
        // A .cameramodel with its solve where mrcal can hold it (then mrcal has the lens);
        // otherwise the camera as -o writes it in any format, refused there, naming the file,
        // where the format cannot hold it.
        const CameraFormat format = output_format(flags);
        const SolveText solve = format == CameraFormat::Cameramodel ? solve_text([&] { return mrcal_solve_inputs(c); })
                                                                    : SolveText{};
        if (!solve.inputs.empty()) {
            write_file_atomically(flags.output, format_cameramodel(c.chosen().camera, solve.inputs, 0));
        } else {
            write_camera_file(flags.output, c.chosen().camera, format);
            if (!solve.why_not.empty()) say_without_solve(flags.output, solve.why_not);
        }
    }
    if (!flags.heatmap.empty()) write_heatmap(flags.heatmap, c);
    if (flags.observations_out.empty()) return;
    ObservationsText text;
    try {
        text = format_opencv_observations(c);
    } catch (const NotRepresentable& error) {
        throw Error(flags.observations_out + ": " + error.what());
    }
    write_file_atomically(flags.observations_out, text.text);
    if (text.left_out > 0) {
        std::cerr << "libcam calibrate: " << flags.observations_out << ": " << text.left_out
                  << " views that saw part of the board left out (OpenCV's calibration output holds whole boards)\n";
    }
}

// The pair's text report: each camera's model and K after the joint fit, R and T.
// "  sigma 0.031 px at the centre (319.5, 239.5), 0.12 px at (10, 10): ..." of one camera.
std::string pair_uncertainty_text(const PairUncertainty& u, const ImageSize& size) {
    if (!u.failure.empty()) return "  no projection uncertainty: " + u.failure + "\n";
    std::string out = "  projection uncertainty in the pair's solve (points at infinity):";
    for (std::size_t i = 0; i < u.pixels.size(); ++i) {
        const Vec2& p = u.pixels[i];
        const bool centre = p.x() == size.centre_x() && p.y() == size.centre_y();
        out += std::string(i == 0 ? " " : ", ") + "sigma " + format_short(u.sigma_px[i], 3) + " px at " +
               (centre ? "the centre " : "") + "(" + format_short(p.x(), 8) + ", " + format_short(p.y(), 8) + ")";
    }
    return out + "\n";
}

std::string format_pair_text(const PairCalibration& pair, const std::vector<Vec2>& at) {
    std::ostringstream out;
    out << pair.pairs.size() << " views used by both cameras (left: " << pair.first.views.size() << " of "
        << pair.first.images << ", right: " << pair.second.views.size() << " of " << pair.second.images << ")\n";
    for (const RejectedImage& r : pair.first.rejected) out << "  rejected " << r.image << ": " << r.why << "\n";
    for (const RejectedImage& r : pair.second.rejected) out << "  rejected " << r.image << ": " << r.why << "\n";
    const auto camera_line = [&](const char* name, const Calibration& alone, const Camera& camera, int side) {
        const Intrinsics& k = camera.intrinsics;
        out << name << ": " << alone.fit.reason << "\n  after the joint fit: fx " << format_short(k.fx, 8) << ", fy "
            << format_short(k.fy, 8) << ", cx " << format_short(k.cx, 8) << ", cy " << format_short(k.cy, 8) << "; "
            << lens_text(camera) << "\n";
        out << pair_uncertainty_text(pair_uncertainty(pair, side, at), camera.size);
    };
    camera_line("left", pair.first, pair.first_camera, 0);
    camera_line("right", pair.second, pair.second_camera, 1);
    const Pose& pose = pair.second_camera.pose;
    out << "right from left (X_right = R X_left + T): rvec " << format_short(pose.rvec().x(), 6) << " "
        << format_short(pose.rvec().y(), 6) << " " << format_short(pose.rvec().z(), 6) << " rad, T "
        << format_short(pose.t.x(), 6) << " " << format_short(pose.t.y(), 6) << " " << format_short(pose.t.z(), 6)
        << " (baseline " << format_short(pose.t.norm(), 6) << ", the board's unit)\n";
    out << "rms " << format_short(pair.rms_px, 4) << " px over both cameras' corners in the views both used\n";
    return out.str();
}

// -o DIR for a pair: OpenCV's stereo_calib files (intrinsics.yml, extrinsics.yml), the two
// cameras as mrcal .cameramodel files (the right one posed from the left) and as a Kalibr
// camchain (camchain.yaml), each where its format holds the pair's models (else one line
// says why). Every text is made before any file is written.
void write_pair_outputs(const std::string& folder, const PairCalibration& pair) {
    std::vector<std::pair<std::filesystem::path, std::string>> files;
    const std::filesystem::path dir(folder);
    // One form's files, all or none.
    using Named = std::vector<std::pair<std::string, std::string>>;  // file names and texts
    const auto add = [&](const std::string& what, const std::function<Named()>& make) {
        try {
            for (auto& [name, text] : make()) files.emplace_back(dir / name, std::move(text));
        } catch (const NotRepresentable& error) {
            std::cerr << "libcam calibrate: " << folder << ": " << what << " not written: " << error.what() << "\n";
        }
    };
    add("intrinsics.yml and extrinsics.yml", [&] {
        OpenCvStereoFiles opencv = format_opencv_stereo(pair);
        return Named{{"intrinsics.yml", std::move(opencv.intrinsics)}, {"extrinsics.yml", std::move(opencv.extrinsics)}};
    });
    add("the .cameramodel files", [&] {
        // Each camera's model holds the whole solve, as mrcal-calibrate-cameras writes a pair.
        Named models{{"left.cameramodel", format_camera(pair.first_camera, CameraFormat::Cameramodel)},
                     {"right.cameramodel", format_camera(pair.second_camera, CameraFormat::Cameramodel)}};
        const SolveText solve = solve_text([&] { return mrcal_solve_inputs(pair); });
        if (solve.inputs.empty()) {
            say_without_solve(folder + ": left.cameramodel and right.cameramodel", solve.why_not);
        } else {
            models[0].second = format_cameramodel(pair.first_camera, solve.inputs, 0);
            models[1].second = format_cameramodel(pair.second_camera, solve.inputs, 1);
        }
        return models;
    });
    add("camchain.yaml", [&] {
        return Named{{"camchain.yaml", format_kalibr_rig({pair.first_camera, pair.second_camera})}};
    });
    if (files.empty()) {
        throw Error(folder + ": neither OpenCV's stereo files, mrcal's models nor Kalibr's camchain can hold this pair");
    }
    std::error_code error;
    std::filesystem::create_directories(dir, error);
    if (error) throw FileError(folder + ": cannot create the folder: " + error.message());
    for (const auto& [path, text] : files) write_file_atomically(path, text);
}

int run_pair(const CalibrateFlags& flags, const BoardSpec& board, const CalibrationOptions& options,
             ProgressMode progress_when) {
    if (!flags.inputs.empty()) throw UsageError("--left and --right take the pair's images: no images before them");
    if (!flags.pairs.empty() && (!flags.left.empty() || !flags.right.empty())) {
        throw UsageError("--pairs names the pair's images: not with --left or --right");
    }
    if (flags.pairs.empty() && (flags.left.empty() || flags.right.empty())) {
        throw UsageError("a pair needs both --left and --right images");
    }
    if (!flags.heatmap.empty() || !flags.observations_out.empty() || !flags.to.empty()) {
        throw UsageError("--heatmap, --observations-out and --to are for one camera, not a pair");
    }
    for (const std::string& pixel : flags.at) parse_vec2("--at", pixel);  // on the images: checked once their sizes are known
    const CornerMethod method = flags.corners == "opencv-sample" ? CornerMethod::OpenCvSample : CornerMethod::Libcam;
    std::vector<std::filesystem::path> lists[2];
    if (!flags.pairs.empty()) {
        PairList list = read_pair_list(flags.pairs);
        lists[0] = std::move(list.left);
        lists[1] = std::move(list.right);
    } else {
        lists[0] = images_of(flags.left);
        lists[1] = images_of(flags.right);
    }
    std::vector<BoardDetection> found[2];
    for (int side = 0; side < 2; ++side) {
        const std::vector<std::filesystem::path>& images = lists[side];
        ProgressPrinter printer(progress_when);
        found[side] = detect_boards(
            images, board, flags.threads, [&](std::size_t done) { printer.found(done, images.size()); }, method);
    }
    const PairCalibration pair = calibrate_pair(found[0], found[1], board, options);
    std::vector<Vec2> at;
    if (!flags.at.empty()) {
        at = at_pixels(flags.at, pair.first_camera.size);
        at_pixels(flags.at, pair.second_camera.size);  // on both images
    }
    if (!flags.output.empty()) write_pair_outputs(flags.output, pair);
    emit(flags.json ? pair_calibration_json(pair, at) : format_pair_text(pair, at), "");
    return 0;
}

}  // namespace

Runner add_calibrate(CLI::App& app) {
    CLI::App* command = add_command(app, "calibrate");
    auto flags = std::make_shared<CalibrateFlags>();
    add_flags(*command, *flags);
    return [flags, command] {
        // Every flag checked before any work.
        const ProgressMode progress_when = progress_mode(flags->progress);
        const BoardSpec board = board_from(flags->board);
        CalibrationOptions options;
        if (command->count("--opencv-flags") > 0) options.held = opencv_flags_from(flags->opencv_flags);
        options.candidates = flags->models == "auto" ? std::vector<Candidate>{} : candidates_from(flags->models);
        options.folds = flags->folds;
        options.margin = flags->margin;
        if (flags->keep_outliers) options.outlier_sigmas = std::numeric_limits<double>::infinity();
        if (!flags->left.empty() || !flags->right.empty() || !flags->pairs.empty()) {
            return run_pair(*flags, board, options, progress_when);
        }
        if (!flags->output.empty()) output_format(*flags);
        if (flags->inputs.empty()) throw UsageError("give the board images (or --left and --right for a pair)");
        for (const std::string& pixel : flags->at) parse_vec2("--at", pixel);  // on the image: checked once its size is known
        const std::vector<std::filesystem::path> images = images_of(flags->inputs);
        ProgressPrinter printer(progress_when);
        const std::vector<BoardDetection> detections = detect_boards(
            images, board, flags->threads, [&](std::size_t done) { printer.found(done, images.size()); },
            flags->corners == "opencv-sample" ? CornerMethod::OpenCvSample : CornerMethod::Libcam);
        options.stage = [&](const std::string& what) { printer.stage(what); };
        const Calibration calibration = calibrate(detections, board, options);
        const ChosenUncertainty at = chosen_uncertainty(calibration, flags->at);
        write_outputs(*flags, calibration);
        emit(flags->json ? format_json(calibration, at) : format_text(calibration, at), "");
        return 0;
    };
}

}  // namespace libcam::cli
