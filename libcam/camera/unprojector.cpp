#include "libcam/camera/unprojector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "libcam/camera/batch_kernels.hpp"
#include "libcam/camera/parallel.hpp"
#include "libcam/error.hpp"
#include "libcam/lens/undistort.hpp"

namespace libcam {

namespace {

using batch::kBlock;

// Models without a closed-form inverse, solved through their distort() (lens/undistort.hpp).
template <class Model>
concept SolvedIteratively = requires(const typename Model::Parameters& lens, const typename Model::Vec2T& u,
                                     typename Model::Vec2T& m) {
    Model::distort(lens, u, m);
    Model::ray_from_undistorted(u);
};

constexpr int kFastNewtonSteps = 1;
// From the bilinear start two steps reach rounding level on the lenses measured (issue
// 3's wide lens: 0.2 px, then 5e-5 px, then 4e-12 px); the residual check sends any
// pixel they do not bring there to the full solver.
constexpr int kExactNewtonSteps = 2;

// ---------------------------------------------------------------------------------
// Interpolation in the table, used to build it and to read it.

template <class Scalar>
Scalar bilinear(const Scalar* values, int k, int stride, Scalar fx, Scalar fy) {
    const Scalar upper = values[k] + fx * (values[k + 1] - values[k]);
    const Scalar lower = values[k + stride] + fx * (values[k + stride + 1] - values[k + stride]);
    return upper + fy * (lower - upper);
}

// Catmull-Rom weights of the nodes at -1, 0, 1, 2 for the fraction t in [0, 1).
template <class Scalar>
void catmull_rom_weights(Scalar t, Scalar w[4]) {
    const Scalar half(0.5);
    w[0] = half * t * ((Scalar(2) - t) * t - Scalar(1));
    w[1] = half * ((Scalar(3) * t - Scalar(5)) * t * t + Scalar(2));
    w[2] = half * t * ((Scalar(4) - Scalar(3) * t) * t + Scalar(1));
    w[3] = half * (t - Scalar(1)) * t * t;
}

template <class Scalar>
Scalar bicubic(const Scalar* values, int k, int stride, const Scalar wx[4], const Scalar wy[4]) {
    Scalar sum(0);
    for (int r = 0; r < 4; ++r) {
        const int row = k + (r - 1) * stride - 1;
        sum += wy[r] * (wx[0] * values[row] + wx[1] * values[row + 1] + wx[2] * values[row + 2] +
                        wx[3] * values[row + 3]);
    }
    return sum;
}

// ---------------------------------------------------------------------------------
// Per camera: the certified disc and the table (in double, by the full solver).

// The largest |m| of the image's corners.
double largest_corner_radius(const Camera& camera) {
    const double right = static_cast<double>(camera.size.width) - 0.5;
    const double bottom = static_cast<double>(camera.size.height) - 0.5;
    double largest = 0;
    for (const Vec2& corner : {Vec2(-0.5, -0.5), Vec2(right, -0.5), Vec2(-0.5, bottom), Vec2(right, bottom)}) {
        largest = std::max(largest, camera.intrinsics.normalized_from_pixel(corner).norm());
    }
    return largest;
}

// The radius R of the disc of undistorted points to certify: just inside the valid
// radius, or where that is unbounded, far enough for the radial part to reach twice the
// largest |m| in the image.
template <class Model>
double disc_to_certify(const Camera& camera, const typename Model::Parameters& lens) {
    if (std::isfinite(lens.valid_radius)) return lens.valid_radius * (1 - 1e-9);
    const double target = 2 * largest_corner_radius(camera);
    double radius = 1, slope = 0;
    for (int i = 0; i < 64 && Model::radial_distortion(lens, radius, slope) < target; ++i) radius *= 2;
    return radius;
}

// The image of the disc |u| <= radius under distort, sampled on 64 rings of 4096 points:
// the smallest |m| on its rim and the largest anywhere. nullopt where distort is not
// defined on the whole disc.
struct DiscImage {
    double rim_inner = std::numeric_limits<double>::infinity();
    double outer = 0;
    std::vector<Vec2> rim;  // the image of the circle itself, in the order of the angle
};

template <class Model>
std::optional<DiscImage> image_of_disc(const typename Model::Parameters& lens, double radius) {
    constexpr int kRings = 64, kAngles = 4096;
    DiscImage image;
    for (int ring = 1; ring <= kRings; ++ring) {
        const double r = radius * ring / kRings;
        for (int a = 0; a < kAngles; ++a) {
            const double angle = 2 * std::numbers::pi * a / kAngles;
            Vec2 m;
            if (!Model::distort(lens, Vec2(r * std::cos(angle), r * std::sin(angle)), m)) return std::nullopt;
            if (ring == kRings) {
                image.rim_inner = std::min(image.rim_inner, m.norm());
                image.rim.push_back(m);
            }
            image.outer = std::max(image.outer, m.norm());
        }
    }
    return image;
}

// Radii of normalised points that settle validity without the full solver:
//  - every m with |m| < certified has a ray in the valid domain. Why: distort is
//    continuous on a disc |u| <= R inside the domain and maps 0 to 0; the image C of
//    the circle |u| = R winds once around 0 (the model's own premise that the terms
//    beyond the radial one are small) and keeps a distance min |C| from it, so the disc
//    |m| < min |C| lies inside C, and each of its points has a preimage with |u| < R
//    (the degree of the map);
//  - no m with |m| > no_ray has one: the whole valid domain maps inside |m| <= no_ray
//    (known only for a bounded domain; infinite otherwise);
//  - no m past the rim (the image of the domain's edge, when it is star-shaped) has one.
// The radii are 0.1 % inside the sampled extremes, which covers the map between samples
// many times over. certified is 0 if no disc can be certified.
struct DomainBounds {
    double certified = 0;
    double no_ray = std::numeric_limits<double>::infinity();
    detail::DomainRim rim;
};

// The rim as its radius against its polar angle, if every ray from the centre crosses it
// once (its angle increases all the way round); empty otherwise. Sorted by angle, with
// the last sample repeated before the first and the first after the last, 2 pi apart.
detail::DomainRim rim_by_angle(const std::vector<Vec2>& rim) {
    const std::size_t n = rim.size();
    double turned = 0;
    std::size_t first = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const Vec2& a = rim[k];
        const Vec2& b = rim[(k + 1) % n];
        const double step = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));  // angle from a to b
        if (!(step > 0)) return {};
        turned += step;
        if (std::atan2(b.y(), b.x()) < std::atan2(rim[first].y(), rim[first].x())) first = (k + 1) % n;
    }
    if (std::abs(turned - 2 * std::numbers::pi) > 1e-6) return {};
    detail::DomainRim out;
    for (std::size_t k = 0; k < n; ++k) {
        const Vec2& m = rim[(first + k) % n];
        out.angle.push_back(std::atan2(m.y(), m.x()));
        out.radius.push_back(m.norm());
    }
    out.angle.insert(out.angle.begin(), out.angle.back() - 2 * std::numbers::pi);
    out.radius.insert(out.radius.begin(), out.radius.back());
    out.angle.push_back(out.angle[1] + 2 * std::numbers::pi);
    out.radius.push_back(out.radius[1]);
    return out;
}

