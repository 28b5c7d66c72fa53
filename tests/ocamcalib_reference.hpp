#pragma once
// OCamCalib's files against values worked out without libcam: a calib_results.txt against
// real-data/vectors/ocamcalib-computed.json (the formulas of the toolbox's C functions
// cam2world and world2cam, ocam_functions.cpp), and py-OCamCalib's JSON against
// py-OCamCalib's own cam2world, written out here. Shared by the OCamCalib tests and the
// table of real files.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "libcam/camera/camera.hpp"
#include "libcam/io/ocamcalib.hpp"

namespace libcam::test {

// The toolbox's axes (x down the rows, y along the columns, z backwards) from libcam's,
// and back (the swap is its own inverse).
inline Vec3 toolbox_axes(const Vec3& v) { return Vec3(v.y(), v.x(), -v.z()); }
inline Vec3 libcam_axes(const Vec3& v) { return Vec3(v.y(), v.x(), -v.z()); }
// A (row, column) pair as an OpenCV pixel (x, y).
inline Vec2 toolbox_pixel(const nlohmann::json& row_column) {
    return Vec2(row_column[1].get<double>(), row_column[0].get<double>());
}
inline Vec3 vec3_of(const nlohmann::json& xyz) {
    return Vec3(xyz[0].get<double>(), xyz[1].get<double>(), xyz[2].get<double>());
}

// How far libcam lands from one file's computed values: world2cam by the file's invpol
// (as the C code computes it) in pixels, cam2world's unit rays, and libcam's exact
// projection of each sample's ray back onto its pixel. An invalid ray counts as infinity.
struct OcamcalibVectorsMiss {
    double world2cam_px = 0.0;
    double cam2world = 0.0;
    double exact_px = 0.0;
    std::size_t pixels = 0;  // the sample pixels compared, and the C example's point
};

inline OcamcalibVectorsMiss ocamcalib_vectors_miss(const Camera& camera, const OcamCalibInverse& inverse,
                                                   const nlohmann::json& expected) {
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    const PreparedCamera prepared(camera);
    OcamcalibVectorsMiss miss;
    const auto worse = [](double& worst, double value) {
        worst = std::max(worst, std::isnan(value) ? std::numeric_limits<double>::infinity() : value);
    };
    // world2cam of the C example's point, by invpol as the C code does; the ray through
    // that pixel is cam2world's.
    const Vec2 c_world2cam = toolbox_pixel(expected["world2cam_100_200_m300"]);
    worse(miss.world2cam_px, (ocamcalib_inverse_pixel(camera, inverse, libcam_axes(Vec3(100, 200, -300))) - c_world2cam).norm());
    const Unprojection back = prepared.unproject(c_world2cam);
    worse(miss.cam2world, back.valid ? (toolbox_axes(back.direction.normalized()) - vec3_of(expected["cam2world_of_that"])).norm()
                                     : kInfinity);
    ++miss.pixels;
    for (const auto& sample : expected["samples"]) {
        const Vec2 pixel = toolbox_pixel(sample["pixel_row_col"]);
        const Unprojection ray = prepared.unproject(pixel);
        ++miss.pixels;
        if (!ray.valid) {
            miss.cam2world = kInfinity;
            continue;
        }
        worse(miss.cam2world, (toolbox_axes(ray.direction.normalized()) - vec3_of(sample["cam2world"])).norm());
        worse(miss.world2cam_px, (ocamcalib_inverse_pixel(camera, inverse, ray.direction) - toolbox_pixel(sample["world2cam_of_that"])).norm());
        const Projection exact = prepared.project_camera_point(ray.direction);
        worse(miss.exact_px, exact.valid ? (exact.pixel - pixel).norm() : kInfinity);
    }
    return miss;
}

// py-OCamCalib's Camera.cam2world of a pixel, from its JSON: (x, y) = (column, row) minus
// distortion_center, times the stretch matrix's inverse; z = taylor(rho); OpenCV's axes.
inline Vec3 py_ocamcalib_ray(const nlohmann::json& file, const Vec2& pixel) {
    const double c = file["stretch_matrix"][0][0], d = file["stretch_matrix"][0][1], e = file["stretch_matrix"][1][0];
    const double determinant = c - d * e;
    const double x = pixel.x() - file["distortion_center"][0].get<double>();
    const double y = pixel.y() - file["distortion_center"][1].get<double>();
    const double u = (x - d * y) / determinant, v = (-e * x + c * y) / determinant;
    const double rho = std::hypot(u, v);
    double z = 0.0;
    const auto& taylor = file["taylor_coefficient"];
    for (std::size_t i = taylor.size(); i-- > 0;) z = z * rho + taylor[i].get<double>();
    return Vec3(u, v, z).normalized();
}

// The pixels the py-OCamCalib checks use: a corner, the distortion centre and two others.
inline std::vector<Vec2> py_ocamcalib_pixels() {
    return {Vec2(0, 0), Vec2(543.9861511428039, 377.64882547339226), Vec2(900, 100), Vec2(200, 700)};
}

}  // namespace libcam::test
