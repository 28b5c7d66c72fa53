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
// the intrinsics. The image's size gives what K holds fixed: the FOV camera's principal
// point (the image centre), a sensor-scale candidate's pixels per millimetre. Calls
// `hook` after each iteration (options.progress is fit_candidates' business).
LeastSquaresState solve_least_squares(const Candidate& candidate, const ImageSize& size,
                                      const std::vector<Observation>& observations, LeastSquaresState start,
                                      const SolveOptions& options, const IterationHook& hook);

}  // namespace libcam::detail