// True when m lies past the rim by more than 0.01 % of its radius there.
bool beyond_rim(const detail::DomainRim& rim, const Vec2& m) {
    if (rim.angle.empty()) return false;
    const double angle = std::atan2(m.y(), m.x());
    const std::size_t i = static_cast<std::size_t>(std::upper_bound(rim.angle.begin(), rim.angle.end(), angle) - rim.angle.begin());
    if (i == 0 || i >= rim.angle.size()) return false;
    const double t = (angle - rim.angle[i - 1]) / (rim.angle[i] - rim.angle[i - 1]);
    const double radius = rim.radius[i - 1] + t * (rim.radius[i] - rim.radius[i - 1]);
    return m.norm() > radius * (1 + 1e-4);
}

template <class Model>
DomainBounds domain_bounds(const Camera& camera, const typename Model::Parameters& lens) {
    DomainBounds bounds;
    double radius = disc_to_certify<Model>(camera, lens);
    for (int attempt = 0; attempt < 64; ++attempt, radius *= 0.9) {
        if (const std::optional<DiscImage> image = image_of_disc<Model>(lens, radius)) {
            bounds.certified = image->rim_inner * (1 - 1e-3);
            // The disc is the whole domain only if it is the valid radius itself.
            if (attempt == 0 && std::isfinite(lens.valid_radius)) {
                bounds.no_ray = image->outer * (1 + 1e-3);
                bounds.rim = rim_by_angle(image->rim);
            }
            return bounds;
        }
    }
    return bounds;
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
    for (std::vector<Scalar>* v : {&table.u_x, &table.u_y, &table.fast_ok, &table.lut_ok}) v->assign(count, Scalar(0));
    return table;
}

