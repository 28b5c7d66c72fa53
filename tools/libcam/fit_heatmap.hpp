#pragma once
// `libcam fit --heatmap`: the chosen model's reprojection error over the whole image
// as a PNG, with the scene outlined.

#include <string>
#include <vector>

#include "libcam/fit/fit.hpp"

namespace libcam::cli {

// Colours run from 0 to the tolerance (viridis); red where the error exceeds the
// tolerance, grey where the source has no ray or the model no projection. The scene's
// outline is white; a scale bar and a caption sit beside the image. Returns PNG bytes.
// `max_in_scene_px` goes into the caption.
std::string fit_heatmap_png(const Camera& source, const Scene& scene, const FittedModel& chosen,
                            const std::vector<double>& depths, double tolerance_px, double max_in_scene_px);

}  // namespace libcam::cli
