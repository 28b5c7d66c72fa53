#pragma once
// Between libcam::report's Image and the cv::Mat OpenCV draws on. Inside libcam::report
// only: not installed, so that report's headers stay free of OpenCV.

#include <cstring>
#include <opencv2/core.hpp>

#include "libcam/error.hpp"
#include "libcam/report/image.hpp"

namespace libcam::detail {

// A copy of an 8-bit three-channel picture.
inline Image to_image(const cv::Mat& picture) {
    if (picture.type() != CV_8UC3) throw Error("report: a picture must be 8-bit with three channels");
    const cv::Mat packed = picture.isContinuous() ? picture : picture.clone();
    Image image;
    image.width = packed.cols;
    image.height = packed.rows;
    image.bgr.resize(packed.total() * 3);
    std::memcpy(image.bgr.data(), packed.data, image.bgr.size());
    return image;
}

// A view of the image's bytes (no copy): valid while the image lives unchanged.
inline cv::Mat as_mat(const Image& image) {
    if (image.width < 0 || image.height < 0 ||
        image.bgr.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3) {
        throw InvalidArgument("image: " + std::to_string(image.bgr.size()) + " bytes do not make " +
                              std::to_string(image.width) + "x" + std::to_string(image.height) + " BGR pixels");
    }
    return cv::Mat(image.height, image.width, CV_8UC3, const_cast<std::uint8_t*>(image.bgr.data()));
}

}  // namespace libcam::detail
