#include "libcam/lens/valid_radius.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <unsupported/Eigen/Polynomials>
#include <vector>

namespace libcam {

namespace {

using Polynomial = std::vector<double>;  // coefficients in increasing powers

Polynomial product(const Polynomial& a, const Polynomial& b) {
    Polynomial out(a.size() + b.size() - 1, 0.0);
    for (std::size_t i = 0; i < a.size(); ++i)
        for (std::size_t j = 0; j < b.size(); ++j) out[i + j] += a[i] * b[j];
    return out;
}

Polynomial sum(Polynomial a, const Polynomial& b, double scale_b) {
    a.resize(std::max(a.size(), b.size()), 0.0);
    for (std::size_t i = 0; i < b.size(); ++i) a[i] += scale_b * b[i];
    return a;
}

// 2 s p'(s): the coefficient of s^i becomes 2 i c_i.
Polynomial twice_s_times_derivative(const Polynomial& p) {
    Polynomial out(p.size(), 0.0);
    for (std::size_t i = 1; i < p.size(); ++i) out[i] = 2.0 * static_cast<double>(i) * p[i];
    return out;
}

long double evaluate(std::span<const double> c, long double s, long double* derivative) {
    long double value = 0, slope = 0;
    for (std::size_t i = c.size(); i-- > 0;) {
        slope = slope * s + value;
        value = value * s + c[i];
    }
    *derivative = slope;
    return value;
}

// Newton steps in long double: the eigenvalues of the companion matrix are accurate to
// about the matrix's rounding error, not to the last bit.
double polish_root(std::span<const double> c, double root) {
    long double s = root;
    for (int i = 0; i < 4; ++i) {
        long double slope = 0;
        const long double value = evaluate(c, s, &slope);
        if (slope == 0) break;
        s -= value / slope;
    }
    return std::isfinite(static_cast<double>(s)) && s > 0 ? static_cast<double>(s) : root;
}

}  // namespace

double smallest_positive_root(std::span<const double> coefficients) {
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    std::size_t size = coefficients.size();
    while (size > 0 && coefficients[size - 1] == 0.0) --size;  // the solver needs a non-zero leading term
    if (size < 2) return kInfinity;
    const std::span<const double> c = coefficients.first(size);
    Eigen::VectorXd eigen_coefficients(static_cast<Eigen::Index>(size));
    for (std::size_t i = 0; i < size; ++i) eigen_coefficients(static_cast<Eigen::Index>(i)) = c[i];

    Eigen::PolynomialSolver<double, Eigen::Dynamic> solver;
    solver.compute(eigen_coefficients);
    double smallest = kInfinity;
    for (const std::complex<double>& root : solver.roots()) {
        // A real root comes out with a rounding-size imaginary part (larger for a double root).
        const bool real = std::abs(root.imag()) <= 1e-6 * std::abs(root);
        if (real && root.real() > 0.0) smallest = std::min(smallest, polish_root(c, root.real()));
    }
    return smallest;
}

namespace {

double search_valid_radius(std::span<const double> p, std::span<const double> q) {
    const Polynomial P(p.begin(), p.end());
    const Polynomial Q(q.begin(), q.end());
    // N = (P + 2 s P') Q - 2 s P Q'
    const Polynomial N = sum(product(sum(P, twice_s_times_derivative(P), 1.0), Q),
                             product(P, twice_s_times_derivative(Q)), -1.0);
    const double s = std::min(smallest_positive_root(N), smallest_positive_root(Q));
    return std::sqrt(s);
}

}  // namespace

// Microseconds (an eigenvalue problem): worked out once per camera (PreparedCamera,
// and per evaluation of a fit, whose coefficients change), never per point.
double radial_valid_radius(std::span<const double> p, std::span<const double> q) { return search_valid_radius(p, q); }

}  // namespace libcam
