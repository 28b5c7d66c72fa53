#pragma once
// The check that a 3x3 camera matrix OpenCV holds (read from a file, or built by
// libcam's bridge) is K of the given intrinsics, entry for entry: [fx s cx; 0 fy cy; 0 0 1].

#include <catch2/catch.hpp>

#include <opencv2/core.hpp>

#include "libcam/geometry/intrinsics.hpp"

namespace libcam::test {

inline void check_opencv_k(const cv::Mat& K, const Intrinsics& k) {
    REQUIRE(K.type() == CV_64F);
    REQUIRE(K.rows == 3);
    REQUIRE(K.cols == 3);
    CHECK(K.at<double>(0, 0) == k.fx);
    CHECK(K.at<double>(0, 1) == k.skew);
    CHECK(K.at<double>(0, 2) == k.cx);
    CHECK(K.at<double>(1, 0) == 0.0);
    CHECK(K.at<double>(1, 1) == k.fy);
    CHECK(K.at<double>(1, 2) == k.cy);
    CHECK(K.at<double>(2, 0) == 0.0);
    CHECK(K.at<double>(2, 1) == 0.0);
    CHECK(K.at<double>(2, 2) == 1.0);
}

}  // namespace libcam::test
