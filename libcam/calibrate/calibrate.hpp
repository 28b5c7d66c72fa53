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

namespace libcam {

struct CalibrationOptions {
    // The models to try, simplest first; empty: default_calibration_candidates.
    std::vector<Candidate> candidates;
    int folds = 5;
    double margin = 0.05;
    double outlier_sigmas = 5.0;
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

struct Calibration {
    BoardSpec board;
    ImageSize size;
    std::size_t images = 0;
    std::vector<RejectedImage> rejected;  // in the images' order
    std::vector<CalibrationView> views;   // the fit's views, in the same order
    ObservationFitReport fit;             // candidates, the choice; poses in views' order
    std::size_t outliers = 0;             // corners dropped, over every view
    int rounds = 0;                       // fits run (one more for each round that dropped corners)
    bool rounds_capped = false;           // the last fit still had corners beyond the limit
    double noise_px = 0.0;                // the chosen fit's residual spread, per coordinate

    const ObservationCandidate& chosen() const { return fit.candidates[*fit.chosen]; }
    std::size_t corners() const;
    // |residual| of each kept corner of view v under the chosen camera and that view's pose.
    std::vector<double> view_errors(std::size_t v) const;
};

// PINHOLE, OPENCV4, OPENCV5, OPENCV8 and FISHEYE; and where the corners reach past
// kWideSceneAngleDeg from the axis of the start camera, the fit's wide-scene models.
std::vector<Candidate> default_calibration_candidates(double widest_angle_deg);

// Throws Error, in one line, when fewer than two images can be used (naming how many were
// given and the first reasons).
Calibration calibrate(const std::vector<BoardDetection>& detections, const BoardSpec& board,
                      const CalibrationOptions& options);

}  // namespace libcam
