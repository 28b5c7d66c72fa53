#pragma once
// libmrcal's parser says why a .cameramodel failed only on stderr, in its own words
// ("cameramodel-parser.re(254): Didn't see expected ',' at 59 while parsing intrinsics",
// "malloc() failed"): this says the same as libcam's other readers do, with the line.

#include <string>
#include <string_view>

namespace libcam {

// What is wrong with `text`, the .cameramodel libmrcal's parser refused, from the
// diagnostic it printed: "line 3: \"intrinsics\": expected ',' between its numbers",
// "missing \"extrinsics\" (a .cameramodel needs lensmodel, intrinsics, extrinsics and
// imagersize)". A diagnostic it does not know is given as libmrcal wrote it, its
// positions as lines.
std::string mrcal_parse_failure(std::string_view diagnostic, std::string_view text);

}  // namespace libcam
