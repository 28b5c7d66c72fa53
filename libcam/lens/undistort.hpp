#pragma once
// The one iterative unprojection solver, shared by every model without a closed-form
// inverse (OpenCV's family, FISHEYE), as COLMAP shares one IterativeUndistortion, but
// with the analytic Jacobian and a certified result.
//
// Such a model factors as  camera point -> u -> m = Model::distort(u), where u is the
// model's undistorted point ((x/z, y/z) for OpenCV's models, theta times the unit
// direction for FISHEYE) and |u| < valid_radius is the model's valid domain.
// Unprojection solves distort(u) = m:
//   1. the radial part alone, in 1-D: d(r) = |m| for r in [0, valid_radius), where d
//      increases (that is how valid_radius is chosen), by Newton's method kept inside a
//      shrinking bracket by bisection: a start that converges for every pixel;
//   2. the whole distortion (tangential, thin prism, tilt) in 2-D from there: Newton's
//      method with the analytic 2x2 Jacobian, halving a step that leaves the valid disc
//      or does not reduce the residual, until the residual stops decreasing.
// The answer is valid only inside the valid disc with a residual at rounding level
// (unprojection_tolerance); anything else is flagged, never returned approximately.
//
// A model provides, besides distort(lens, u, m, d_m_d_u):
//   Scalar radial_distortion(lens, r, Scalar& slope)   d(r) and d'(r)

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

