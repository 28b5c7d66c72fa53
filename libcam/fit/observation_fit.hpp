#pragma once
// The lens model a calibration's observations support, judged on views held out of the
// fit (`libcam fit --observations`).
//
// Each candidate model, simplest first, is fitted to every view (its intrinsics shared,
// each view's pose its own; Ceres, Levenberg-Marquardt) and cross-validated by view: the
// views are dealt into K folds; for each fold the intrinsics are fitted on the other
// folds, then each held-out view's pose is solved alone with those intrinsics and its
// residuals counted. A model with more parameters than the data determine fits its
// training views better and the held-out ones worse.
//
// Views that repeat another (a board left still while frames were taken) are held out
// together: a held-out view whose twin is in training could not show an overfit.
//
// The choice is the simplest candidate whose held-out RMS is within a margin of the best
// candidate's. A parameter whose value changes from fold to fold by more than its own size
// is flagged: the data do not determine it (a k3 of -19949 on a telephoto lens).
//
// The points are held where the file has them: a board's corners in its own frame (exact:
// the board is what was measured), or a reconstruction's triangulated points.

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "libcam/fit/fit.hpp"

namespace libcam {

// One view: its observations (points in the world or board frame, and their pixels) and
// the pose the file's tool solved for it, where the fit starts.
struct FitView {
    std::string name;
    Pose pose;
    std::vector<FitSample> observations;
};

struct ObservationFitOptions {
    // The models to try (candidate_named), simplest first; empty: candidates_for the widest
    // observed angle.
    std::vector<Candidate> candidates;
    int folds = 5;  // at most the number of views
    // The chosen model's held-out RMS may exceed the best candidate's by this fraction.
    double margin = 0.05;
};

struct ObservationCandidate {
    Candidate candidate;
    bool fitted = false;
    std::string failure;       // why not, when not fitted
    Camera camera;             // fitted on every view (pose: identity)
    std::vector<double> params;
    std::vector<Pose> poses;   // each view's, fitted with it
    double rms_px = 0.0;       // over every view, after the fit on every view
    double heldout_rms_px = 0.0;  // over every held-out view, each with intrinsics fitted without it
    std::size_t heldout_count = 0;
    // Parameters the data do not determine (their name: how much they vary from fold to fold).
    std::vector<std::string> flags;
};

struct ObservationFitReport {
    std::size_t views = 0;
    std::size_t observations = 0;
    int folds = 0;
    // Views that repeat an earlier one (the same points within 2 px each: a board left
    // still); each is held out with the view it repeats, never against it.
    std::size_t repeated_views = 0;
    double margin = 0.0;
    std::vector<ObservationCandidate> candidates;
    std::optional<std::size_t> chosen;  // index into candidates
    std::string reason;                 // why that one, in words
};

// The names of a candidate's free parameters, in their order ("fx", "fy", "cx", "cy",
// then the lens's coefficients after the held ones; "f" for LOOK_AT).
std::vector<std::string> parameter_names(const Candidate& candidate);

// The directions the candidate's parameters may move in under its held ones: one column
// per free direction (orthonormal), num_params() rows. Without held parameters, the
// identity; fx = fy: one column (1, 1) / sqrt(2) for both; a coefficient held at 0: no
// column has it (a held name the model lacks holds nothing). Parameters p that satisfy
// what is held are B B^T p.
Eigen::MatrixXd free_directions(const Candidate& candidate);

// A camera as the free parameters of the candidate of its own lens model, exactly.
struct CameraParameters {
    Candidate candidate;
    std::vector<double> params;
};
// Throws InvalidArgument, naming the model, for a model libcam does not fit, a camera with
// skew, or a model the fit holds at a sensor's scale or with coefficients held at 0
// (the candidate could not hold the camera exactly).
CameraParameters parameters_of(const Camera& camera);

// The residuals of observations seen by a camera with `params` from `pose`, as the fit
// defines them (two per observation: projected minus observed, x then y), and their
// derivatives by automatic differentiation (the solver's own): by_intrinsics has a column
// per parameter, by_pose six: the pose's rotation (Rodrigues vector) then its
// translation. Throws InvalidArgument when an observation does not project.
struct ResidualDerivatives {
    Eigen::VectorXd residuals;
    Eigen::MatrixXd by_intrinsics;
    Eigen::MatrixXd by_pose;
};
ResidualDerivatives residual_derivatives(const Candidate& candidate, const ImageSize& size,
                                         const std::vector<double>& params, const Pose& pose,
                                         const std::vector<FitSample>& observations);

// `start`: the file's own camera (its size, and intrinsics and lens as a start); its pose
// is ignored. Throws InvalidArgument for fewer than two views or an empty view list.
ObservationFitReport fit_observations(const Camera& start, const std::vector<FitView>& views,
                                      const ObservationFitOptions& options);

}  // namespace libcam
