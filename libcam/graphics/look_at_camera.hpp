#pragma once
// The graphics (look-at) camera: an eye, a gaze (or a target), an up vector, a
// field-of-view angle and an image size. The ray through pixel (x, y) is given by the
// look-at formula
//
//     d = alpha u + beta v + w_gaze,
//     alpha = tan_x (2x - W + 1) / W,    beta = tan_y (2y - H + 1) / H,
//
// where tan_x, tan_y are the tangents of half the field of view on each image axis
// and rows are counted upward from the bottom-left pixel.
//
// The look-at formula's own fov (FovAxis::Both) puts the same angle on both axes, each
// normalised by its own side, so tan_x = tan_y and the pixels are not square when
// W != H. The other axes give square pixels: the angle spans the width (Horizontal),
// the height (Vertical) or the diagonal (Diagonal) of the image, and the other tangent
// follows from the aspect ratio.

#include <string_view>

#include "libcam/graphics/look_at_formulas.hpp"
#include "libcam/geometry/image_size.hpp"
#include "libcam/geometry/pixel_origin.hpp"
#include "libcam/geometry/vector_math.hpp"

namespace libcam {

// PixelOrigin, opencv_pixel and user_pixel live with the geometry: geometry/pixel_origin.hpp.
std::string_view to_string(FovAxis axis);
FovAxis fov_axis_from_string(std::string_view text);  // throws InvalidArgument

// Smallest angle between up and the gaze: below it the camera's roll is undefined
// (a one-ulp change of up turns u by more than 1e-7 rad) and validate() refuses it.
inline constexpr double kMinUpGazeAngleRad = 1e-9;

// The double instances of the formulas in look_at_formulas.hpp.
using Basis = BasisT<double>;
using LookAtRayFormula = LookAtRayFormulaT<double>;

struct LookAtCamera {
    Vec3 eye = Vec3::Zero();
    Vec3 gaze = Vec3(0, 0, -1);  // any positive length
    Vec3 up = Vec3(0, 1, 0);     // need not be orthogonal to the gaze
    double fov_deg = 90.0;
    FovAxis fov_axis = FovAxis::Both;
    ImageSize size{1, 1};

    static LookAtCamera look_at(const Vec3& eye, const Vec3& target, const Vec3& up, double fov_deg,
                             FovAxis fov_axis, ImageSize size);

    // Throws InvalidArgument naming the field unless: every number is finite,
    // 0 < fov_deg < 180, the size is valid, the gaze and up are non-zero and at
    // least kMinUpGazeAngleRad apart.
    void validate() const;

    // These, and look_at_ray and field_ray, validate() first.
    Basis basis(Handedness handedness = Handedness::Left) const;

    // (tan_x, tan_y): tangents of half the field of view across the width and height.
    Vec2 half_tangents() const;

    LookAtRayFormula look_at_formula() const;

    // The look-at formula's ray d = alpha u + beta v + w_gaze through pixel (x, y), not
    // normalised.
    Vec3 look_at_ray(const Vec2& pixel, PixelOrigin origin = PixelOrigin::BottomLeft) const {
        return look_at_formula().ray(pixel, origin);
    }

    // The ray through a point of the field of view given as fractions (sx, sy) of its
    // half-extent, y up: (-1, -1) is the lower-left corner, (0, 1) the top centre.
    Vec3 field_ray(double sx, double sy) const { return look_at_formula().field_ray(sx, sy); }
};

// The look-at formula of a look-at camera in Scalar: look_at_formula() in double, and the
// tests' reference in 113 bits from the same inputs.
template <class Scalar>
LookAtRayFormulaT<Scalar> look_at_formula_in(const LookAtCamera& camera) {
    return {basis_from_gaze_up<Scalar>(camera.gaze.cast<Scalar>(), camera.up.cast<Scalar>(), Handedness::Left),
            half_tangents_of_fov<Scalar>(Scalar(camera.fov_deg), camera.fov_axis, camera.size), camera.size};
}
inline LookAtRayFormula LookAtCamera::look_at_formula() const {
    validate();
    return look_at_formula_in<double>(*this);
}

// tan(angle/2) for an angle in degrees in (0, 180), accurate near 180 too; evaluated in
// long double and rounded once.
inline double tan_half_angle_deg(double angle_deg) {
    return static_cast<double>(tan_half_angle_deg<long double>(angle_deg));
}
// The inverse: 2 atan(tangent) in degrees, likewise.
inline double angle_deg_from_half_tangent(double tangent) {
    return static_cast<double>(angle_deg_from_half_tangent<long double>(tangent));
}

}  // namespace libcam
