#pragma once
// The picture of `libcam reproject --heatmap`: where on the image a file's residuals are,
// and which views carry them, drawn from a reprojection (reproject/reproject.hpp), as
// mrcal-show-residuals draws a calibration's.

#include "libcam/reproject/reproject.hpp"
#include "libcam/report/image.hpp"

namespace libcam {

// The image of the camera with the most counted observations (the only one, after
// `--camera`), cut into regions about 1/16 of its longer side: each region coloured by
// the RMS of the residuals observed in it (viridis, from 0 to the largest region's RMS;
// dark grey where nothing was observed), with an arrow from its centre along the mean
// residual (projected - observed), drawn longer by a stated factor. Below, a bar per
// view: its RMS, with the RMS of every view as a line. A title with the statistics.
// Throws Error when no observation is counted.
Image reprojection_heatmap(const ObservationSet& set, const Reprojection& reprojection);

}  // namespace libcam