namespace libcam {

// The largest residual |distort(u) - m| accepted as converged: a few dozen roundings of
// the distorted point's magnitude. In double with |m| = 3 that is 6e-14 (1e-10 px at
// f = 2000).
template <class Scalar>
Scalar unprojection_tolerance(const Scalar& distorted_radius) {
    return Scalar(64) * std::numeric_limits<Scalar>::epsilon() * (Scalar(1) + distorted_radius);
}

// A residual still above about two roundings of the distorted point, which another
// Newton step may reduce: 2 eps (1 + |m|). (The full solver steps until the residual
// stops decreasing; the batch `exact` method takes up to three more steps, each kept only
// if it lowers the residual, for a block in which any pixel is still above this after
// two.)
template <class Scalar>
Scalar reducible_residual(const Scalar& distorted_radius) {
    return Scalar(2) * std::numeric_limits<Scalar>::epsilon() * (Scalar(1) + distorted_radius);
}

// The Newton step J^-1 residual for the 2x2 Jacobian J, by its adjugate. Not finite
// when J is singular.
template <class Scalar>
Eigen::Matrix<Scalar, 2, 1> newton_step(const Eigen::Matrix<Scalar, 2, 2>& J, const Eigen::Matrix<Scalar, 2, 1>& residual) {
    const Scalar inverse_determinant = Scalar(1) / (J(0, 0) * J(1, 1) - J(0, 1) * J(1, 0));
    return {(J(1, 1) * residual.x() - J(0, 1) * residual.y()) * inverse_determinant,
            (J(0, 0) * residual.y() - J(1, 0) * residual.x()) * inverse_determinant};
}

namespace detail {

// Solves d(r) = target for r in [0, valid_radius) (d increasing there); false when no
// bracket exists. With no bound, the bracket is found by doubling.
template <class Model, class Parameters, class Scalar>
bool solve_radial(const Parameters& lens, Scalar target, Scalar& r) {
    using std::abs;
    constexpr int kMaxIterations = 200;
    Scalar low(0), high = lens.valid_radius, slope(0);
    if (high < std::numeric_limits<Scalar>::infinity()) {
        // Where d folds over, d(valid_radius) is its largest value. Where the rational
        // model's denominator reaches 0 instead, d runs to +infinity there, and the root's
        // rounding may put valid_radius just past it, where d has changed sign: every
        // target is then below d inside the bracket.
        const Scalar at_high = Model::radial_distortion(lens, high, slope);
        if (!(at_high > target) && !(at_high < Scalar(0))) {
            // Past the radial part's maximum: only the tangential terms can still bring
            // the pixel in. Start step 2 well inside the fold, where its Jacobian is sound.
            r = high * Scalar(0.9);
            return true;
        }
    } else {
        high = std::max(target, Scalar(1));
        for (int i = 0; Model::radial_distortion(lens, high, slope) < target; ++i) {
            if (i == 64) return false;
            low = high;
            high *= 2;
        }
    }
    r = (target > low && target < high) ? target : low + (high - low) / Scalar(2);
    for (int i = 0; i < kMaxIterations; ++i) {
        const Scalar error = Model::radial_distortion(lens, r, slope) - target;
        if (error == Scalar(0)) return true;
        (error < Scalar(0) ? low : high) = r;
        const Scalar newton = r - error / slope;
        const Scalar next = (newton > low && newton < high) ? newton : low + (high - low) / Scalar(2);
        if (abs(next - r) <= std::numeric_limits<Scalar>::epsilon() * r || next == low || next == high) {
            r = next;
            return true;
        }
        r = next;
    }
    return true;  // the bracket has shrunk as far as it goes; step 2 decides
}

}  // namespace detail

// Step 2 alone: from the start u, Newton's method on distort(u) = m with step halving,
// until the residual stops decreasing. True when it ends inside the valid domain with
// a residual within unprojection_tolerance(|m|); u is then the solution.
template <class Model, class Parameters, class Scalar>
bool polish_undistorted(const Parameters& lens, const Eigen::Matrix<Scalar, 2, 1>& m, Eigen::Matrix<Scalar, 2, 1>& u) {
    using std::abs;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;
    constexpr int kMaxIterations = 30;
    constexpr int kMaxHalvings = 30;

    Vec2T m_u;
    Jacobian22 d_m_d_u;
    if (!Model::distort(lens, u, m_u, &d_m_d_u)) return false;
    Vec2T residual = m_u - m;
    Scalar error = residual.norm();
    const Scalar tolerance = unprojection_tolerance(m.norm());
    for (int iteration = 0; iteration < kMaxIterations && error > Scalar(0); ++iteration) {
        const Vec2T step = newton_step(d_m_d_u, residual);
        if (!(abs(step.x()) < std::numeric_limits<Scalar>::infinity() && abs(step.y()) < std::numeric_limits<Scalar>::infinity())) break;
        // Once converged, only a full step that still lowers the residual is worth taking.
        const int halvings = error > tolerance ? kMaxHalvings : 0;
        bool improved = false;
        Scalar fraction(1);
        for (int h = 0; h <= halvings && !improved; ++h, fraction /= Scalar(2)) {
            const Vec2T candidate = u - fraction * step;
            Vec2T m_candidate;
            Jacobian22 d_candidate;
            if (!Model::distort(lens, candidate, m_candidate, &d_candidate)) continue;
            const Vec2T candidate_residual = m_candidate - m;
            const Scalar candidate_error = candidate_residual.norm();
            if (candidate_error < error) {
                u = candidate;
                residual = candidate_residual;
                error = candidate_error;
                d_m_d_u = d_candidate;
                improved = true;
            }
        }
        if (!improved) break;
    }
    return error <= tolerance;
}

// Solves Model::distort(lens, u) = m for u, as described above. Returns false, and
// leaves u unspecified, when there is no accurate solution inside the valid domain.
template <class Model, class Parameters, class Scalar>
bool solve_undistorted(const Parameters& lens, const Eigen::Matrix<Scalar, 2, 1>& m, Eigen::Matrix<Scalar, 2, 1>& u) {
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    const Scalar distorted_radius = m.norm();
    Scalar r(0);
    if (!detail::solve_radial<Model>(lens, distorted_radius, r)) return false;
    u = distorted_radius > Scalar(0) ? Vec2T(m * (r / distorted_radius)) : Vec2T::Zero();
    return polish_undistorted<Model>(lens, m, u);
}

// A solved model's unproject: the ray through m is Model::ray_from_undistorted of the
// solution; false (ray left as it was) where there is none.
template <class Model, class Parameters, class Scalar>
bool unproject_solved(const Parameters& lens, const Eigen::Matrix<Scalar, 2, 1>& m, Eigen::Matrix<Scalar, 3, 1>& ray) {
    Eigen::Matrix<Scalar, 2, 1> u;
    if (!solve_undistorted<Model>(lens, m, u)) return false;
    ray = Model::ray_from_undistorted(lens, u);
    return true;
}

}  // namespace libcam
