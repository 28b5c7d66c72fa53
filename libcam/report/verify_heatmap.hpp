#pragma once
// The picture of one `libcam verify` check's error over the image
// (`libcam verify --heatmap`), drawn from its report (check/verify.hpp).

#include <string_view>

#include "libcam/check/verify.hpp"
#include "libcam/report/image.hpp"

namespace libcam {

// The longer side of the map in the picture, in pixels.
inline constexpr int kHeatmapMapSide = 720;

// The error per grid pixel on a log10 colour scale (viridis), the image scaled so that
// its longer side is kHeatmapMapSide px, a title with the statistics above, a scale bar
// with labelled decades to the right, and a legend below. Pixels where libcam has no ray
// are grey and hatched; pixels with a ray that the check did not measure are plain grey.
// Throws InvalidArgument for an unknown name, Error for a skipped check.
Image verify_heatmap(const VerifyReport& report, std::string_view check_name);

}  // namespace libcam
