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
