#pragma once
// The camera of an image made from another camera's image by resizing, cropping,
// padding, binning or turning it by quarter turns: the same lens and centre, with K (and
// for quarter turns the axes) moved to match. Pixel centres follow OpenCV's convention
// (integers), so scaling by s moves a coordinate as
//     x' = s (x + 0.5) - 0.5
// (the image's outer edge, -0.5, stays at -0.5): cx' = s (cx + 0.5) - 0.5, fx' = s fx.
//
// A mirror image (one axis flipped) has no camera: no rotation of the axes gives it
// (its determinant is -1); flipping both axes is the half turn, quarter_turns(camera, 2).
//
// Each throws InvalidArgument naming the value that does not fit.

#include "libcam/camera/camera.hpp"

namespace libcam {

// The image resized to `size` (each axis by its own factor, as cv::resize does).
Camera resized(const Camera& camera, const ImageSize& size);
// The image scaled by `scale` on both axes, its size rounded to the nearest pixel, and
// each axis's factor the ratio of the sizes (so that the edges stay the edges).
Camera scaled(const Camera& camera, double scale);
// The pixels [x0, x1) x [y0, y1) of the image (numpy's image[y0:y1, x0:x1]); a range
// past the image's edge pads it.
Camera cropped(const Camera& camera, long x0, long y0, long x1, long y1);
// The image with `left`, `top`, `right` and `bottom` pixels added around it (negative: cut).
Camera padded(const Camera& camera, long left, long top, long right, long bottom);
// Each `factor` x `factor` block of pixels made one (the rows and columns left over at
// the right and bottom dropped, as a camera's binning does).
Camera binned(const Camera& camera, int factor);
// The image turned clockwise by `turns` quarter turns (1: clockwise, 2: half turn,
// 3: anticlockwise). The camera turns about its optical axis: the pose turns with it.
// The lens must look the same turned: radially symmetric models as they are; OpenCV's
// tangential and thin prism terms, MEI's and the thin-prism fisheye's, move to their
// turned places. LONLAT, LATLON, splined, CAHVOR(E) and OpenCV's tilted sensor (OPENCV14)
// are refused, as is skew (a turned skewed K is not upper triangular).
Camera quarter_turns(const Camera& camera, int turns);

}  // namespace libcam
