#pragma once
// The picture of `libcam fit --heatmap`: the chosen model's reprojection error over the
// whole image (computed by fit/error_map.hpp), with the scene outlined.

#include "libcam/fit/fit.hpp"
#include "libcam/report/image.hpp"

namespace libcam {

// The picture is at most this wide: enough to see the error's shape, cheap to compute.
inline constexpr int kFitHeatmapMaxWidth = 640;

// Colours run from 0 to options.tolerance_px (viridis); red where the error exceeds the
// tolerance, grey where the source has no ray or the model no projection. The scene's
// outline is white; a scale bar and a caption (the model, chosen.max_px, the tolerance)
// sit beside and below the image. The points lie at options.depths along each ray, as
// in the fit.
Image fit_heatmap(const Camera& source, const Scene& scene, const FitOptions& options, const CandidateReport& chosen);

}  // namespace libcam