template <class Scalar>
Vec2 node_pixel(const UnprojectionTable<Scalar>& table, double i, double j) {
    return {table.origin_x + i * table.step, table.origin_y + j * table.step};
}

// Every node's exact u, by the full solver; NaN where the pixel has no ray.
template <class Model>
void solve_nodes(const Camera& camera, const typename Model::Parameters& lens, UnprojectionTable<double>& table) {
    for (int j = 0, k = 0; j < table.nodes_y; ++j) {
        for (int i = 0; i < table.nodes_x; ++i, ++k) {
            Vec2 u;
            const bool solved = solve_undistorted<Model>(lens, camera.intrinsics.normalized_from_pixel(node_pixel(table, i, j)), u);
            table.u_x[static_cast<std::size_t>(k)] = solved ? u.x() : std::numeric_limits<double>::quiet_NaN();
            table.u_y[static_cast<std::size_t>(k)] = solved ? u.y() : std::numeric_limits<double>::quiet_NaN();
        }
    }
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
    const Vec2 start(bilinear(table.u_x.data(), k, table.nodes_x, fx, fy), bilinear(table.u_y.data(), k, table.nodes_x, fx, fy));
    Vec2 m_start;
    Eigen::Matrix2d d_m_d_u;
    Model::distort(lens, start, m_start, &d_m_d_u);
    const Vec2 fast = start - newton_step(d_m_d_u, Vec2(m_start - m));
    double wx[4], wy[4];
    catmull_rom_weights(fx, wx);
    catmull_rom_weights(fy, wy);
    const Vec2 lut(bicubic(table.u_x.data(), k, table.nodes_x, wx, wy), bicubic(table.u_y.data(), k, table.nodes_x, wx, wy));
    return {reprojection_px<Model>(camera, lens, fast, pixel), reprojection_px<Model>(camera, lens, lut, pixel)};
}

// Marks the cells where fast and lut stay within the budget: checked at the cell's
// centre (where bilinear interpolation errs most) and at its four quarter points (near
// where bicubic does). Near a fold the inverse steepens and they do not; such cells go
// to the full solver.
template <class Model>
void check_cells(const Camera& camera, const typename Model::Parameters& lens, double budget_px,
                 UnprojectionTable<double>& table) {
    constexpr double kCheckpoints[5][2] = {{0.5, 0.5}, {0.25, 0.25}, {0.75, 0.25}, {0.25, 0.75}, {0.75, 0.75}};
    // Only cells whose bicubic stencil fits are ever used (locate_in_table).
    for (int j = 1; j + 2 < table.nodes_y; ++j) {
        for (int i = 1; i + 2 < table.nodes_x; ++i) {
            double fast = 0, lut = 0;
            for (const auto& [fx, fy] : kCheckpoints) {
                const auto [fast_error, lut_error] = estimate_errors<Model>(camera, lens, table, i, j, fx, fy);
                fast = std::max(fast, fast_error);
                lut = std::max(lut, lut_error);
            }
            const std::size_t k = static_cast<std::size_t>(j * table.nodes_x + i);
            table.fast_ok[k] = fast <= budget_px ? 1.0 : 0.0;
            table.lut_ok[k] = lut <= budget_px ? 1.0 : 0.0;
        }
    }
}

template <class Scalar>
UnprojectionTable<Scalar> in_scalar(const UnprojectionTable<double>& table) {
    UnprojectionTable<Scalar> out{table.origin_x, table.origin_y, table.step, table.nodes_x, table.nodes_y, {}, {}, {}, {}};
    out.u_x.assign(table.u_x.begin(), table.u_x.end());
    out.u_y.assign(table.u_y.begin(), table.u_y.end());
    out.fast_ok.assign(table.fast_ok.begin(), table.fast_ok.end());
    out.lut_ok.assign(table.lut_ok.begin(), table.lut_ok.end());
    return out;
}

