#pragma once
// Shared test helpers: random cameras drawn the same way in every test, and
// tolerance helpers. Expected values never come from here: only inputs.

#include <Eigen/Geometry>
#include <exception>
#include <random>
#include <string>

#include "libcam/convert/look_at_convert.hpp"
#include "libcam/error.hpp"

namespace libcam::test {

// A deterministic generator per test, so failures reproduce.
inline std::mt19937_64& rng() {
    static std::mt19937_64 generator(20261121);
    return generator;
}

inline double uniform(double low, double high) { return std::uniform_real_distribution<double>(low, high)(rng()); }

inline Vec3 random_vector(double scale) { return {uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale)}; }

inline Vec3 random_unit() {
    Vec3 v;
    do v = random_vector(1.0);
    while (v.norm() < 0.1 || v.norm() > 1.0);
    return v.normalized();
}

inline FovAxis random_axis(int i) {
    constexpr FovAxis axes[] = {FovAxis::Horizontal, FovAxis::Vertical, FovAxis::Diagonal, FovAxis::Both};
    return axes[i % 4];
}

// A look-at camera with a random eye, gaze, up (at least ~6 degrees from the gaze), fov in
// [fov_low, fov_high] and the given size.
inline LookAtCamera random_look_at_camera(ImageSize size, FovAxis axis, double fov_low = 1.0, double fov_high = 179.0) {
    LookAtCamera camera;
    camera.eye = random_vector(100.0);
    camera.gaze = random_unit() * uniform(0.1, 10.0);
    do camera.up = random_unit() * uniform(0.1, 10.0);
    while (angle_between(camera.gaze, camera.up) < 0.1 || angle_between(camera.gaze, camera.up) > 3.04);
    camera.fov_deg = uniform(fov_low, fov_high);
    camera.fov_axis = axis;
    camera.size = size;
    return camera;
}

// Relative difference, scaled by the larger magnitude (or 1 near zero).
inline double relative_error(double a, double b) { return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-300}); }

// "FileError: ...", "InvalidArgument: ..." or what else happened, for matching.
template <class F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const FileError& error) {
        return std::string("FileError: ") + error.what();
    } catch (const InvalidArgument& error) {
        return std::string("InvalidArgument: ") + error.what();
    } catch (const Error& error) {
        return std::string("other libcam::Error: ") + error.what();
    } catch (const std::exception& error) {
        return std::string("not a libcam::Error: ") + error.what();
    }
    return "no exception";
}

}  // namespace libcam::test
