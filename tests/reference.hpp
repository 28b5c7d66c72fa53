#pragma once
// The high-precision reference: IEEE binary128 (113-bit significand, through
// boost::multiprecision::float128 and libquadmath). The tests run libcam's own
// templated formulas in it from the same inputs as the double (or float) code under
// test, so a difference is the rounding error of the code under test: the reference's
// own is 2^-113 ~ 1e-34 relative, 18 digits below double's.

#include <boost/multiprecision/eigen.hpp>
#include <boost/multiprecision/float128.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "libcam/geometry/vector_math.hpp"

namespace libcam::test {

using Quad = boost::multiprecision::float128;
using Vec2Q = Vec2T<Quad>;
using Vec3Q = Vec3T<Quad>;

// The spacing of Scalar's numbers at |x| (its ulp), as a Quad; the smallest subnormal
// spacing at 0.
template <class Scalar>
Quad ulp_of(const Quad& x) {
    using Limits = std::numeric_limits<Scalar>;
    const Quad magnitude = abs(x);
    if (magnitude < Quad(Limits::min())) return Quad(Limits::denorm_min());
    return ldexp(Quad(1), static_cast<int>(ilogb(magnitude)) - (Limits::digits - 1));
}

// |value - reference| in ulps of Scalar at the reference.
template <class Scalar>
double ulps(const Scalar& value, const Quad& reference) {
    return static_cast<double>(abs(Quad(value) - reference) / ulp_of<Scalar>(reference));
}

// A vector's error in ulps of Scalar at its norm (normwise: the error of the largest
// component counts against the vector's size, not against a component that is ~0).
template <class Scalar, int N>
double ulps(const Eigen::Matrix<Scalar, N, 1>& value, const Eigen::Matrix<Quad, N, 1>& reference) {
    return static_cast<double>((value.template cast<Quad>() - reference).norm() / ulp_of<Scalar>(reference.norm()));
}

// Angle in radians between a computed direction and the reference direction.
template <class Scalar>
double angle_error(const Vec3T<Scalar>& value, const Vec3Q& reference) {
    return static_cast<double>(angle_between<Quad>(value.template cast<Quad>(), reference));
}

// -log10 of a relative error: the decimal digits that survive (16 for a correctly rounded double).
inline double digits_from_relative(double relative) {
    return relative > 0 ? -std::log10(relative) : std::numeric_limits<double>::infinity();
}

// The largest value seen and where it was seen, for error sweeps. A NaN is the worst
// of all and stays. `describe` (called only for a new worst) says where.
struct Worst {
    double value = 0;
    std::string where;
    template <class Describe>
    void update(double candidate, Describe&& describe) {
        if (std::isnan(value) || candidate <= value) return;
        value = candidate;
        where = describe();
    }
};

}  // namespace libcam::test
