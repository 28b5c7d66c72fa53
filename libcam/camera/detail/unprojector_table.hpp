#pragma once
// Internal to libcam (camera/unprojector.cpp): the table of exact undistorted points
// over the image, its interpolation (bilinear for fast and exact's start, Catmull-Rom
// bicubic for lut), and the per-cell check of the fast and lut estimates.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/camera/unprojector.hpp"
#include "libcam/lens/undistort.hpp"

namespace libcam::detail {

// Node n of the table, (x, y) as a two-lane vector (the kernels' node).
template <class Scalar>
struct NodePairs {
    typedef Scalar Two __attribute__((vector_size(2 * sizeof(Scalar))));
    const Scalar* pairs;
    [[gnu::always_inline]] Two operator()(std::size_t n) const {
        Two xy;
        __builtin_memcpy(&xy, pairs + 2 * n, sizeof xy);
        return xy;
    }
};

// The interpolations of the table, for its check here (check_cells, one coordinate at a
// time) and for the batch kernels (unprojector_kernel.inl, each node's (x, y) pair as a
// two-lane vector): `node(n)` gives node n's value, a number or such a pair, and the sums
// are the same operations in the same order, so the kernels give the bits that were
// checked. Always inlined, here and in catmull_rom_weights: the kernels' loops vectorise
// only once the bodies are inlined into them.
template <class Node, class Scalar>
[[gnu::always_inline]] inline auto bilinear(const Node& node, std::size_t k, std::size_t stride, Scalar fx, Scalar fy) {
    const auto upper = node(k) + fx * (node(k + 1) - node(k));
    const auto lower = node(k + stride) + fx * (node(k + stride + 1) - node(k + stride));
    return upper + fy * (lower - upper);
}

// Catmull-Rom weights of the nodes at -1, 0, 1, 2 for the fraction t in [0, 1).
template <class Scalar>
[[gnu::always_inline]] inline void catmull_rom_weights(Scalar t, Scalar w[4]) {
    const Scalar half(0.5);
    w[0] = half * t * ((Scalar(2) - t) * t - Scalar(1));
    w[1] = half * ((Scalar(3) * t - Scalar(5)) * t * t + Scalar(2));
    w[2] = half * t * ((Scalar(4) - Scalar(3) * t) * t + Scalar(1));
    w[3] = half * (t - Scalar(1)) * t * t;
}

// Catmull-Rom over the 4 x 4 nodes about the cell whose top-left node is k.
template <class Node, class Scalar>
[[gnu::always_inline]] inline auto bicubic(const Node& node, std::size_t k, std::size_t stride, const Scalar wx[4],
                                           const Scalar wy[4]) {
    decltype(node(k)) sum{};  // 0
    for (std::size_t r = 0; r < 4; ++r) {
        const std::size_t row = k + r * stride - stride - 1;
        sum += wy[r] * (wx[0] * node(row) + wx[1] * node(row + 1) + wx[2] * node(row + 2) + wx[3] * node(row + 3));
    }
    return sum;
}

// The table's nodes for an image: every `step` pixels, from one node beyond the
// top-left corner to one beyond the bottom-right, so that the bicubic stencil of every
// pixel in the image lies inside.
template <class Scalar>
UnprojectionTable<Scalar> table_layout(const ImageSize& size, int nodes) {
    UnprojectionTable<Scalar> table;
    const double width = static_cast<double>(size.width), height = static_cast<double>(size.height);
    table.step = std::max(width, height) / (nodes - 1);
    // Pixel p sits at grid coordinate (p + 0.5) / step + 1: the image spans [1, 1 + W / step],
    // strictly below nodes - 2, the last start of a bicubic stencil.
    table.nodes_x = static_cast<int>(std::floor(width / table.step)) + 4;
    table.nodes_y = static_cast<int>(std::floor(height / table.step)) + 4;
    table.origin_x = table.origin_y = -0.5 - table.step;
    const std::size_t count = static_cast<std::size_t>(table.nodes_x) * static_cast<std::size_t>(table.nodes_y);
    table.u_pairs.assign(2 * count, Scalar(0));
    for (std::vector<std::uint8_t>* v : {&table.fast_ok, &table.lut_ok}) v->assign(count, 0);
    return table;
}

template <class Scalar>
Vec2 node_pixel(const UnprojectionTable<Scalar>& table, double i, double j) {
    return {table.origin_x + i * table.step, table.origin_y + j * table.step};
}

// Calls row(j) for every j in [first, end), on `threads` threads (one per core when 0).
// Each row writes only its own entries, so the table is the same for any number.
template <class Row>
void for_each_row(int first, int end, int threads, Row&& row) {
    if (end <= first) return;
    parallel_chunks(static_cast<std::size_t>(end - first), worker_count(threads), 1, [&](std::size_t begin, std::size_t stop) {
        for (std::size_t j = begin; j < stop; ++j) row(first + static_cast<int>(j));
    });
}

// Every node's exact u, by the full solver; NaN where the pixel has no ray.
template <class Model>
void solve_nodes(const Camera& camera, const typename Model::Parameters& lens, int threads,
                 UnprojectionTable<double>& table) {
    for_each_row(0, table.nodes_y, threads, [&](int j) {
        for (int i = 0; i < table.nodes_x; ++i) {
            const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(table.nodes_x) + static_cast<std::size_t>(i);
            Vec2 u;
            const bool solved = solve_undistorted<Model>(lens, camera.intrinsics.normalized_from_pixel(node_pixel(table, i, j)), u);
            table.u_pairs[2 * k] = solved ? u.x() : std::numeric_limits<double>::quiet_NaN();
            table.u_pairs[2 * k + 1] = solved ? u.y() : std::numeric_limits<double>::quiet_NaN();
        }
    });
}

// How far from `pixel` the estimate u reprojects, in px; infinity outside the domain.
template <class Model>
double reprojection_px(const Camera& camera, const typename Model::Parameters& lens, const Vec2& u, const Vec2& pixel) {
    Vec2 m;
    if (!Model::distort(lens, u, m)) return std::numeric_limits<double>::infinity();
    const double error = (camera.intrinsics.pixel_from_normalized(m) - pixel).norm();
    return std::isnan(error) ? std::numeric_limits<double>::infinity() : error;
}

// The fast and lut estimates' reprojection errors at a point (fractions fx, fy) of the
// cell whose top-left node is k.
template <class Model>
std::pair<double, double> estimate_errors(const Camera& camera, const typename Model::Parameters& lens,
                                          const UnprojectionTable<double>& table, int i, int j, double fx, double fy) {
    const int k = j * table.nodes_x + i;
    const Vec2 pixel = node_pixel(table, i + fx, j + fy);
    const Vec2 m = camera.intrinsics.normalized_from_pixel(pixel);
    const std::size_t cell = static_cast<std::size_t>(k), stride = static_cast<std::size_t>(table.nodes_x);
    const auto node_x = [&table](std::size_t n) { return table.u_pairs[2 * n]; };
    const auto node_y = [&table](std::size_t n) { return table.u_pairs[2 * n + 1]; };
    const Vec2 start(bilinear(node_x, cell, stride, fx, fy), bilinear(node_y, cell, stride, fx, fy));
    Vec2 m_start;
    Eigen::Matrix2d d_m_d_u;
    Model::distort(lens, start, m_start, &d_m_d_u);
    const Vec2 fast = start - newton_step(d_m_d_u, Vec2(m_start - m));
    double wx[4], wy[4];
    catmull_rom_weights(fx, wx);
    catmull_rom_weights(fy, wy);
    const Vec2 lut(bicubic(node_x, cell, stride, wx, wy), bicubic(node_y, cell, stride, wx, wy));
    return {reprojection_px<Model>(camera, lens, fast, pixel), reprojection_px<Model>(camera, lens, lut, pixel)};
}

// Marks the cells where fast and lut stay within the budget: checked at the cell's
// centre (where bilinear interpolation errs most) and at its four quarter points (near
// where bicubic does). Near a fold the inverse steepens and they do not; such cells go
// to the full solver.
template <class Model>
void check_cells(const Camera& camera, const typename Model::Parameters& lens, double budget_px, int threads,
                 UnprojectionTable<double>& table) {
    constexpr double kCheckpoints[5][2] = {{0.5, 0.5}, {0.25, 0.25}, {0.75, 0.25}, {0.25, 0.75}, {0.75, 0.75}};
    // Only cells whose bicubic stencil fits are ever used (locate_in_table).
    for_each_row(1, table.nodes_y - 2, threads, [&](int j) {
        for (int i = 1; i + 2 < table.nodes_x; ++i) {
            double fast = 0, lut = 0;
            for (const auto& [fx, fy] : kCheckpoints) {
                const auto [fast_error, lut_error] = estimate_errors<Model>(camera, lens, table, i, j, fx, fy);
                fast = std::max(fast, fast_error);
                lut = std::max(lut, lut_error);
            }
            const std::size_t k = static_cast<std::size_t>(j * table.nodes_x + i);
            table.fast_ok[k] = fast <= budget_px ? 1 : 0;
            table.lut_ok[k] = lut <= budget_px ? 1 : 0;
        }
    });
}

template <class Scalar>
UnprojectionTable<Scalar> in_scalar(const UnprojectionTable<double>& table) {
    UnprojectionTable<Scalar> out{table.origin_x, table.origin_y, table.step, table.nodes_x, table.nodes_y, {}, {}, {}};
    out.u_pairs.assign(table.u_pairs.begin(), table.u_pairs.end());
    out.fast_ok = table.fast_ok;
    out.lut_ok = table.lut_ok;
    return out;
}

template <class Model, class Scalar>
UnprojectionTable<Scalar> build_table(const Camera& camera, const typename Model::Parameters& lens,
                                      const UnprojectorOptions& options) {
    UnprojectionTable<double> table = table_layout<double>(camera.size, options.table_nodes);
    solve_nodes<Model>(camera, lens, options.threads, table);
    check_cells<Model>(camera, lens, options.approximation_budget_px, options.threads, table);
    return in_scalar<Scalar>(table);
}

}  // namespace libcam::detail
