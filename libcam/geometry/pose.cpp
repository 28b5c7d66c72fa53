#include "libcam/geometry/pose.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <string>

#include "libcam/error.hpp"

namespace libcam {

Mat3 nearest_rotation_if_rounded(const Mat3& R) {
    const double off = (R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff();
    if (off <= kRotationTolerance || !(off <= kRoundedRotationTolerance) || !(R.determinant() > 0)) return R;
    const Eigen::JacobiSVD<Mat3> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
    return svd.matrixU() * svd.matrixV().transpose();
}

namespace {

// Throws InvalidArgument naming `field` unless R is finite and a rotation to within
// kRotationTolerance.
void require_rotation(const char* field, const Mat3& R) {
    require_finite_all(field, R);
    const double orthogonality = (R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff();
    const double det = R.determinant();
    if (orthogonality > kRotationTolerance || std::abs(det - 1.0) > kRotationTolerance) {
        throw InvalidArgument(std::string(field) + ": not a rotation matrix (max |R^T R - I| = " +
                              format_number(orthogonality) + ", det = " + format_number(det) + ", tolerance " +
                              format_number(kRotationTolerance) + ")");
    }
}

}  // namespace

Vec3 rvec_from_rotation(const Mat3& R) {
    require_rotation("R", R);
    // Eigen converts R to a quaternion (Shepperd's method), then takes
    // angle = 2 atan2(|q.vec|, |q.w|): accurate at every angle.
    const Eigen::AngleAxisd axis_angle(R);
    return axis_angle.angle() * axis_angle.axis();
}

Mat3 rotation_from_rvec(const Vec3& rvec) {
    require_finite_all("rvec", rvec);
    const double angle = rvec.norm();
    if (angle == 0.0) return Mat3::Identity();
    return Eigen::AngleAxisd(angle, rvec / angle).toRotationMatrix();
}

Mat34 Pose::matrix() const {
    Mat34 Rt;
    Rt << R, t;
    return Rt;
}

void Pose::validate(const char* field) const {
    require_rotation(field, R);
    require_finite_all("t", t);
}

}  // namespace libcam