template <class Model, class Scalar>
UnprojectionTable<Scalar> build_table(const Camera& camera, const typename Model::Parameters& lens,
                                      const UnprojectorOptions& options) {
    UnprojectionTable<double> table = table_layout<double>(camera.size, options.table_nodes);
    solve_nodes<Model>(camera, lens, table);
    check_cells<Model>(camera, lens, options.approximation_budget_px, table);
    return in_scalar<Scalar>(table);
}

// ---------------------------------------------------------------------------------
// Per block of pixels: each step is one loop over the block's arrays. The steps that
// vectorise read the camera's constants from local copies (see batch_kernels.hpp).

template <class Scalar>
struct Block {
    std::size_t count = 0;
    Scalar pixel_x[kBlock], pixel_y[kBlock];
    Scalar m_x[kBlock], m_y[kBlock];  // K^-1 [x, y, 1]
    Scalar u_x[kBlock], u_y[kBlock];  // undistorted point
    Scalar ok[kBlock];  // 1: u (then the ray) is the answer; -1: settled, no ray; 0: for the full solver
    detail::RayOutput<Scalar> rays;           // where the block's rays and flags go
    int cell[kBlock];                             // table node at the top-left of the pixel's cell
    Scalar fraction_x[kBlock], fraction_y[kBlock];  // position within that cell
};

template <class Scalar>
struct TableView;

template <class Scalar>
struct Context {
    const Intrinsics& intrinsics;
    const TableView<Scalar>& table;
    Scalar certified_radius_squared;
    Scalar no_ray_radius_squared;
    const detail::DomainRim& rim;
    Scalar valid_radius_squared;
};

template <class Scalar>
using Vec2L = Eigen::Matrix<Lane<Scalar>, 2, 1>;
template <class Scalar>
using Vec3L = Eigen::Matrix<Lane<Scalar>, 3, 1>;

template <class Scalar>
void normalize(const Intrinsics& camera_intrinsics, Block<Scalar>& b) {
    const Intrinsics intrinsics = camera_intrinsics;
    for (std::size_t i = 0; i < b.count; ++i) {
        const Vec2L<Scalar> m = intrinsics.normalized_from_pixel(Vec2L<Scalar>(b.pixel_x[i], b.pixel_y[i]));
        b.m_x[i] = lane_value(m.x());
        b.m_y[i] = lane_value(m.y());
    }
}

enum class Interpolation { Bilinear, Bicubic };

// The table as the loops read it (copied before each loop, see above).
template <class Scalar>
struct TableView {
    const Scalar* u_x;
    const Scalar* u_y;
    const Scalar* fast_ok;  // per cell
    const Scalar* lut_ok;
    int stride;  // nodes per row
    Scalar origin_x, origin_y, inv_step;
    Scalar end_x, end_y;  // a pixel's grid coordinates must lie in [1, end) for its bicubic stencil to fit

    explicit TableView(const UnprojectionTable<Scalar>& table)
        : u_x(table.u_x.data()),
          u_y(table.u_y.data()),
          fast_ok(table.fast_ok.data()),
          lut_ok(table.lut_ok.data()),
          stride(table.nodes_x),
          origin_x(Scalar(table.origin_x)),
          origin_y(Scalar(table.origin_y)),
          inv_step(table.step > 0 ? Scalar(1 / table.step) : Scalar(0)),
          end_x(Scalar(table.nodes_x - 2)),
          end_y(Scalar(table.nodes_y - 2)) {}
};

// The table cell of each pixel: the index of its top-left node and the fractions within
// it; ok = 0 for a pixel whose stencil would leave the table (it reads a harmless cell
// inside instead, so that every read stays in bounds).
template <class Scalar>
void locate_in_table(const TableView<Scalar>& table_view, Block<Scalar>& b) {
    const TableView<Scalar> table = table_view;
    for (std::size_t i = 0; i < b.count; ++i) {
        const Scalar gx = (b.pixel_x[i] - table.origin_x) * table.inv_step;
        const Scalar gy = (b.pixel_y[i] - table.origin_y) * table.inv_step;
        const bool inside = gx >= Scalar(1) && gx < table.end_x && gy >= Scalar(1) && gy < table.end_y;
        const Scalar x = inside ? gx : Scalar(1), y = inside ? gy : Scalar(1);
        const int column = static_cast<int>(x), row = static_cast<int>(y);
        b.cell[i] = row * table.stride + column;
        b.fraction_x[i] = x - Scalar(column);
        b.fraction_y[i] = y - Scalar(row);
        b.ok[i] = batch::flag<Scalar>(inside);
    }
}

