#pragma once
// A picture as libcam::report draws it, and its PNG file. The drawing is done with
// OpenCV inside libcam::report; nothing of OpenCV shows here.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace libcam {

// 8 bits per channel, three channels in the order blue, green, red (OpenCV's), rows from
// the top, each row width * 3 bytes, no padding.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> bgr;
};

// The bytes of a PNG file of the image; throws Error when it cannot be encoded.
std::string encode_png(const Image& image);

// Writes the image as a PNG file, atomically (io/atomic_write.hpp): on failure the old
// file, if any, is untouched. Throws FileError naming the path.
void write_png(const std::filesystem::path& path, const Image& image);

}  // namespace libcam
