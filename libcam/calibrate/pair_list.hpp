#pragma once
// A stereo pair's image list as OpenCV's stereo_calib sample reads it (stereo_calib.xml:
// an `imagelist` of file names, left and right in turn, in cv::FileStorage's XML, YAML or
// JSON), for `libcam calibrate --pairs FILE`. Names are taken relative to the list's own
// folder, as the images usually lie beside it.

#include <filesystem>
#include <string_view>
#include <vector>

namespace libcam {

struct PairList {
    std::vector<std::filesystem::path> left, right;
};

// Throws FileError, in one line naming `source`, for text that is not such a list (no
// `imagelist` sequence of strings, an odd count, none at all).
PairList parse_pair_list(std::string_view text, const std::filesystem::path& source);

// Reads and parses the file (FileError when it cannot be read).
PairList read_pair_list(const std::filesystem::path& path);

}  // namespace libcam
