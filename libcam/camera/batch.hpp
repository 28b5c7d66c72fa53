#pragma once
// Batches of points as structure-of-arrays, for the batch paths of Projector and
// Unprojector: one array per coordinate, so that a loop over points reads and writes
// contiguous floats or doubles and the compiler can put one point in each SIMD lane.
//
// Validity travels beside the coordinates as one byte per point (1 valid, 0 not); the
// coordinates of an invalid point are 0.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "libcam/geometry/vector_math.hpp"

namespace libcam {

using ValidFlags = std::vector<std::uint8_t>;

// Pixels (OpenCV's convention, see camera.hpp) or any 2-D points.
template <class Scalar>
struct Points2 {
    std::vector<Scalar> x, y;

    std::size_t size() const { return x.size(); }
    void resize(std::size_t n) {
        x.resize(n);
        y.resize(n);
    }
};

// Camera-frame points or ray directions.
template <class Scalar>
struct Points3 {
    std::vector<Scalar> x, y, z;

    std::size_t size() const { return x.size(); }
    void resize(std::size_t n) {
        x.resize(n);
        y.resize(n);
        z.resize(n);
    }
};

// A batch from a list of Eigen points, each coordinate rounded to Scalar.
template <class Scalar>
Points2<Scalar> as_points2(const std::vector<Vec2>& points) {
    Points2<Scalar> out;
    for (const Vec2& p : points) {
        out.x.push_back(Scalar(p.x()));
        out.y.push_back(Scalar(p.y()));
    }
    return out;
}

template <class Scalar>
Points3<Scalar> as_points3(const std::vector<Vec3>& points) {
    Points3<Scalar> out;
    for (const Vec3& p : points) {
        out.x.push_back(Scalar(p.x()));
        out.y.push_back(Scalar(p.y()));
        out.z.push_back(Scalar(p.z()));
    }
    return out;
}

// How Unprojector solves distort(u) = m for the undistorted point u of a pixel. Each
// keeps the validity flag exact: a pixel outside the lens's domain is never valid.
// Models with a closed-form inverse (PINHOLE, STEREOGRAPHIC, LONLAT, LATLON) use it
// for every method.
enum class UnprojectMethod {
    Exact,  // Newton's method to rounding level, certified by its residual (<= 1e-9 px)
    Fast,   // one Newton step from the table's bilinear start, no convergence test
    Lut,    // the table alone, bicubic interpolation: no model evaluation at all
};

inline constexpr UnprojectMethod kUnprojectMethods[] = {UnprojectMethod::Exact, UnprojectMethod::Fast,
                                                       UnprojectMethod::Lut};

constexpr std::string_view method_name(UnprojectMethod method) {
    switch (method) {
        case UnprojectMethod::Exact: return "exact";
        case UnprojectMethod::Fast: return "fast";
        case UnprojectMethod::Lut: return "lut";
    }
    return "?";
}

constexpr std::optional<UnprojectMethod> method_from_name(std::string_view name) {
    for (UnprojectMethod method : kUnprojectMethods) {
        if (method_name(method) == name) return method;
    }
    return std::nullopt;
}

}  // namespace libcam
