#pragma once
// SPLINED_STEREOGRAPHIC: mrcal's LENSMODEL_SPLINED_STEREOGRAPHIC_order=O_Nx=NX_Ny=NY_fov_x_deg=F
// (libmrcal 2.2, mrcal.c's _project_point_splined): a stereographic projection corrected
// by a smooth surface,
//
//   u = 2 (X, Y) / (|p| + Z) = 2 tan(theta / 2) (X, Y) / |(X, Y)|     (STEREOGRAPHIC's m)
//   m = u + delta(u)
//
// delta is a uniform B-spline surface of order O (2: quadratic, 3: cubic) over Nx x Ny
// control points, each a 2-vector, on a square grid in u centred on u = 0:
//
//   spacing 1 / spu,   spu = (Nx - 1 - margin) / (2 u_edge),   u_edge = 2 tan(F / 4),
//   margin 1 for O = 2 and 2 for O = 3,
//
// so that the spline interpolates over |u_x| <= u_edge (F / 2 degrees either side of the
// axis, horizontally) and |u_y| <= u_edge (Ny - 1 - margin) / (Nx - 1 - margin). At u, the
// (O + 1) x (O + 1) control points around the knot coordinate u spu + (N - 1) / 2 (along
// each axis) are weighted by the uniform B-spline basis. (mrcal: q = f m + c.)
//
// Coefficients: order, Nx, Ny, fov_x_deg (whole numbers; mrcal keeps them in the model's
// name), then the 2 Nx Ny control-point values in mrcal's order: control point (i, j),
// column i of Nx and row j of Ny, holds delta_x at 4 + 2 (j Nx + i) and delta_y after it.
// The four configuration values are not parameters: their Jacobian columns are zero.
//
// unproject solves u + delta(u) = m for u with the certified solver of undistort.hpp
// (started from u = m), and the ray is STEREOGRAPHIC's, (u_x, u_y, 1 - |u|^2 / 4).
//
// Valid domain: the rectangle of u above, where the spline interpolates its control
// points, wherever the map's Jacobian determinant det(I + d delta / d u) is positive.
// Outside the rectangle mrcal goes on with the edge patches' polynomials, which soon turn
// the image back on itself; here those points are flagged. Inside it the map of a fitted
// lens is one-to-one, and the determinant flags a fold where one starts (a fold the
// determinant does not see, two far-apart parts of the rectangle on one pixel, is not
// checked). valid_radius is the radius of the circle through the rectangle's corners (in
// u), valid_angle() the corners' angle from the axis, 2 atan(valid_radius / 2).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <string>

#include "libcam/error.hpp"
#include "libcam/lens/lens_model.hpp"
#include "libcam/lens/model_support.hpp"
#include "libcam/lens/stereographic.hpp"
#include "libcam/lens/undistort.hpp"
#include "libcam/text/number_format.hpp"

namespace libcam {

// The knot grid of a SPLINED_STEREOGRAPHIC lens, from its four configuration values.
struct SplineGrid {
    int order = 3;  // 2 (quadratic) or 3 (cubic)
    int nx = 0, ny = 0;
    double segments_per_u = 0;  // spu: knot intervals per unit of u
    // The knot coordinates (u spu + (N - 1) / 2) where the spline interpolates run from
    // `low` to N - 1 - low: 1 for a cubic (its patch starts one knot before), 0.5 for a
    // quadratic (its patch is centred on the nearest knot).
    double low = 1;

