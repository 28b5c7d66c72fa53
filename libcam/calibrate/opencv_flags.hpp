#pragma once
// OpenCV's calibrateCamera flags, as `libcam calibrate --opencv-flags` takes them: what a
// calibration made with them held, so that libcam's fit holds the same.
//
// Taken: CALIB_FIX_ASPECT_RATIO (fx = fy: OpenCV's calibration sample with its aspect
// ratio of 1), CALIB_ZERO_TANGENT_DIST (p1 = p2 = 0) and CALIB_FIX_K1 to CALIB_FIX_K6
// (that coefficient held at 0, where OpenCV holds it when it starts without a guess).
// Written as OpenCV's names (with or without CALIB_, any case) or as the number OpenCV's
// files store (its calibration sample's `flags: 2`), comma-separated: "2",
// "FIX_ASPECT_RATIO,ZERO_TANGENT_DIST", "CALIB_FIX_K3". The other flags choose a model
// (--model says which), start from a guess or hold values libcam has no start for: each
// is refused with its reason.

#include <string_view>

#include "libcam/fit/fit.hpp"

namespace libcam {

// Throws InvalidArgument, in one line naming the flag, for a flag it does not take.
HeldParameters held_by_opencv_flags(std::string_view text);

}  // namespace libcam
