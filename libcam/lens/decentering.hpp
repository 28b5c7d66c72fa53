#pragma once
// The decentering (tangential) and thin-prism terms shared by the models that add them
// to a point (x, y) after a radial distortion, with r2 = x^2 + y^2:
//
//   decentering = (2 p1 x y + p2 (r2 + 2 x^2),  p1 (r2 + 2 y^2) + 2 p2 x y)
//   thin prism  = (s1 r2 + s2 r2^2,  s3 r2 + s4 r2^2)
//
// in OpenCV's naming (Brown-Conrady's decentering, Weng et al.'s thin prism, TPAMI
// 1992). COLMAP's THIN_PRISM_FISHEYE and RAD_TAN_THIN_PRISM_FISHEYE add them in the
// plane of the equidistant fisheye (thin_prism_fisheye.hpp, fisheye624.hpp).

#include <Eigen/Core>

namespace libcam::detail {

template <class Scalar>
using Vec2Of = Eigen::Matrix<Scalar, 2, 1>;
template <class Scalar>
using Jacobian22Of = Eigen::Matrix<Scalar, 2, 2>;

template <class Scalar>
Vec2Of<Scalar> decentering(const Scalar& p1, const Scalar& p2, const Vec2Of<Scalar>& point) {
    const Scalar x = point.x(), y = point.y(), two(2);
    const Scalar r2 = x * x + y * y, xy2 = two * x * y;
    return {p1 * xy2 + p2 * (r2 + two * x * x), p1 * (r2 + two * y * y) + p2 * xy2};
}

// d decentering / d (x, y).
template <class Scalar>
Jacobian22Of<Scalar> decentering_jacobian(const Scalar& p1, const Scalar& p2, const Vec2Of<Scalar>& point) {
    const Scalar x = point.x(), y = point.y(), two(2), six(6);
    const Scalar mixed = two * (p1 * x + p2 * y);
    Jacobian22Of<Scalar> jacobian;
    jacobian << two * p1 * y + six * p2 * x, mixed,  //
        mixed, six * p1 * y + two * p2 * x;
    return jacobian;
}

// d decentering / d p1 and d p2 (the columns).
template <class Scalar>
Jacobian22Of<Scalar> decentering_coefficient_jacobian(const Vec2Of<Scalar>& point) {
    const Scalar x = point.x(), y = point.y(), two(2);
    const Scalar r2 = x * x + y * y, xy2 = two * x * y;
    Jacobian22Of<Scalar> jacobian;
    jacobian << xy2, r2 + two * x * x,  //
        r2 + two * y * y, xy2;
    return jacobian;
}

}  // namespace libcam::detail
