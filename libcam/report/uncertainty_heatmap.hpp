#pragma once
// The picture of `libcam uncertainty --heatmap` (and `libcam calibrate --heatmap`): the
// projection uncertainty over the image, as mrcal-show-projection-uncertainty draws it.

#include <string>
#include <vector>

#include "libcam/report/image.hpp"
#include "libcam/uncertainty/uncertainty_map.hpp"

namespace libcam {

// Each tile of the map coloured by sigma_px on a log scale (viridis, from 0.01 px or the
// map's smallest sigma up to 100 times that, clamped), grey where a pixel has no ray;
// contours at 0.1 px and 1 px; every observed pixel a small dot; the observed region
// outlined; a scale bar beside and `caption` below. At most 640 pixels wide.
Image uncertainty_heatmap(const UncertaintyMap& map, const std::vector<Vec2>& observed,
                          const std::vector<Vec2>& region, const std::string& caption);

}  // namespace libcam
