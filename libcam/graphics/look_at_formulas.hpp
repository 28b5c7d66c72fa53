#pragma once
// The look-at camera's formulas (the look-at ray, the basis, the half-angle tangents, K
// from the fov), each written once as a template on the scalar type. The double API
// (LookAtCamera, to_camera) calls them in double; the tests call the very same code in a
// 113-bit type and use it as the reference (tests/reference.hpp). Where a double overload
// of the same name exists, the template's scalar is never deduced (std::type_identity_t).

#include <cmath>
#include <type_traits>

#include "libcam/geometry/image_size.hpp"
#include "libcam/geometry/pixel_origin.hpp"
#include "libcam/geometry/vector_math.hpp"

namespace libcam {

enum class FovAxis { Horizontal, Vertical, Diagonal, Both };

// The two bases of the look-at camera: w along the gaze (left-handed, the one the
// look-at formula uses) or against it (right-handed). u and v are the same in both.
enum class Handedness { Left, Right };

// The type a half-angle tangent is evaluated in: long double for the built-in types, so
// that double and float get it rounded once, with exact cases exact (tan 45 deg = 1);
// a wider class type (the tests' reference) uses itself.
template <class Scalar>
using TangentScalar = std::conditional_t<std::is_floating_point_v<Scalar>, long double, Scalar>;

// tan(angle/2) for an angle in degrees in (0, 180), evaluated in Scalar. Near 180
// degrees tan(angle/2) = 1 / tan(90 - angle/2), and 90 - angle/2 is exact, so the small
// complement keeps its digits.
template <class Scalar>
Scalar tan_half_angle_deg(const std::type_identity_t<Scalar>& angle_deg) {
    using std::tan;
    const Scalar half = angle_deg / Scalar(2);
    const Scalar radians_per_degree = pi_in<Scalar>() / Scalar(180);
    if (half > Scalar(45)) return Scalar(1) / tan((Scalar(90) - half) * radians_per_degree);
    return tan(half * radians_per_degree);
}

// The inverse: 2 atan(tangent) in degrees, through the complement above 90 degrees.
template <class Scalar>
Scalar angle_deg_from_half_tangent(const std::type_identity_t<Scalar>& tangent) {
    using std::atan;
    const Scalar radians_per_degree = pi_in<Scalar>() / Scalar(180);
    if (tangent > Scalar(1)) return Scalar(180) - Scalar(2) * atan(Scalar(1) / tangent) / radians_per_degree;
    return Scalar(2) * atan(tangent) / radians_per_degree;
}

// (tan_x, tan_y), the tangents of half the field of view across the width and height,
// from the tangent of half the fov on `axis`.
template <class Scalar>
Vec2T<Scalar> half_tangents_on_axes(const Scalar& tangent, FovAxis axis, const ImageSize& size) {
    using std::hypot;
    const Scalar width(size.width), height(size.height);
    switch (axis) {
        case FovAxis::Both: return {tangent, tangent};
        case FovAxis::Horizontal: return {tangent, tangent * height / width};
        case FovAxis::Vertical: return {tangent * width / height, tangent};
        case FovAxis::Diagonal: {
            const Scalar diagonal = hypot(width, height);
            return {tangent * (width / diagonal), tangent * (height / diagonal)};
        }
    }
    return {tangent, tangent};
}

// (tan_x, tan_y) of an fov in degrees on `axis`; the tangent itself in TangentScalar.
template <class Scalar>
Vec2T<Scalar> half_tangents_of_fov(const Scalar& fov_deg, FovAxis axis, const ImageSize& size) {
    using Wide = TangentScalar<Scalar>;
    const Scalar tangent(tan_half_angle_deg<Wide>(Wide(fov_deg)));
    return half_tangents_on_axes<Scalar>(tangent, axis, size);
}

template <class Scalar>
struct BasisT {
    Vec3T<Scalar> u;  // right
    Vec3T<Scalar> v;  // up
    Vec3T<Scalar> w;  // along the gaze (Left) or against it (Right)
    Handedness handedness = Handedness::Left;

    Vec3T<Scalar> gaze() const { return handedness == Handedness::Left ? w : Vec3T<Scalar>(-w); }
};

// u = gaze x up for both handednesses (w x up with w along the gaze, or
// up x w with w against it). The accurate cross product of the raw inputs (scaled by
// powers of two, exactly) keeps u right to a few ulps even when up is within a small
// angle of the gaze, at any magnitude.
template <class Scalar>
BasisT<Scalar> basis_from_gaze_up(const Vec3T<Scalar>& gaze, const Vec3T<Scalar>& up, Handedness handedness) {
    const Vec3T<Scalar> gaze_scaled = scaled_to_unit_range<Scalar>(gaze);
    const Vec3T<Scalar> u = accurate_cross<Scalar>(gaze_scaled, scaled_to_unit_range<Scalar>(up)).normalized();
    const Vec3T<Scalar> along_gaze = gaze_scaled.normalized();
    const Vec3T<Scalar> v = accurate_cross<Scalar>(u, along_gaze);
    return {u, v, handedness == Handedness::Left ? along_gaze : Vec3T<Scalar>(-along_gaze), handedness};
}

// The look-at formula with everything per camera computed once, for generating many rays:
//     d = alpha u + beta v + w_gaze,
//     alpha = tan_x (2x - W + 1) / W,    beta = tan_y (2y - H + 1) / H.
template <class Scalar>
struct LookAtRayFormulaT {
    BasisT<Scalar> basis;    // left-handed: w along the gaze
    Vec2T<Scalar> tangents;  // (tan_x, tan_y)
    ImageSize size;

    // d through pixel (x, y), not normalised. 2x - W + 1 is exact for pixels up to 2^52.
    Vec3T<Scalar> ray(const Vec2T<Scalar>& pixel, PixelOrigin origin) const {
        const Scalar width(size.width), height(size.height);
        const Scalar y = origin == PixelOrigin::BottomLeft ? pixel.y() : flip_row<Scalar>(pixel.y(), size);
        return field_ray((Scalar(2) * pixel.x() - width + Scalar(1)) / width,
                         (Scalar(2) * y - height + Scalar(1)) / height);
    }

    // (sx, sy): fractions of the half field of view, y up.
    Vec3T<Scalar> field_ray(const Scalar& sx, const Scalar& sy) const {
        return (tangents.x() * sx) * basis.u + (tangents.y() * sy) * basis.v + basis.w;
    }
};

// The focal lengths of the pinhole camera with these half tangents:
// fx = W / (2 tan_x), fy = H / (2 tan_y); the principal point is the image centre.
template <class Scalar>
Vec2T<Scalar> focal_lengths_from_half_tangents(const Vec2T<Scalar>& tangents, const ImageSize& size) {
    return {Scalar(size.width) / (Scalar(2) * tangents.x()), Scalar(size.height) / (Scalar(2) * tangents.y())};
}

// R with rows (u, -v, gaze): the camera axes of OpenCV (x right, y down, z forward).
template <class Scalar>
Mat3T<Scalar> rotation_from_basis(const BasisT<Scalar>& basis) {
    Mat3T<Scalar> R;
    R.row(0) = basis.u.transpose();
    R.row(1) = -basis.v.transpose();
    R.row(2) = basis.gaze().transpose();
    return R;
}

}  // namespace libcam
