#include "libcam/report/image.hpp"

#include <opencv2/imgcodecs.hpp>

#include "libcam/error.hpp"
#include "libcam/io/atomic_write.hpp"
#include "libcam/report/detail/cv_image.hpp"

namespace libcam {

std::string encode_png(const Image& image) {
    std::vector<std::uint8_t> png;
    if (image.width == 0 || image.height == 0 || !cv::imencode(".png", detail::as_mat(image), png)) {
        throw Error("PNG: OpenCV could not encode a " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + " picture");
    }
    return std::string(png.begin(), png.end());
}

void write_png(const std::filesystem::path& path, const Image& image) {
    write_file_atomically(path, encode_png(image));
}

}  // namespace libcam
