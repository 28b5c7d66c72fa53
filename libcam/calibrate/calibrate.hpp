#pragma once
// A calibration from the corners found in a set of board images (`libcam calibrate`).
//
// Each view's start: the intrinsics of OpenCV's initCameraMatrix2D over every view (a
// pinhole from the boards' homographies) and each board's pose by cv::solvePnP with them.
// The fit is `libcam fit --observations`' (fit/observation_fit.hpp): every candidate
// model, simplest first, fitted to every view (intrinsics shared, each board pose its
// own) and cross-validated by view; the simplest within the margin of the best held-out
// RMS is chosen.
//
// Each fitted candidate's projection uncertainty is measured at the end (at the image
// centre, and the worst over the region the corners covered); a parameter whose standard
// deviation exceeds its own size is flagged on the candidate: the data do not pin it down.
//
// Outliers, as mrcal rejects them: after a fit, a corner whose residual under the chosen
// model is more than `outlier_sigmas` times the fit's noise (the residuals' standard
// deviation per coordinate) from where the model puts it is dropped, and the candidates
// are fitted again without it, until no corner is dropped. The noise is the first fit's,
// estimated once more after the first drop and then held. A view left with fewer than
// kMinCornersPerView corners is dropped too, and said.

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/calibrate/board.hpp"
#include "libcam/calibrate/detect.hpp"
#include "libcam/fit/observation_fit.hpp"
#include "libcam/uncertainty/projection_uncertainty.hpp"

namespace libcam {

struct CalibrationOptions {
    // The models to try, simplest first; empty: default_calibration_candidates.
    std::vector<Candidate> candidates;
    int folds = 5;
    double margin = 0.05;
    double outlier_sigmas = 5.0;
    // Held in every candidate, as OpenCV's calibration flags hold them (opencv_flags.hpp).
    HeldParameters held;
    // Called as each stage starts ("fitting 6 models to 13 views"), for a progress line.
    std::function<void(const std::string&)> stage;
};

struct RejectedImage {
    std::string image;
    std::string why;
};

// One image that entered the fit: the corners kept (ids into the board's corners, and
// their pixels) and those dropped as outliers.
struct CalibrationView {
    std::string image;
    std::vector<int> ids;
    std::vector<Vec2> pixels;
    std::vector<int> outlier_ids;
    std::vector<Vec2> outlier_pixels;
};

// A candidate's projection uncertainty (uncertainty/projection_uncertainty.hpp), points at
// infinity: how far the data pin the model down, beside its held-out RMS.
struct CandidateUncertainty {
    bool computed = false;
    std::string failure;             // why not, when not computed
    double noise_px = 0.0;           // the noise its residuals imply
    double centre_px = 0.0;          // sigma at the image centre
    double worst_observed_px = 0.0;  // the largest sigma over the region the corners covered
    std::vector<ParameterSpread> parameters;
};

struct Calibration {
    BoardSpec board;
    ImageSize size;
    std::size_t images = 0;
    std::vector<RejectedImage> rejected;  // in the images' order
    std::vector<CalibrationView> views;   // the fit's views, in the same order
    ObservationFitReport fit;             // candidates, the choice; poses in views' order
    HeldParameters held;                  // what every candidate held
    std::size_t outliers = 0;             // corners dropped, over every view
    int rounds = 0;                       // fits run (one more for each round that dropped corners)
    bool rounds_capped = false;           // the last fit still had corners beyond the limit
    double noise_px = 0.0;                // the chosen fit's residual spread, per coordinate
    std::vector<CandidateUncertainty> uncertainty;  // one per fit.candidates

    const ObservationCandidate& chosen() const { return fit.candidates[*fit.chosen]; }
    std::size_t corners() const;
    // |residual| of each kept corner of view v under the chosen camera and that view's pose.
    std::vector<double> view_errors(std::size_t v) const;
    // Their RMS.
    double view_rms_px(std::size_t v) const;
    // A fitted candidate (index into fit.candidates) as a solved calibration: its camera,
    // each view's pose under it and the corners kept.
    SolvedCalibration solved(std::size_t candidate) const;
};

// PINHOLE, OPENCV4, OPENCV5, OPENCV8 and FISHEYE; and where the corners reach past
// kWideSceneAngleDeg from the axis of the start camera, the fit's wide-scene models.
std::vector<Candidate> default_calibration_candidates(double widest_angle_deg);

// Throws Error, in one line, when fewer than two images can be used (naming how many were
// given and the first reasons).
Calibration calibrate(const std::vector<BoardDetection>& detections, const BoardSpec& board,
                      const CalibrationOptions& options);

}  // namespace libcam
