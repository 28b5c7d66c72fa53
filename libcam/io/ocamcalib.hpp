#pragma once
// OCamCalib's inverse polynomial (invpol): the fitted approximation of the projection its
// files carry beside the model (detail/ocamcalib_format.hpp), which the toolbox's C
// world2cam evaluates instead of solving the model's polynomial. libcam's OCAMCALIB lens
// projects exactly; these say how far the file's invpol lands from that.

#include <filesystem>
#include <optional>
#include <vector>

#include "libcam/camera/camera.hpp"

namespace libcam {

struct OcamCalibInverse {
    std::vector<double> coefficients;  // lowest degree first, in the file's pixels
    // The angle it is a polynomial of: the toolbox's atan(z / |(x, y)|) in its axes
    // (z backwards: the angle from the sensor plane, -pi/2 on the axis), or py-OCamCalib's
    // angle from the optical axis.
    bool of_angle_from_axis = false;
    // The file's sensor-plane units per unit of the lens's radius r (ocamcalib.hpp): -a0
    // for the toolbox's files, a0 for py-OCamCalib's.
    double units_per_radius = 1.0;
};

// The invpol of a calib_results.txt or py-OCamCalib JSON (format detected as
// read_camera_set does); nullopt for any other format. Throws FileError as reading does.
std::optional<OcamCalibInverse> read_ocamcalib_inverse(const std::filesystem::path& path);

// The pixel the invpol gives a camera-frame point of an OCAMCALIB camera (the C world2cam).
Vec2 ocamcalib_inverse_pixel(const Camera& camera, const OcamCalibInverse& inverse, const Vec3& point);

// How far the invpol lands from each pixel it should: |invpol(ray(p)) - p| for every pixel
// p of the image (centres at integers), the largest within min(width, height) / 2 of the
// centre (cx, cy) and over the whole image, and where the largest is.
struct InverseMiss {
    double within_half_side = 0.0;
    double whole_image = 0.0;
    Vec2 worst_pixel = Vec2::Zero();
};
InverseMiss ocamcalib_inverse_miss(const Camera& camera, const OcamCalibInverse& inverse);

}  // namespace libcam
