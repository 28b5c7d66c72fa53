#pragma once
// JPL's .cahvor and .cahvore text, as mrcal reads and writes it (mrcal's cahvor.py):
// "key = value" lines, # comments.
//
//   Dimensions = W H
//   Model = CAHV = perspective, linear | CAHVOR = perspective, distortion
//         | CAHVORE3,<linearity> = general
//   C, A, H, V (3 numbers each): the camera centre, its axis, and the horizontal and
//   vertical vectors, H = fx H' + cx A, V = fy V' + cy A
//   O, R (CAHVOR), and E (CAHVORE): the distortion's axis and coefficients
//   LENSMODEL_OPENCV4/5/8/12 = ... (older files: DISTORTION_OPENCV...): mrcal's way of
//   storing an OpenCV lens in a CAHV file
//
// Read as mrcal reads it: fx = |H - (H.A) A|, cx = H.A (likewise fy, cy from V), the
// camera's axes H', V', A and its centre C in the file's reference frame (so libcam's
// pose is that placement inverted); CAHVOR's alpha and beta are the angles of O in the
// camera frame. mrcal ignores the Hs, Hc, Vs, Vc and Theta lines (derived), and so does
// libcam. Pixel centres are at integers, as in libcam. Read only.

#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> parse_cahvor(std::string_view text, const std::string& source);

}  // namespace libcam
