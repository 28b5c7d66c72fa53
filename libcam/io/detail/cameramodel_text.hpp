#pragma once
// What libcam takes for the text of an mrcal .cameramodel, checked before either of its
// readers sees it: libmrcal's own parser (the camera, libcam/interop/mrcal.cpp) and
// libcam's reader of the optimization_inputs (the observations, mrcal_observations.cpp).
// One check for both, so that `libcam info` and `libcam reproject` take and refuse the
// same files.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace libcam::detail {

// The largest .cameramodel read. mrcal writes the inputs of its solve into the file
// (optimization_inputs: every observed corner, compressed and in base85, about 20 bytes of
// text each): mrcal's own 186-view example calibration is 0.37 MB, one of 558 views of a
// 10 x 10 board 1.07 MiB, and several cameras over thousands of views reach tens of MB.
constexpr std::size_t kLargestCameramodel = std::size_t{256} << 20;

// Throws FileError "<source>: N bytes: larger than the 256 MiB libcam reads as a .cameramodel".
void check_cameramodel_size(std::uintmax_t bytes, const std::string& source);

// The size above, then the lexical shape: no NUL bytes, every string closed on its own
// line, brackets balanced and at most 8 deep. libmrcal 2.2's parser reads past the end
// of its buffer on an unterminated string (found by fuzzing: it crashes, or reads
// whatever follows, even with a 0 terminator); what passes is safe to hand to it.
// Throws FileError "<source>: line L: <what>".
void check_cameramodel_lexically(std::string_view text, const std::string& source);

}  // namespace libcam::detail
