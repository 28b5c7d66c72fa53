// Encodes a two-pixel picture as a PNG file's bytes with an installed libcam::report and
// prints the file's signature (the 8 bytes every PNG file starts with).

#include <cstdio>

#include "libcam/report/image.hpp"

int main() {
    const libcam::Image image{2, 1, {0, 0, 255, 255, 0, 0}};  // a red pixel, a blue one
    const std::string png = libcam::encode_png(image);
    std::printf("png");
    for (std::size_t i = 0; i < 8 && i < png.size(); ++i) std::printf(" %02x", static_cast<unsigned char>(png[i]));
    std::printf("\n");
    return 0;
}
