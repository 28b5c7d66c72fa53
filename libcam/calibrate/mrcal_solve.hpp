#pragma once
// A calibration's solve as mrcal keeps one in a .cameramodel (its optimization_inputs,
// io/observations.hpp's mrcal_optimization_inputs), so that mrcal's own tools
// (mrcal-show-projection-uncertainty, mrcal-show-residuals, mrcal.projection_uncertainty)
// and `libcam uncertainty` can take a model `libcam calibrate -o` wrote: the corners of
// every view (the outliers weighed -1), the board poses, the cameras' poses and intrinsics
// as libcam solved them, the board flat and no regularization, as libcam's solve.
//
// The board's corners as mrcal places them: corner (row i, column j) at (j, i) * spacing.
// A ChArUco board's first inner corner is one square in: each board pose is moved by that
// square so that mrcal's corners land where libcam's did.

#include <string>

#include "libcam/calibrate/calibrate.hpp"
#include "libcam/calibrate/calibrate_pair.hpp"

namespace libcam {

// The optimization_inputs of the chosen model's solve (the bytes literal). Throws
// NotRepresentable saying why mrcal cannot hold the solve as libcam solved it: a parameter
// held (fx = fy, a coefficient at 0: mrcal frees all or none), a lens mrcal lacks.
std::string mrcal_solve_inputs(const Calibration& calibration);

// The same for a pair's joint solve: both cameras (the first the reference), the second
// camera's pose, one board pose per view both used. Also refused where the two cameras'
// models differ (mrcal solves one model for all).
std::string mrcal_solve_inputs(const PairCalibration& pair);

}  // namespace libcam