    // Reads the configuration at the front of a SPLINED_STEREOGRAPHIC lens's coefficients
    // and checks them and the coefficient count. Throws InvalidArgument naming field[i].
    static SplineGrid from(std::span<const double> k, const char* field) {
        const std::string name(field);
        if (k.size() < 4) {
            throw InvalidArgument(name + ": model SPLINED_STEREOGRAPHIC takes order, Nx, Ny, fov_x_deg and then 2 Nx Ny " +
                                  "control-point values, got " + std::to_string(k.size()) + " values");
        }
        const auto whole = [&](std::size_t i, const char* what, double low, double high) {
            if (!(k[i] >= low && k[i] <= high && k[i] == std::floor(k[i]))) {
                throw InvalidArgument(name + "[" + std::to_string(i) + "] (" + what + "): must be a whole number from " +
                                      format_number(low) + " to " + format_number(high) + ", got " +
                                      format_number(k[i]));
            }
            return static_cast<int>(k[i]);
        };
        SplineGrid grid;
        grid.order = whole(0, "order", 2, 3);
        // mrcal's smallest grids: one whole patch (order + 1 control points) each way.
        grid.nx = whole(1, "Nx", grid.order + 1, 65535);
        grid.ny = whole(2, "Ny", grid.order + 1, 65535);
        const int fov_x_deg = whole(3, "fov_x_deg", 1, 359);
        const std::size_t expected = 4 + 2 * static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny);
        if (k.size() != expected) {
            throw InvalidArgument(name + ": model SPLINED_STEREOGRAPHIC with Nx = " + std::to_string(grid.nx) +
                                  " and Ny = " + std::to_string(grid.ny) + " takes 4 + 2 Nx Ny = " +
                                  std::to_string(expected) + " values, got " + std::to_string(k.size()));
        }
        const int margin = grid.order == 2 ? 1 : 2;
        grid.low = grid.order == 2 ? 0.5 : 1.0;
        // As mrcal: the stereographic u of the angle fov_x_deg / 2.
        const double u_edge = 2 * std::tan(fov_x_deg / 4.0 * std::numbers::pi / 180);
        grid.segments_per_u = (grid.nx - 1 - margin) / (2 * u_edge);
        return grid;
    }

    // The rectangle where the spline interpolates, as half-widths in u.
    double half_width_x() const { return ((nx - 1) / 2.0 - low) / segments_per_u; }
    double half_width_y() const { return ((ny - 1) / 2.0 - low) / segments_per_u; }

    // The first control point (column or row) of the patch at knot coordinate `index` on
    // an axis of n knots: the patch's start knot, kept on the grid (mrcal's clamp, which
    // extrapolates the edge patch past the grid). NaN and huge values clamp too.
    int patch_start(double index, int n) const {
        const double start = (order == 3 ? std::floor(index) : std::floor(index + 0.5)) - 1;
        const double last = n - 1 - order;
        return start >= 0 ? (start <= last ? static_cast<int>(start) : static_cast<int>(last)) : 0;
    }
};

template <class Scalar>
struct SplinedStereographicLens {
    static constexpr LensType type = LensType::SplinedStereographic;
    // 4 + 2 Nx Ny: the table's kVariableCoefficientCount.
    static constexpr int num_coefficients = Eigen::Dynamic;
    // The leading coefficients that configure the model rather than parameterise it.
    static constexpr int num_configuration_values = 4;
    template <class Other>
    using InScalar = SplinedStereographicLens<Other>;
    using Vec2T = Eigen::Matrix<Scalar, 2, 1>;
    using Vec3T = Eigen::Matrix<Scalar, 3, 1>;
    using Jacobian22 = Eigen::Matrix<Scalar, 2, 2>;
    using Jacobian23 = Eigen::Matrix<Scalar, 2, 3>;
    using CoefficientJacobian = Eigen::Matrix<Scalar, 2, Eigen::Dynamic>;

    struct Parameters {
        Eigen::Matrix<Scalar, Eigen::Dynamic, 1> coefficients;
        Scalar valid_radius = Scalar(std::numeric_limits<double>::infinity());
        SplineGrid grid;
    };

    static void check_coefficients(std::span<const double> k, const char* field) { SplineGrid::from(k, field); }

    // The radius (in u) of the circle through the corners of the rectangle where the
    // spline interpolates, a little outside them: the disc that holds the domain.
    static double valid_radius(std::span<const double> k) {
        const SplineGrid grid = SplineGrid::from(k, "dist");
        return std::hypot(grid.half_width_x(), grid.half_width_y()) * (1 + 1e-12);
    }

    // The angle of the rectangle's corners from the axis.
    static double valid_angle(std::span<const double>, double radius) { return 2 * std::atan(radius / 2); }

