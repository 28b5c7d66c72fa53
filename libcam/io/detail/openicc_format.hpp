#pragma once
// OpenImuCameraCalibrator's camera JSON, as the Universal Manipulation Interface (UMI)
// ships its GoPro calibrations:
//
//   {"image_width": 2704, "image_height": 2028, "intrinsic_type": "FISHEYE",
//    "intrinsics": {"focal_length": f, "aspect_ratio": a, "principal_pt_x": cx,
//                   "principal_pt_y": cy, "radial_distortion_1".."_4": k1..k4, "skew": s},
//    "fps": ..., "final_reproj_error": ..., "nr_calib_images": ..., "stabelized": ...}
//
// fx = f and fy = a f (the calibrator's aspect ratio is fy / fx; UMI's own loader uses f
// for both, which differs from the calibration by the aspect ratio); pixel centres are at
// integers. Files other writers fill in the same layout give the focal lengths themselves:
// focal_length_x and focal_length_y, or fx and fy (UMI's RealSense PINHOLE files:
// "intrinsics": {"fx", "fy", "principal_pt_x", "principal_pt_y"}). The types: FISHEYE is cv::fisheye's model (FISHEYE, "radial_distortion_1".."_4"),
// DOUBLE_SPHERE is DOUBLE_SPHERE ("xi", "alpha"), EXTENDED_UNIFIED is EUCM ("alpha",
// "beta"), PINHOLE has no distortion (the calibrator writes none for it), and
// DIVISION_UNDISTORTION ("div_undist_distortion": Theia's k, per squared pixel) is DIVISION
// with k f^2, read only with an aspect ratio of 1 and no skew (Theia divides the offset in
// pixels, which is radial in the normalised point only then). The rest (the types the
// calibrator writes without their parameters) are refused naming the type. Read only.

#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> parse_openicc_camera(std::string_view text, const std::string& source);

// Whether a parsed JSON file is OpenImuCameraCalibrator's: an object with "intrinsic_type".
bool claims_openicc_camera(const DocumentNode& root);

}  // namespace libcam
