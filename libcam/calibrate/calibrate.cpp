#include "libcam/calibrate/calibrate.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>

#include "libcam/error.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/text/number_format.hpp"
#include "libcam/uncertainty/uncertainty_map.hpp"

namespace libcam {

namespace {

// Far past where the outlier rounds settle (two or three on real boards): a bound, so
// that a fit that keeps finding new outliers still ends.
constexpr int kMaxRounds = 6;

struct StartGuess {
    Camera camera;
    std::vector<Pose> poses;
};

std::vector<cv::Point3f> board_points_of(const std::vector<Vec3>& corners, const std::vector<int>& ids) {
    std::vector<cv::Point3f> out;
    for (const int id : ids) {
        const Vec3& p = corners[static_cast<std::size_t>(id)];
        out.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
    }
    return out;
}

std::vector<cv::Point2f> pixels_of(const std::vector<Vec2>& pixels) {
    std::vector<cv::Point2f> out;
    for (const Vec2& p : pixels) out.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
    return out;
}

// A pinhole from the boards' homographies (initCameraMatrix2D: square pixels, the
// principal point at the image centre) and each board's pose under it (solvePnP).
StartGuess start_guess(const std::vector<CalibrationView>& views, const BoardSpec& board, const ImageSize& size) {
    const std::vector<Vec3> corners = board.corner_points();
    std::vector<std::vector<cv::Point3f>> object_points;
    std::vector<std::vector<cv::Point2f>> image_points;
    for (const CalibrationView& view : views) {
        object_points.push_back(board_points_of(corners, view.ids));
        image_points.push_back(pixels_of(view.pixels));
    }
    const cv::Size image_size(static_cast<int>(size.width), static_cast<int>(size.height));
    const cv::Mat K = cv::initCameraMatrix2D(object_points, image_points, image_size, 1.0);
    StartGuess guess;
    guess.camera.size = size;
    guess.camera.intrinsics = {K.at<double>(0, 0), K.at<double>(1, 1), K.at<double>(0, 2), K.at<double>(1, 2), 0.0};
    guess.camera.lens = {LensType::Pinhole, {}};
    for (std::size_t v = 0; v < views.size(); ++v) {
        cv::Vec3d rvec, tvec;
        cv::solvePnP(object_points[v], image_points[v], K, cv::noArray(), rvec, tvec);
        guess.poses.push_back(Pose::from_rvec({rvec[0], rvec[1], rvec[2]}, {tvec[0], tvec[1], tvec[2]}));
    }
    return guess;
}

// The widest angle from the start camera's axis of any corner: whether the wide-angle
// models are candidates.
double widest_angle_deg(const StartGuess& guess, const std::vector<CalibrationView>& views) {
    const Intrinsics& k = guess.camera.intrinsics;
    double widest = 0.0;
    for (const CalibrationView& view : views) {
        for (const Vec2& p : view.pixels) {
            widest = std::max(widest, std::atan(std::hypot((p.x() - k.cx) / k.fx, (p.y() - k.cy) / k.fy)));
        }
    }
    return widest * 180.0 / 3.14159265358979323846;
}

std::vector<FitView> fit_views_of(const std::vector<CalibrationView>& views, const std::vector<Pose>& poses,
                                  const BoardSpec& board) {
    const std::vector<Vec3> corners = board.corner_points();
    std::vector<FitView> out;
    for (std::size_t v = 0; v < views.size(); ++v) {
        FitView fit_view{views[v].image, poses[v], {}};
        for (std::size_t k = 0; k < views[v].ids.size(); ++k) {
            fit_view.observations.push_back({corners[static_cast<std::size_t>(views[v].ids[k])], views[v].pixels[k]});
        }
        out.push_back(std::move(fit_view));
    }
    return out;
}

// The usable detections as views (every image of the first usable one's size); the
// others rejected with their reason.
void sort_detections(const std::vector<BoardDetection>& detections, Calibration& out) {
    for (const BoardDetection& detection : detections) {
        if (!detection.rejected.empty()) {
            out.rejected.push_back({detection.image, detection.rejected});
            continue;
        }
        if (out.views.empty()) out.size = detection.size;
        if (!(detection.size == out.size)) {
            out.rejected.push_back({detection.image, "its size " + std::to_string(detection.size.width) + "x" +
                                                         std::to_string(detection.size.height) + " is not the " +
                                                         std::to_string(out.size.width) + "x" +
                                                         std::to_string(out.size.height) + " of the first image used"});
            continue;
        }
        out.views.push_back({detection.image, detection.ids, detection.pixels, {}, {}});
    }
}

[[noreturn]] void too_few_views(const Calibration& out) {
    std::string reasons;
    for (std::size_t i = 0; i < out.rejected.size() && i < 2; ++i) {
        reasons += "; " + out.rejected[i].image + ": " + out.rejected[i].why;
    }
    if (out.rejected.size() > 2) reasons += "; ...";
    throw Error("calibrate: " + std::to_string(out.views.size()) + " of " + std::to_string(out.images) +
                " images usable, a calibration needs at least two" + reasons);
}

// Drops the corners whose residual under the chosen model is beyond the outlier limit;
// then the views left with too few. Returns how many corners were dropped.
std::size_t drop_outliers(Calibration& out, double limit) {
    std::size_t dropped = 0;
    for (std::size_t v = 0; v < out.views.size(); ++v) {
        const std::vector<double> errors = out.view_errors(v);
        CalibrationView& view = out.views[v];
        std::size_t kept = 0;
        for (std::size_t k = 0; k < view.ids.size(); ++k) {
            if (errors[k] > limit) {
                view.outlier_ids.push_back(view.ids[k]);
                view.outlier_pixels.push_back(view.pixels[k]);
                ++dropped;
                continue;
            }
            view.ids[kept] = view.ids[k];
            view.pixels[kept] = view.pixels[k];
            ++kept;
        }
        view.ids.resize(kept);
        view.pixels.resize(kept);
    }
    return dropped;
}

// The chosen fit's residual spread per coordinate: sqrt(sum |r|^2 / 2N).
double noise_of(const Calibration& out) {
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t v = 0; v < out.views.size(); ++v) {
        for (const double e : out.view_errors(v)) sum += e * e;
        count += out.views[v].ids.size();
    }
    return std::sqrt(sum / static_cast<double>(2 * count));
}

// Tiles across the image for a candidate's worst sigma over the observed region.
constexpr long kUncertaintyColumns = 40;

CandidateUncertainty uncertainty_of(const Calibration& c, std::size_t candidate) {
    CandidateUncertainty out;
    try {
        const SolvedCalibration solved = c.solved(candidate);
        const ProjectionUncertainty uncertainty(solved);
        out.noise_px = uncertainty.observed_pixel_uncertainty_px();
        out.centre_px = uncertainty.sigma_px({Vec2(c.size.centre_x(), c.size.centre_y())}).front();
        const UncertaintyMap map = uncertainty_map(uncertainty, kUncertaintyColumns, kAtInfinity);
        out.worst_observed_px = summarize(map, observed_region(solved)).worst_observed_px;
        out.parameters = uncertainty.parameters();
        out.computed = true;
    } catch (const InvalidArgument& error) {
        out.failure = error.what();
    }
    return out;
}

// A parameter whose standard deviation exceeds its size, flagged on its candidate: on the
// line the folds already flagged it on, if they did ("k3 = ... ranges from ... over the
// folds, with a standard deviation of ...: ..."), else on a line of its own.
void flag_spread(ObservationCandidate& candidate, const ParameterSpread& p) {
    const std::string spread = "a standard deviation of " + format_short(p.stdev, 4);
    const std::string named = p.name + " = ";
    for (std::string& flag : candidate.flags) {
        const std::size_t why = flag.rfind(": ");
        if (flag.rfind(named, 0) != 0 || why == std::string::npos) continue;
        flag.insert(why, ", with " + spread);
        return;
    }
    candidate.flags.push_back(named + format_short(p.value, 4) + " with " + spread + ": the data do not pin it down");
}

// Each fitted candidate's uncertainty; its parameters whose standard deviation exceeds
// their size flagged on it.
void measure_uncertainty(Calibration& c) {
    c.uncertainty.clear();
    for (std::size_t i = 0; i < c.fit.candidates.size(); ++i) {
        ObservationCandidate& candidate = c.fit.candidates[i];
        c.uncertainty.push_back(candidate.fitted ? uncertainty_of(c, i) : CandidateUncertainty{});
        for (const ParameterSpread& p : c.uncertainty.back().parameters) {
            if (p.stdev > std::abs(p.value)) flag_spread(candidate, p);
        }
    }
}

}  // namespace