    // Where the rectangle ends towards azimuth phi, as an angle from the axis (the
    // determinant's folds aside).
    static double edge_angle(std::span<const double> k, double azimuth) {
        const SplineGrid grid = SplineGrid::from(k, "dist");
        const double c = std::abs(std::cos(azimuth)), s = std::abs(std::sin(azimuth));
        const double u = std::min(c > 0 ? grid.half_width_x() / c : HUGE_VAL, s > 0 ? grid.half_width_y() / s : HUGE_VAL);
        return 2 * std::atan(u / 2);
    }

    static Parameters parameters(std::span<const double> k) { return parameters(k, valid_radius(k)); }

    // With the valid radius worked out before (the batch paths keep it per camera).
    static Parameters parameters(std::span<const double> k, double radius) {
        Parameters lens;
        lens.grid = SplineGrid::from(k, "dist");
        lens.coefficients.resize(static_cast<Eigen::Index>(k.size()));
        for (std::size_t i = 0; i < k.size(); ++i) lens.coefficients(static_cast<Eigen::Index>(i)) = Scalar(k[i]);
        lens.valid_radius = Scalar(radius);
        return lens;
    }

    template <class PointJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool project(const Parameters& lens, const Vec3T& point, Vec2T& m, PointJacobianPtr d_m_d_point = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        Vec2T u;
        Jacobian23 d_u_d_point;
        if (!StereographicLens<Scalar>::project({}, point, u, pass_request<PointJacobianPtr>(&d_u_d_point))) return false;
        Jacobian22 d_m_d_u;
        const bool in_domain = distort(lens, u, m, pass_request<PointJacobianPtr>(&d_m_d_u), d_m_d_coefficients);
        if constexpr (is_requested<PointJacobianPtr>) *d_m_d_point = d_m_d_u * d_u_d_point;
        return in_domain;
    }

    static bool unproject(const Parameters& lens, const Vec2T& m, Vec3T& ray) {
        return unproject_solved<SplinedStereographicLens>(lens, m, ray);
    }

    static Vec3T ray_from_undistorted(const Parameters&, const Vec2T& u) {
        return Vec3T(u.x(), u.y(), Scalar(1) - u.squaredNorm() / Scalar(4));
    }

    // The solver's 1-D start: the spline is a correction to u, so m = u.
    static Scalar radial_distortion(const Parameters&, const Scalar& r, Scalar& slope) {
        slope = Scalar(1);
        return r;
    }

