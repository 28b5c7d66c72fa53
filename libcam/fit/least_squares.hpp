#pragma once
// One candidate's nonlinear least-squares fit, by Ceres (fit.cpp's engine; Ceres
// stays out of the headers).
//
// Unknowns: the candidate's free intrinsics (f for FOV; fx fy cx cy, or cx cy alone at
// a sensor's fixed scale, and the lens coefficients otherwise), a rotation (Rodrigues
// vector) and a shift of the camera.
// Residuals, two per observation, in pixels:
//     K lens(R(rotation) point + shift) - pixel
// Every observation, and every point of options.must_project, must project at the
// start; a step that takes one out of the model's valid domain is rejected by the
// solver, so the result projects them all.

#include <functional>
#include <vector>

#include "libcam/fit/fit.hpp"

namespace libcam::detail {

struct LeastSquaresState {
    std::vector<double> params;  // the candidate's free intrinsics
    Vec3 rotation = Vec3::Zero();
    Vec3 shift = Vec3::Zero();
    int iterations = 0;
};

// Called after each solver iteration with its number.
using IterationHook = std::function<void(int)>;

// Fits `candidate` from `start`; only the unknowns options.motion allows move besides
// the intrinsics. The image's size gives what K holds fixed: the look-at camera's principal
// point (the image centre), a sensor-scale candidate's pixels per millimetre. Calls
// `hook` after each iteration (options.progress is fit_candidates' business).
LeastSquaresState solve_least_squares(const Candidate& candidate, const ImageSize& size,
                                      const std::vector<FitSample>& observations, LeastSquaresState start,
                                      const SolveOptions& options, const IterationHook& hook);

// Several views of known points through one camera (a calibration's board views): the
// candidate's intrinsics shared, each view's pose (Rodrigues rotation, translation: world
// to camera) its own. Residuals, two per observation: K lens(R(rotation) point + shift) -
// pixel. With `hold_intrinsics` only the poses move (a held-out view's pose, solved with
// intrinsics fitted on the other views).
struct ViewsState {
    std::vector<double> params;    // the candidate's free intrinsics
    std::vector<Vec3> rotations;   // one per view
    std::vector<Vec3> shifts;      // one per view
    int iterations = 0;
};
ViewsState solve_views(const Candidate& candidate, const ImageSize& size,
                       const std::vector<std::vector<FitSample>>& views, ViewsState start, bool hold_intrinsics);

// Two cameras' views of the same boards (a stereo pair): each camera's intrinsics shared
// over its views, one board pose per view in the first camera's frame (Rodrigues, shift:
// board to first camera), and the second camera's pose from the first (X_second =
// R(rotation) X_first + shift, OpenCV's stereoCalibrate R and T). Residuals, two per
// observation: the first camera's as solve_views', the second's K lens(R(rotation)
// (R(board) point + board shift) + shift) - pixel. first_views[v] and second_views[v]
// are one view's corners seen by each camera.
struct PairState {
    ViewsState first;            // the first camera's intrinsics and the board poses
    std::vector<double> second;  // the second camera's intrinsics
    Vec3 rotation = Vec3::Zero();
    Vec3 shift = Vec3::Zero();
};
PairState solve_pair(const Candidate& first, const ImageSize& first_size, const Candidate& second,
                     const ImageSize& second_size, const std::vector<std::vector<FitSample>>& first_views,
                     const std::vector<std::vector<FitSample>>& second_views, PairState start);

// The camera that a candidate's parameters describe, with pose `pose` (fit.cpp).
Camera camera_from_params(const Candidate& candidate, const ImageSize& size, const std::vector<double>& params,
                          const Pose& pose);
// A camera's intrinsics and lens as a start for `candidate` (with the camera's pose as its
// motion): exact when the candidate's model contains the camera's, else the model's own
// start with the camera's K (fit.cpp).
LeastSquaresState start_from(const Candidate& candidate, const Camera& base);
// Whether the candidate's model can express every camera of `lens` exactly.
bool contains_model(const Candidate& candidate, LensType lens);
// How many of a candidate's parameters belong to K (f; cx cy; fx fy cx cy).
std::size_t core_count(const Candidate& candidate);
Camera camera_from_state(const Candidate& candidate, const ImageSize& size, const LeastSquaresState& state);

}  // namespace libcam::detail