SolvedCalibration Calibration::solved(std::size_t candidate) const {
    const ObservationCandidate& fitted = fit.candidates.at(candidate);
    SolvedCalibration out;
    out.camera = fitted.camera;
    out.views = fit_views_of(views, fitted.poses, board);
    out.held = fitted.candidate.held;
    return out;
}

std::size_t Calibration::corners() const {
    std::size_t total = 0;
    for (const CalibrationView& view : views) total += view.ids.size();
    return total;
}

std::vector<double> Calibration::view_errors(std::size_t v) const {
    Camera camera = chosen().camera;
    camera.pose = chosen().poses[v];
    const std::vector<Vec3> corners = board.corner_points();
    std::vector<FitSample> samples;
    for (std::size_t k = 0; k < views[v].ids.size(); ++k) {
        samples.push_back({corners[static_cast<std::size_t>(views[v].ids[k])], views[v].pixels[k]});
    }
    return reprojection_errors(camera, samples);
}

double Calibration::view_rms_px(std::size_t v) const {
    double sum = 0.0;
    const std::vector<double> errors = view_errors(v);
    for (const double e : errors) sum += e * e;
    return std::sqrt(sum / static_cast<double>(errors.size()));
}

std::vector<Candidate> default_calibration_candidates(double widest_angle_deg) {
    std::vector<Candidate> list;
    for (const char* name : {"PINHOLE", "OPENCV4", "OPENCV5", "OPENCV8", "FISHEYE"}) list.push_back(candidate_named(name));
    for (const Candidate& wide : candidates_for(widest_angle_deg)) {
        const bool listed = std::any_of(list.begin(), list.end(), [&](const Candidate& c) { return c.lens == wide.lens; });
        if (!wide.look_at && !listed && lens_info(wide.lens).fit == FitCandidate::WideScenes) list.push_back(wide);
    }
    return list;
}

