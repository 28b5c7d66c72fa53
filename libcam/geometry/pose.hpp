#pragma once
// Extrinsics in OpenCV's and mrcal's direction: world to camera,
//     X_cam = R X_world + t,
// with the camera frame x right, y down, z forward. The rows of R are the camera
// axes in world coordinates and the camera centre is C = -R^T t. The rotation
// vector rvec is Rodrigues' (axis times angle), as cv::Rodrigues and mrcal's
// rt_cam_ref use it.

#include <Eigen/Core>

#include "libcam/geometry/vector_math.hpp"

namespace libcam {

using Mat34 = Eigen::Matrix<double, 3, 4>;

// Rodrigues' formula both ways, through a quaternion so that angles near 0 and near pi
// keep their accuracy. Throw InvalidArgument for a non-finite rvec, or an R that is not
// a rotation (within kRotationTolerance).
Vec3 rvec_from_rotation(const Mat3& R);
Mat3 rotation_from_rvec(const Vec3& rvec);

// Largest |R^T R - I| and |det R - 1| accepted for a rotation read from outside.
inline constexpr double kRotationTolerance = 1e-9;

// Files that print rotations with few digits (five decimals in OpenVINS's rig files,
// float32 in NeRF's transforms.json) give an R whose R^T R is I only to about 1e-5.
// Such a matrix, within kRoundedRotationTolerance of a rotation, is read as the nearest
// rotation (by SVD: what the rounding moved it from); one within kRotationTolerance, or
// farther off than kRoundedRotationTolerance, is returned as it is (validate() refuses
// the latter).
inline constexpr double kRoundedRotationTolerance = 1e-4;
Mat3 nearest_rotation_if_rounded(const Mat3& R);

// t = -R C for a camera at centre C, and back C = -R^T t.
template <class Scalar>
Vec3T<Scalar> translation_from_centre(const Mat3T<Scalar>& R, const Vec3T<Scalar>& centre) {
    return -(R * centre);
}
template <class Scalar>
Vec3T<Scalar> centre_from_translation(const Mat3T<Scalar>& R, const Vec3T<Scalar>& t) {
    return -(R.transpose() * t);
}

struct Pose {
    Mat3 R = Mat3::Identity();
    Vec3 t = Vec3::Zero();

    static Pose from_rvec(const Vec3& rvec, const Vec3& t) { return {rotation_from_rvec(rvec), t}; }
    // A camera at `centre` whose axes (rows of R) are `R`.
    static Pose from_centre(const Mat3& R, const Vec3& centre) { return {R, translation_from_centre<double>(R, centre)}; }

    Vec3 rvec() const { return rvec_from_rotation(R); }
    Vec3 centre() const { return centre_from_translation<double>(R, t); }
    Mat34 matrix() const;  // [R | t]

    // The transform back (X_world = R^T X_cam - R^T t), as a pose: a file's "camera in
    // the reference frame" turned into libcam's world-to-camera, and the other way.
    Pose inverse() const { return {R.transpose(), -(R.transpose() * t)}; }
    // This transform applied after `first`: X -> R (R_first X + t_first) + t (a camera
    // placed relative to another, or moved after its pose).
    Pose after(const Pose& first) const { return {R * first.R, R * first.t + t}; }

    Vec3 camera_from_world(const Vec3& world) const { return R * world + t; }
    Vec3 world_direction_from_camera(const Vec3& direction) const { return R.transpose() * direction; }

    // Throws InvalidArgument naming `field` unless R is a finite proper rotation
    // (within kRotationTolerance) and t is finite.
    void validate(const char* field = "R") const;
};

}  // namespace libcam