// u interpolated from the table at each located pixel; ok stays 1 only where every
// node used has a ray (a node without one is NaN and makes the sum NaN).
template <Interpolation kind, class Scalar>
void interpolate(const TableView<Scalar>& table_view, Block<Scalar>& b) {
    const TableView<Scalar> table = table_view;
    for (std::size_t i = 0; i < b.count; ++i) {
        const int k = b.cell[i];
        Scalar x, y;
        if constexpr (kind == Interpolation::Bilinear) {
            x = bilinear(table.u_x, k, table.stride, b.fraction_x[i], b.fraction_y[i]);
            y = bilinear(table.u_y, k, table.stride, b.fraction_x[i], b.fraction_y[i]);
        } else {
            Scalar wx[4], wy[4];
            catmull_rom_weights(b.fraction_x[i], wx);
            catmull_rom_weights(b.fraction_y[i], wy);
            x = bicubic(table.u_x, k, table.stride, wx, wy);
            y = bicubic(table.u_y, k, table.stride, wx, wy);
        }
        b.u_x[i] = x;
        b.u_y[i] = y;
        const bool numbers = (x == x) & (y == y);  // not NaN; & not &&: no branch in the loop
        b.ok[i] = numbers ? b.ok[i] : Scalar(0);
    }
}

template <Interpolation kind, class Scalar>
void start_from_table(const TableView<Scalar>& table, Block<Scalar>& b) {
    locate_in_table(table, b);
    interpolate<kind>(table, b);
}

// Keeps ok only in the cells where the method's estimate was checked to be within the
// budget (check_cells).
template <class Scalar>
void require_accurate_cell(const Scalar* cell_ok, Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) b.ok[i] = cell_ok[b.cell[i]] != Scalar(0) ? b.ok[i] : Scalar(0);
}

// Without the full solver, only a pixel inside the certified disc may be called valid.
template <class Scalar>
void require_certified_disc(Scalar radius_squared, Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) {
        const bool inside = b.m_x[i] * b.m_x[i] + b.m_y[i] * b.m_y[i] < radius_squared;
        b.ok[i] = inside ? b.ok[i] : Scalar(0);
    }
}

// The answer must lie inside the valid domain itself.
template <class Scalar>
void require_valid_radius(Scalar radius_squared, Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) {
        const bool inside = b.u_x[i] * b.u_x[i] + b.u_y[i] * b.u_y[i] < radius_squared;
        b.ok[i] = inside ? b.ok[i] : Scalar(0);
    }
}

template <class Model, class Scalar>
void newton_steps(const typename Model::Parameters& lens_parameters, int steps, Block<Scalar>& b) {
    const typename Model::Parameters lens = lens_parameters;
    for (int step = 0; step < steps; ++step) {
        for (std::size_t i = 0; i < b.count; ++i) {
            const Vec2L<Scalar> u(b.u_x[i], b.u_y[i]);
            Vec2L<Scalar> m_u;
            Eigen::Matrix<Lane<Scalar>, 2, 2> d_m_d_u;
            const bool in_domain = Model::distort(lens, u, m_u, &d_m_d_u);
            const Vec2L<Scalar> next = u - newton_step(d_m_d_u, Vec2L<Scalar>(m_u - Vec2L<Scalar>(b.m_x[i], b.m_y[i])));
            b.u_x[i] = lane_value(next.x());
            b.u_y[i] = lane_value(next.y());
            b.ok[i] = in_domain ? b.ok[i] : Scalar(0);
        }
    }
}