    // m = u + delta(u); false outside the rectangle, where the map folds, or on overflow.
    template <class UJacobianPtr = std::nullptr_t, class CoefficientJacobianPtr = std::nullptr_t>
    static bool distort(const Parameters& lens, const Vec2T& u, Vec2T& m, UJacobianPtr d_m_d_u = nullptr,
                        CoefficientJacobianPtr d_m_d_coefficients = nullptr) {
        const SplineGrid& grid = lens.grid;
        const auto& k = lens.coefficients;
        const Scalar spu(grid.segments_per_u);
        const Scalar ix = u.x() * spu + Scalar(0.5 * (grid.nx - 1));
        const Scalar iy = u.y() * spu + Scalar(0.5 * (grid.ny - 1));
        const int column = grid.patch_start(value_as_double(ix), grid.nx);
        const int row = grid.patch_start(value_as_double(iy), grid.ny);
        // The position within the patch: [0, 1] between its second and third knots for a
        // cubic, [-1/2, 1/2] about its middle knot for a quadratic.
        std::array<Scalar, 4> wx, wy, slope_x, slope_y;
        basis(grid.order, ix - Scalar(column + 1), wx, slope_x);
        basis(grid.order, iy - Scalar(row + 1), wy, slope_y);
        Vec2T delta, d_delta_d_ix, d_delta_d_iy;
        // The order as a constant: loops of a known length, which the compiler unrolls.
        if (grid.order == 3) {
            patch_sums<3>(grid, k, column, row, wx, wy, slope_x, slope_y, delta, d_delta_d_ix, d_delta_d_iy);
        } else {
            patch_sums<2>(grid, k, column, row, wx, wy, slope_x, slope_y, delta, d_delta_d_ix, d_delta_d_iy);
        }
        m = u + delta;
        Jacobian22 jacobian;
        jacobian << Scalar(1) + spu * d_delta_d_ix.x(), spu * d_delta_d_iy.x(),  //
            spu * d_delta_d_ix.y(), Scalar(1) + spu * d_delta_d_iy.y();
        const Scalar determinant = jacobian(0, 0) * jacobian(1, 1) - jacobian(0, 1) * jacobian(1, 0);
        const Scalar low(grid.low);
        const bool inside = (ix >= low) & (ix <= Scalar(grid.nx - 1) - low) & (iy >= low) &
                            (iy <= Scalar(grid.ny - 1) - low);  // &, not &&: no branch
        if constexpr (is_requested<UJacobianPtr>) *d_m_d_u = jacobian;
        if constexpr (is_requested<CoefficientJacobianPtr>) {
            d_m_d_coefficients->setZero(2, k.size());
            for (int r = 0; r <= grid.order; ++r) {
                for (int c = 0; c <= grid.order; ++c) {
                    const Eigen::Index at = control_point(grid, column + c, row + r);
                    const Scalar weight = wy[r] * wx[c];
                    (*d_m_d_coefficients)(0, at) = weight;
                    (*d_m_d_coefficients)(1, at + 1) = weight;
                }
            }
        }
        return inside & (determinant > Scalar(0)) & all_finite(m);
    }

private:
    // delta(u) and its derivatives in the knot coordinates, from the patch whose first
    // control point is (column, row), for a spline of order kOrder.
    template <int kOrder, class Coefficients>
    static void patch_sums(const SplineGrid& grid, const Coefficients& k, int column, int row,
                           const std::array<Scalar, 4>& wx, const std::array<Scalar, 4>& wy,
                           const std::array<Scalar, 4>& slope_x, const std::array<Scalar, 4>& slope_y, Vec2T& delta,
                           Vec2T& d_delta_d_ix, Vec2T& d_delta_d_iy) {
        delta = d_delta_d_ix = d_delta_d_iy = Vec2T::Zero();
        for (int r = 0; r <= kOrder; ++r) {
            Vec2T across = Vec2T::Zero(), d_across = Vec2T::Zero();  // this row of the patch, along x
            for (int c = 0; c <= kOrder; ++c) {
                const Eigen::Index at = control_point(grid, column + c, row + r);
                const Vec2T control(k(at), k(at + 1));
                across += wx[c] * control;
                d_across += slope_x[c] * control;
            }
            delta += wy[r] * across;
            d_delta_d_ix += wy[r] * d_across;
            d_delta_d_iy += slope_y[r] * across;
        }
    }

    // Where control point (i, j) starts among the coefficients (mrcal's layout).
    static Eigen::Index control_point(const SplineGrid& grid, int i, int j) {
        return 4 + 2 * (static_cast<Eigen::Index>(j) * grid.nx + i);
    }

    // The uniform B-spline basis of the given order at t, and its derivative in t: a
    // cubic's four weights for t in [0, 1], a quadratic's three for t in [-1/2, 1/2]
    // (either extrapolated outside).
    static void basis(int order, const Scalar& t, std::array<Scalar, 4>& w, std::array<Scalar, 4>& slope) {
        const Scalar one(1), two(2), three(3), four(4), six(6);
        const Scalar t2 = t * t;
        if (order == 3) {
            const Scalar s = one - t, t3 = t2 * t;
            w = {s * s * s / six, (three * t3 - six * t2 + four) / six, (-three * t3 + three * t2 + three * t + one) / six,
                 t3 / six};
            slope = {-(s * s) / two, (three * t2 - four * t) / two, (-three * t2 + two * t + one) / two, t2 / two};
        } else {
            const Scalar a = one - two * t, c = one + two * t, half(0.5);
            w = {a * a / Scalar(8), (three - four * t2) / four, c * c / Scalar(8), Scalar(0)};
            slope = {t - half, -two * t, t + half, Scalar(0)};
        }
    }
};

}  // namespace libcam
