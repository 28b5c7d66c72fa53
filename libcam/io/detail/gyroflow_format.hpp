#pragma once
// Gyroflow's lens profile (JSON; gyroflow/lens_profiles, and what Gyroflow's calibrator
// writes; src/core/lens_profile.rs):
//
//   calib_dimension {w, h}            the image size calibrated
//   fisheye_params {camera_matrix [[fx, 0, cx], [0, fy, cy], [0, 0, 1]], distortion_coeffs}
//   distortion_model                  "opencv_fisheye" (the default when absent),
//                                     "opencv_standard", "poly3", "poly5", "ptlens", others
//   asymmetrical                      false (the default): Gyroflow puts the principal
//                                     point at (w / 2, h / 2), whatever camera_matrix says
//   input_horizontal_stretch, input_vertical_stretch   anamorphic squeeze (1 by default)
//
// Gyroflow's models on x = X/Z, y = Y/Z (src/core/stabilization/distortion_models/*.rs,
// distort_point), its coefficients k[0..]: opencv_fisheye is cv::fisheye (FISHEYE, k1..k4);
// opencv_standard is cv::projectPoints with k1 k2 p1 p2 k3 k4 k5 k6 s1 s2 s3 s4 (OPENCV12,
// or the simplest OpenCV model that is the same lens); poly3 (k1) and poly5 (k1 k2) are
// OpenCV's radial terms (OPENCV4); ptlens is m = u (1 + k0 r^3 + k1 r^2 + k2 r), PTLENS
// (a b c). Gyroflow holds these in the camera matrix's units (it does not rescale them
// as lensfun does). Gyroflow works in pixel indices, so its (w / 2, h / 2) is that point in
// OpenCV's pixels. Stretched (anamorphic) profiles and the GoPro, Insta360, Sony and other
// models are refused.

#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> read_gyroflow(std::string_view text, const ReadContext& context);

// Whether a parsed JSON file is a Gyroflow lens profile: calib_dimension and fisheye_params.
bool claims_gyroflow(const DocumentNode& root);

}  // namespace libcam