// Keeps ok only where u is inside the domain and reprojects to m within the tolerance
// the full solver accepts.
template <class Model, class Scalar>
void certify(const typename Model::Parameters& lens_parameters, Block<Scalar>& b) {
    const typename Model::Parameters lens = lens_parameters;
    for (std::size_t i = 0; i < b.count; ++i) {
        const Vec2L<Scalar> u(b.u_x[i], b.u_y[i]), m(b.m_x[i], b.m_y[i]);
        Vec2L<Scalar> m_u;
        const bool in_domain = Model::distort(lens, u, m_u);
        const bool converged = (m_u - m).norm() <= unprojection_tolerance(m.norm());
        b.ok[i] = in_domain && converged ? b.ok[i] : Scalar(0);
    }
}

// Settles as having no ray every pixel beyond the image of the whole domain.
template <class Scalar>
void reject_beyond_domain(Scalar no_ray_radius_squared, Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) {
        const bool beyond = b.m_x[i] * b.m_x[i] + b.m_y[i] * b.m_y[i] > no_ray_radius_squared;
        b.ok[i] = beyond ? Scalar(-1) : b.ok[i];
    }
}

// The full solver, in double whatever the scalar type, for every pixel not settled yet:
// its answer, or no ray. In double, so that the float methods flag exactly the pixels
// the double solver flags (a float residual test would accept pixels just past a fold).
// A pixel past the rim has no ray; it is not sent to the solver, whose failures are slow.
template <class ModelDouble, class Scalar>
void solve_remaining(const Context<Scalar>& context, const typename ModelDouble::Parameters& lens, Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) {
        if (b.ok[i] != Scalar(0)) continue;
        const Vec2 m = context.intrinsics.normalized_from_pixel(Vec2(double(b.pixel_x[i]), double(b.pixel_y[i])));
        Vec2 u;
        const bool solved = !beyond_rim(context.rim, m) && solve_undistorted<ModelDouble>(lens, m, u);
        b.u_x[i] = solved ? Scalar(u.x()) : Scalar(0);
        b.u_y[i] = solved ? Scalar(u.y()) : Scalar(0);
        b.ok[i] = batch::flag<Scalar>(solved);
    }
}

template <class Scalar>
void set_ray(Block<Scalar>& b, std::size_t i, bool ok, const Vec3L<Scalar>& ray) {
    b.rays.x[i] = ok ? lane_value(ray.x()) : Scalar(0);
    b.rays.y[i] = ok ? lane_value(ray.y()) : Scalar(0);
    b.rays.z[i] = ok ? lane_value(ray.z()) : Scalar(0);
}

template <class Model, class Scalar>
void rays_from_undistorted(Block<Scalar>& b) {
    for (std::size_t i = 0; i < b.count; ++i) {
        set_ray(b, i, b.ok[i] > Scalar(0), Model::ray_from_undistorted(Vec2L<Scalar>(b.u_x[i], b.u_y[i])));
    }
}

template <class Model, class Scalar>
void unproject_closed_form(const typename Model::Parameters& lens_parameters, Block<Scalar>& b) {
    const typename Model::Parameters lens = lens_parameters;
    for (std::size_t i = 0; i < b.count; ++i) {
        Vec3L<Scalar> ray = Vec3L<Scalar>::Zero();
        const bool ok = Model::unproject(lens, Vec2L<Scalar>(b.m_x[i], b.m_y[i]), ray);
        set_ray(b, i, ok, ray);
        b.ok[i] = batch::flag<Scalar>(ok);
    }
}

// u by `method`, with ok = 1 where that settles it (see approximate).
template <class Model, class Scalar>
void estimate(const Context<Scalar>& context, const typename Model::Parameters& lens, UnprojectMethod method,
              Block<Scalar>& b) {
    switch (method) {
        case UnprojectMethod::Lut:
            start_from_table<Interpolation::Bicubic>(context.table, b);
            require_certified_disc(context.certified_radius_squared, b);
            require_accurate_cell(context.table.lut_ok, b);
            require_valid_radius(context.valid_radius_squared, b);
            return;
        case UnprojectMethod::Fast:
            start_from_table<Interpolation::Bilinear>(context.table, b);
            require_certified_disc(context.certified_radius_squared, b);
            require_accurate_cell(context.table.fast_ok, b);
            newton_steps<Model>(lens, kFastNewtonSteps, b);
            require_valid_radius(context.valid_radius_squared, b);
            return;
        case UnprojectMethod::Exact:
            start_from_table<Interpolation::Bilinear>(context.table, b);
            require_certified_disc(context.certified_radius_squared, b);
            newton_steps<Model>(lens, kExactNewtonSteps, b);
            certify<Model>(lens, b);
            return;
    }
}

