#pragma once
// The look-at camera <-> calibrated camera.
//
// Forward (exact): K = [W/(2 tan_x), 0, (W-1)/2; 0, H/(2 tan_y), (H-1)/2; 0, 0, 1],
// R has rows (u, -v, gaze) (OpenCV axes: x right, y down, z forward), t = -R eye.
// Then R^T K^-1 [x, H-1-y, 1] is the look-at formula's d for pixel (x, y) exactly, the
// pixel counted from the bottom-left as the look-at formula counts it.
//
// Back: eye = -R^T t, gaze = third row of R, up = minus the second row (the camera's
// own up, orthogonal to the gaze: the original up is not recoverable, only the plane
// it spans with the gaze), fov on every axis. A camera is a look-at camera only with a
// pinhole lens, no skew, the principal point at the image centre, and pixels that
// fit the axis: square pixels (fx = fy) for horizontal/vertical/diagonal, equal half
// tangents (W/fx = H/fy) for "both" (the same angle on both axes). Anything else is
// reported, not dropped.

#include <string>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/graphics/look_at_camera.hpp"

namespace libcam {

// Relative tolerance for "is a look-at camera": principal point offset against the image
// side, skew against fx, pixel-shape mismatch against fx.
inline constexpr double kLookAtCameraTolerance = 1e-9;

// The pinhole camera of a look-at camera, in Scalar: the one implementation behind
// to_camera (in double), and the tests' reference (in 113 bits, from the same inputs).
template <class Scalar>
struct FovPinholeT {
    Vec2T<Scalar> focal;            // fx, fy
    Vec2T<Scalar> principal_point;  // cx, cy: the image centre
    Mat3T<Scalar> R;                // rows u, -v, gaze
    Vec3T<Scalar> t;                // -R eye
};

template <class Scalar>
FovPinholeT<Scalar> pinhole_from_fov(const LookAtCamera& look_at_camera) {
    const ImageSize& size = look_at_camera.size;
    const Vec2T<Scalar> tangents = half_tangents_of_fov<Scalar>(Scalar(look_at_camera.fov_deg), look_at_camera.fov_axis, size);
    const BasisT<Scalar> basis = basis_from_gaze_up<Scalar>(look_at_camera.gaze.template cast<Scalar>(),
                                                            look_at_camera.up.template cast<Scalar>(), Handedness::Left);
    const Mat3T<Scalar> R = rotation_from_basis<Scalar>(basis);
    return {focal_lengths_from_half_tangents<Scalar>(tangents, size),
            Vec2T<Scalar>(Scalar(size.width - 1) / Scalar(2), Scalar(size.height - 1) / Scalar(2)), R,
            translation_from_centre<Scalar>(R, look_at_camera.eye.template cast<Scalar>())};
}

// Validates the look-at camera and returns its calibrated camera (PINHOLE lens).
Camera to_camera(const LookAtCamera& look_at_camera);

// Full angles in degrees. For a centred principal point, 2 atan(W / (2 fx)) and so on;
// in general the angle spanned across the image through the principal point, and for
// the diagonal the larger of the two corner-to-corner angles.
struct FovAngles {
    double horizontal = 0.0;
    double vertical = 0.0;
    double diagonal = 0.0;
    double on_axis(FovAxis axis) const;  // Both -> horizontal (equal to vertical when valid)
};

// The image's extent on the plane z = 1 in front of the camera, y up (glFrustum's
// left, right, bottom, top at near = 1); asymmetric when the principal point is off centre.
struct Frustum {
    double left = 0.0;
    double right = 0.0;
    double bottom = 0.0;
    double top = 0.0;
};

struct FovDescription {
    FovAngles fov_deg;
    Frustum frustum;
    Vec3 eye = Vec3::Zero();
    Vec3 gaze = Vec3::Zero();  // unit
    Vec3 up = Vec3::Zero();    // unit, orthogonal to the gaze
    // Axes on which the camera is a look-at camera (empty when it is none).
    std::vector<FovAxis> fov_axes;
    // Why it is not a look-at camera on some axis (empty when every axis works).
    std::vector<std::string> deviations;

    bool is_look_at_camera() const { return !fov_axes.empty(); }
    bool fits_axis(FovAxis axis) const;
};

FovDescription describe_fov(const Camera& camera);

// The look-at camera on `axis`; throws NotRepresentable with the reasons when the camera
// is not one on that axis.
LookAtCamera to_look_at_camera(const Camera& camera, FovAxis axis);

}  // namespace libcam