Calibration calibrate(const std::vector<BoardDetection>& detections, const BoardSpec& board,
                      const CalibrationOptions& options) {
    Calibration out;
    out.board = board;
    out.held = options.held;
    out.images = detections.size();
    sort_detections(detections, out);
    if (out.views.size() < 2) too_few_views(out);
    const StartGuess guess = start_guess(out.views, board, out.size);
    ObservationFitOptions fit_options;
    fit_options.candidates =
        options.candidates.empty() ? default_calibration_candidates(widest_angle_deg(guess, out.views)) : options.candidates;
    for (Candidate& candidate : fit_options.candidates) candidate.held = options.held;
    fit_options.folds = options.folds;
    fit_options.margin = options.margin;
    Camera start = guess.camera;
    std::vector<Pose> poses = guess.poses;
    // mrcal's rule: the limit is k times the noise of the first fit, estimated once more
    // after the first drop (the outliers no longer in it) and then held, so that each round
    // only drops corners beyond the same limit and the rounds settle instead of shaving a
    // few corners off a shrinking noise each time.
    double limit_noise = 0.0;
    while (true) {
        ++out.rounds;
        if (options.stage) {
            options.stage("fitting " + std::to_string(fit_options.candidates.size()) + " models to " +
                          std::to_string(out.views.size()) + " views (" + std::to_string(out.corners()) + " corners)");
        }
        out.fit = fit_observations(start, fit_views_of(out.views, poses, board), fit_options);
        if (!out.fit.chosen) throw Error("calibrate: " + out.fit.reason);
        out.noise_px = noise_of(out);
        if (out.rounds <= 2) limit_noise = out.noise_px;
        const double limit = options.outlier_sigmas * limit_noise;
        if (out.rounds == kMaxRounds) {
            // The last fit stands; whether it still has corners beyond the limit is said.
            Calibration probe = out;
            out.rounds_capped = drop_outliers(probe, limit) > 0;
            break;
        }
        const std::size_t dropped = drop_outliers(out, limit);
        if (dropped == 0) break;
        out.outliers += dropped;
        // The next round starts where this one ended, without the views too few corners remain in.
        start = out.chosen().camera;
        std::vector<CalibrationView> kept;
        poses.clear();
        for (std::size_t v = 0; v < out.views.size(); ++v) {
            if (out.views[v].ids.size() < kMinCornersPerView) {
                out.rejected.push_back({out.views[v].image, std::to_string(out.views[v].outlier_ids.size()) +
                                                                " of its corners are outliers, " +
                                                                std::to_string(out.views[v].ids.size()) + " remain"});
                continue;
            }
            kept.push_back(std::move(out.views[v]));
            poses.push_back(out.chosen().poses[v]);
        }
        out.views = std::move(kept);
        if (out.views.size() < 2) too_few_views(out);
    }
    measure_uncertainty(out);
    return out;
}

}  // namespace libcam