// u for every pixel by `method`, with ok = 1 where that settles it: only inside the
// certified disc, whose pixels all have a ray, so that the validity never depends on
// the approximation. Pixels beyond the domain's image are settled as having none; the
// full solver decides the others.
template <class Model, class Scalar>
void approximate(const Context<Scalar>& context, const typename Model::Parameters& lens, UnprojectMethod method,
                 Block<Scalar>& b) {
    estimate<Model>(context, lens, method, b);
    reject_beyond_domain(context.no_ray_radius_squared, b);
}

// The model in Lane<Scalar> for the vectorised steps, and in double for the full solver.
template <class Model>
struct LensPair {
    using ModelDouble = LensInScalar<Model, double>;
    typename Model::Parameters lanes;
    typename ModelDouble::Parameters full;
};

template <class Model, class Scalar>
void unproject_block(const Context<Scalar>& context, const LensPair<Model>& lens, UnprojectMethod method,
                     Block<Scalar>& b) {
    normalize(context.intrinsics, b);
    if constexpr (SolvedIteratively<Model>) {
        approximate<Model>(context, lens.lanes, method, b);
        solve_remaining<typename LensPair<Model>::ModelDouble>(context, lens.full, b);
        rays_from_undistorted<Model>(b);
    } else {
        unproject_closed_form<Model>(lens.lanes, b);
    }
}

}  // namespace

template <class Scalar>
Unprojector<Scalar>::Unprojector(const Camera& camera, UnprojectorOptions options) : camera_(camera) {
    camera_.validate();
    if (options.table_nodes < 4 || options.table_nodes > 100'000) {
        throw InvalidArgument("table_nodes: must be in [4, 100000], got " + std::to_string(options.table_nodes));
    }
    if (!(options.approximation_budget_px > 0)) {
        throw InvalidArgument("approximation_budget_px: must be > 0, got " + format_number(options.approximation_budget_px));
    }
    valid_radius_ = batch::lens_valid_radius(camera_.lens);
    visit_lens_model<double>(camera_.lens.type, [&]<class Model>() {
        if constexpr (SolvedIteratively<Model>) {
            const auto lens = batch::model_parameters<Model>(camera_.lens, valid_radius_);
            const DomainBounds bounds = domain_bounds<Model>(camera_, lens);
            certified_radius_ = bounds.certified;
            no_ray_radius_ = bounds.no_ray;
            rim_ = bounds.rim;
            table_ = build_table<Model, Scalar>(camera_, lens, options);
        }
    });
}

template <class Scalar>
template <class FillPixels>
void Unprojector<Scalar>::run(std::size_t n, UnprojectMethod method, int threads, FillPixels&& fill,
                              const detail::RayOutput<Scalar>& out) const {
    const TableView<Scalar> table(table_);
    const Context<Scalar> context{camera_.intrinsics, table, Scalar(certified_radius_ * certified_radius_),
                                  Scalar(no_ray_radius_ * no_ray_radius_), rim_, Scalar(valid_radius_ * valid_radius_)};
    visit_lens_model<Lane<Scalar>>(camera_.lens.type, [&]<class Model>() {
        const LensPair<Model> lens{batch::model_parameters<Model>(camera_.lens, valid_radius_),
                                   batch::model_parameters<LensInScalar<Model, double>>(camera_.lens, valid_radius_)};
        parallel_chunks(n, threads, kBlock, [&](std::size_t begin, std::size_t end) {
            Block<Scalar> block;
            for (std::size_t first = begin; first < end; first += kBlock) {
                block.count = std::min(kBlock, end - first);
                block.rays = out.at(first);
                fill(first, block);
                unproject_block<Model>(context, lens, method, block);
                batch::store_flags<Scalar>({block.ok, block.count}, block.rays.valid);
            }
        });
    });
}

namespace {

template <class Scalar>
detail::RayOutput<Scalar> output_into(Points3<Scalar>& directions, ValidFlags& valid) {
    return {directions.x.data(), directions.y.data(), directions.z.data(), valid.data()};
}

}  // namespace

