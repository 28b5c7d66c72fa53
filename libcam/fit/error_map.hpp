#pragma once
// A fitted model's reprojection error over the whole image, sampled at the centres of
// equal tiles (geometry/pixel_grid.hpp's tile_centres): what `libcam fit --heatmap`
// draws (report/fit_heatmap.hpp).

#include <vector>

#include "libcam/fit/fit.hpp"

namespace libcam {

struct FitErrorMap {
    ImageSize image;   // the source camera's
    long columns = 0;  // tiles across
    long rows = 0;     // tiles down
    // Per tile, row by row: the largest error over the depths at the tile's centre;
    // NaN where the source camera has no ray, +infinity where the fitted model does not
    // project a point of that ray.
    std::vector<double> error_px;
};

// The error of `fitted` (in the source camera's frame, as FittedModel::camera) against
// the source at each tile centre, with points along the source's unit ray at each of
// `depths` (the unit ray alone when empty), as fit_scene measures it. Throws
// InvalidArgument unless columns and rows are at least 1.
FitErrorMap fit_error_map(const Camera& source, const FittedModel& fitted, const std::vector<double>& depths,
                          long columns, long rows);

}  // namespace libcam
