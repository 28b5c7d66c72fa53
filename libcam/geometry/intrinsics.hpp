#pragma once
// The intrinsic matrix K of a calibrated camera, in OpenCV's convention:
//
//     [fx  skew  cx]        pixel = K [x/z, y/z, 1]^T for a camera point (x, y, z),
// K = [ 0   fy   cy]        x right, y down, z forward, pixel centres at integers,
//     [ 0    0    1]        row 0 at the top of the image.
//
// Lens distortion, when present, acts between the camera point and K
// (see libcam/lens/), exactly as in OpenCV and mrcal.

#include <Eigen/Core>

#include "libcam/geometry/vector_math.hpp"

namespace libcam {

struct Intrinsics {
    double fx = 1.0;
    double fy = 1.0;
    double cx = 0.0;
    double cy = 0.0;
    double skew = 0.0;

    Mat3 K() const;

    // Reads K; throws InvalidArgument naming `field` unless the bottom row is (0 0 1),
    // K(1,0) is 0, every entry is finite, and fx, fy > 0.
    static Intrinsics from_K(const Mat3& K, const char* field = "K");

    // Throws InvalidArgument unless every value is finite and fx, fy are normal numbers > 0
    // (not subnormal: their inverses must be finite).
    void validate(const char* field = "K") const;

    // K^-1 [x, y, 1]: the normalised image point (x/z, y/z) of a pixel. In any scalar
    // type (float, double, Lane<double> for the batch paths), evaluated in that type.
    // Multiplied by 1/fx and 1/fy: in a loop over pixels those two divisions are made
    // once, not per pixel (the result is within an ulp of dividing).
    template <class Scalar>
    Eigen::Matrix<Scalar, 2, 1> normalized_from_pixel(const Eigen::Matrix<Scalar, 2, 1>& pixel) const {
        const Scalar one(1);
        const Scalar yn = (pixel.y() - Scalar(cy)) * (one / Scalar(fy));
        return {(pixel.x() - Scalar(cx) - Scalar(skew) * yn) * (one / Scalar(fx)), yn};
    }

    // K [xn, yn, 1]: the pixel of a normalised image point.
    template <class Scalar>
    Eigen::Matrix<Scalar, 2, 1> pixel_from_normalized(const Eigen::Matrix<Scalar, 2, 1>& normalized) const {
        return {Scalar(fx) * normalized.x() + Scalar(skew) * normalized.y() + Scalar(cx),
                Scalar(fy) * normalized.y() + Scalar(cy)};
    }
};

}  // namespace libcam