template <class Scalar>
void Unprojector<Scalar>::unproject(const Points2<Scalar>& pixels, UnprojectMethod method, Points3<Scalar>& directions,
                                    ValidFlags& valid, int threads) const {
    const std::size_t n = pixels.size();
    batch::require_same_sizes("pixels", n, {pixels.y.size()});
    directions.resize(n);
    valid.resize(n);
    const auto copy_pixels = [&pixels](std::size_t first, Block<Scalar>& b) {
        std::copy_n(pixels.x.data() + first, b.count, b.pixel_x);
        std::copy_n(pixels.y.data() + first, b.count, b.pixel_y);
    };
    run(n, method, threads, copy_pixels, output_into(directions, valid));
}

namespace {

// Every pixel's ray through a pinhole without skew, row by row. The ray's x depends on
// the column alone and its y on the row alone, so a row is a copy and three fills, at
// the speed of writing the bytes. The numbers are those of the general path, which
// evaluates K^-1 [x, y, 1] per pixel: there the skew term adds an exact 0.
template <class Scalar>
void pinhole_image(const Intrinsics& intrinsics, const ImageSize& size, const detail::RayOutput<Scalar>& out,
                   int threads) {
    const std::size_t width = static_cast<std::size_t>(size.width);
    std::vector<Scalar> column_x(width);
    for (std::size_t x = 0; x < width; ++x) {
        column_x[x] = lane_value(intrinsics.normalized_from_pixel(Vec2L<Scalar>(Scalar(static_cast<int>(x)), Scalar(0))).x());
    }
    parallel_chunks(static_cast<std::size_t>(size.height), threads, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t row = begin; row < end; ++row) {
            const Vec2L<Scalar> start(Scalar(0), Scalar(static_cast<int>(row)));
            const Scalar row_y = lane_value(intrinsics.normalized_from_pixel(start).y());
            const detail::RayOutput<Scalar> rays = out.at(row * width);
            std::copy_n(column_x.data(), width, rays.x);
            std::fill_n(rays.y, width, row_y);
            std::fill_n(rays.z, width, Scalar(1));
            std::fill_n(rays.valid, width, std::uint8_t{1});
        }
    });
}

}  // namespace

template <class Scalar>
void Unprojector<Scalar>::unproject_image(UnprojectMethod method, Points3<Scalar>& directions, ValidFlags& valid,
                                          int threads) const {
    const std::size_t width = static_cast<std::size_t>(camera_.size.width);
    const std::size_t n = width * static_cast<std::size_t>(camera_.size.height);
    directions.resize(n);
    valid.resize(n);
    if (camera_.lens.type == LensType::Pinhole && camera_.intrinsics.skew == 0) {
        pinhole_image(camera_.intrinsics, camera_.size, output_into(directions, valid), threads);
        return;
    }
    // Pixel index k is (k % width, k / width); each block is filled row segment by row segment.
    const auto image_pixels = [width](std::size_t first, Block<Scalar>& b) {
        int x = static_cast<int>(first % width), y = static_cast<int>(first / width);
        for (std::size_t i = 0; i < b.count; x = 0, ++y) {
            const std::size_t run = std::min(b.count - i, width - static_cast<std::size_t>(x));
            for (std::size_t j = 0; j < run; ++j) {
                b.pixel_x[i + j] = Scalar(x + static_cast<int>(j));
                b.pixel_y[i + j] = Scalar(y);
            }
            i += run;
        }
    };
    run(n, method, threads, image_pixels, output_into(directions, valid));
}

template <class Scalar>
bool Unprojector<Scalar>::unproject(const Vec2T& pixel, UnprojectMethod method, Vec3T& direction) const {
    const auto one_pixel = [&pixel](std::size_t, Block<Scalar>& b) {
        b.pixel_x[0] = pixel.x();
        b.pixel_y[0] = pixel.y();
    };
    Vec3T ray;
    std::uint8_t valid = 0;
    run(1, method, 1, one_pixel, detail::RayOutput<Scalar>{&ray.x(), &ray.y(), &ray.z(), &valid});
    if (valid) direction = ray;
    return valid != 0;
}

template class Unprojector<float>;
template class Unprojector<double>;

}  // namespace libcam
