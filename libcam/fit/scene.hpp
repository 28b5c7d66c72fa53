#pragma once
// The part of the image a fitted camera has to serve, and the pixels that sample it.
//
// A scene is the whole image, a circle, a rectangle, or every pixel whose ray lies
// within a largest angle of the optical axis. It lives on the image's pixel centres,
// [0, W-1] x [0, H-1] in OpenCV pixels (row 0 at the top): the span that
// mrcal-convert-lensmodel's sampling grid covers too.
//
// Samples are the points of a lattice over the image (mrcal's --gridn: columns
// evenly spaced from 0 to W-1, rows from 0 to H-1) that fall inside the scene, plus
// points along the scene's boundary, where the error of a simpler model usually peaks.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/geometry/pixel_grid.hpp"

namespace libcam {

// An axis-aligned box of OpenCV pixels.
struct PixelBox {
    Vec2 min = Vec2::Zero();
    Vec2 max = Vec2::Zero();
};

class Scene {
public:
    enum class Shape { WholeImage, Circle, Rectangle, FieldAngle };

    static Scene whole_image();
    // A disc of `radius` pixels around `center` (the image centre is
    // (size.centre_x(), size.centre_y()) = ((W-1)/2, (H-1)/2)).
    static Scene circle(double radius, const Vec2& center);
    // The pixels with corner0 <= (x, y) <= corner1.
    static Scene rectangle(const Vec2& corner0, const Vec2& corner1);
    // The pixels whose ray is at most max_angle_deg from the optical axis.
    static Scene field_angle(double max_angle_deg);

    Shape shape() const { return shape_; }

    // Throws InvalidArgument, naming the value and the image, when the scene is empty
    // or leaves the image (a circle's centre or a rectangle's corner outside it).
    void validate(const ImageSize& size) const;

    // One line for people, e.g. "circle of radius 500 px around (3007.5, 2007.5)".
    std::string describe(const ImageSize& size) const;

    // Is a pixel, with its ray through the source camera, in the scene? Only a
    // field-angle scene looks at the ray; a pixel without one is not in that scene.
    bool contains(const Vec2& pixel, const Unprojection& ray) const;

    // A box inside the image that holds the whole scene.
    PixelBox bounds(const PreparedCamera& source) const;

    // Points along the boundary of the scene's part of the image, about `spacing`
    // pixels apart (the scene's own edge inside the image, and for circles and field
    // angles the stretches of the image border inside the scene).
    std::vector<Vec2> boundary(const PreparedCamera& source, double spacing) const;

    // The scene's own edge as a closed polyline (last point = first) for drawing; may
    // leave the image.
    std::vector<Vec2> outline(const PreparedCamera& source) const;

private:
    Scene() = default;
    // The pixels of the cone at max_angle_deg around the optical axis, `count` of them,
    // and whether every direction of it has a pixel.
    std::vector<Vec2> cone_pixels(const PreparedCamera& source, int count, bool* complete = nullptr) const;

    Shape shape_ = Shape::WholeImage;
    double radius_ = 0.0;
    Vec2 center_ = Vec2::Zero();
    Vec2 corner0_ = Vec2::Zero();
    Vec2 corner1_ = Vec2::Zero();
    double max_angle_deg_ = 0.0;
};

// The sampling lattice over the image: `columns` x values evenly spaced on [0, W-1]
// and `rows` y values on [0, H-1], each at least 2 (mrcal-convert-lensmodel's --gridn):
// libcam's one pixel grid.
using Lattice = PixelGrid;

// Scene pixels that have a ray through the source camera, with that ray.
struct ScenePixels {
    std::vector<Vec2> pixels;        // the boundary's first
    std::vector<Vec3> directions;    // unit, in the source camera's frame
    std::size_t boundary_count = 0;  // how many of them came from the boundary
    std::size_t skipped = 0;         // scene pixels the source has no ray for (left out)
};

// Two sample sets: one to fit on and a denser one to measure the largest error on.
struct SceneSampling {
    Lattice fit_lattice;
    Lattice check_lattice;
    ScenePixels fit;
    ScenePixels check;
};

// How much denser the check samples are than the fitting samples, along each axis and
// along the boundary: the largest error of a fit lies between its samples, so it is
// measured where the fit never looked.
inline constexpr int kCheckDensity = 4;

// About this many fitting samples in the scene's bounding box when no lattice is given.
inline constexpr double kDefaultFitSamples = 2000.0;

// Samples the scene: on `lattice` if given (the fitting lattice; the check lattice is
// kCheckDensity times denser), else on a lattice sized to put about kDefaultFitSamples
// in the scene's bounding box. Throws InvalidArgument for an invalid scene, or when
// no sample of the scene has a ray through the source.
SceneSampling sample_scene(const PreparedCamera& source, const Scene& scene, std::optional<Lattice> lattice = std::nullopt);

}  // namespace libcam
