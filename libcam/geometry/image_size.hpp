#pragma once
// The size of an image in pixels. Pixel centres are at integer coordinates (OpenCV's
// convention): the image spans [-0.5, width - 0.5] x [-0.5, height - 0.5].

namespace libcam {

// Largest accepted image side; larger sizes are rejected as a likely unit mistake.
inline constexpr long kMaxImageSide = 1'000'000;

struct ImageSize {
    long width = 0;
    long height = 0;

    // Throws InvalidArgument naming `field` unless 1 <= width, height <= kMaxImageSide.
    void validate(const char* field = "image_size") const;

    double centre_x() const { return 0.5 * static_cast<double>(width - 1); }
    double centre_y() const { return 0.5 * static_cast<double>(height - 1); }

    bool operator==(const ImageSize&) const = default;
};

// Whether a pixel lies on an image of `size`: within the pixels' own area,
// [-0.5, W - 0.5] x [-0.5, H - 0.5], widened by `margin` (negative: narrowed; -0.5 keeps
// to the span of the pixel centres, where interpolation never reads past the edge). The
// comparisons joined by &, not &&: no branch, so that the remap kernels' loops vectorise.
inline bool on_image(double x, double y, const ImageSize& size, double margin = 0.0) {
    const double edge = 0.5 + margin;
    return (x >= -edge) & (y >= -edge) & (x <= static_cast<double>(size.width) - 1.0 + edge) &
           (y <= static_cast<double>(size.height) - 1.0 + edge);
}

}  // namespace libcam
