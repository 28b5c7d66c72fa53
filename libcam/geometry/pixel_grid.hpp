#pragma once
// The pixel grids libcam samples images on, in one place.
//
// PixelGrid: `columns` x values evenly spaced from 0 to W-1 and `rows` y values from 0
// to H-1, both ends included, over the image's pixel centres (OpenCV pixels, row 0 at
// the top). The corner pixels, where distortion is strongest and approximations fail
// first, are always on it, exactly. `libcam verify` checks on it, `libcam bench` times
// on it, and `libcam fit` samples its scene on it (mrcal-convert-lensmodel's --gridn
// lattice is the same grid).
//
// tile_centres: the centres of an image cut into equal tiles, edges included (the image
// spans [-0.5, W-0.5]); one sample per pixel of a picture of the image drawn smaller.

#include <vector>

#include "libcam/geometry/image_size.hpp"
#include "libcam/geometry/vector_math.hpp"

namespace libcam {

struct PixelGrid {
    long columns = 0;  // at least 2
    long rows = 0;     // at least 2

    // Throws InvalidArgument naming `field` unless columns and rows are both >= 2.
    void validate(const char* field = "grid") const;

    // The coordinate of a column (row): (W-1) i / (columns-1), rounded once, so the last
    // is exactly W-1. For a side of one pixel every coordinate is 0.
    double x(long column, const ImageSize& size) const;
    double y(long row, const ImageSize& size) const;
    // The spacing between neighbouring columns (rows).
    double step_x(const ImageSize& size) const;
    double step_y(const ImageSize& size) const;

    // Every point, row by row (row 0 first, each from column 0).
    std::vector<Vec2> pixels(const ImageSize& size) const;
    // The points inside the box [low, high], row by row; a point within `slack` grid
    // steps of the box counts as inside (rounding).
    std::vector<Vec2> pixels_in(const ImageSize& size, const Vec2& low, const Vec2& high, double slack) const;

    bool operator==(const PixelGrid&) const = default;
};

// The centres of `columns` x `rows` equal tiles covering the whole image, row by row:
// tile (u, v) is centred at ((u + 0.5) W / columns - 0.5, (v + 0.5) H / rows - 0.5).
std::vector<Vec2> tile_centres(const ImageSize& size, long columns, long rows);

}  // namespace libcam
