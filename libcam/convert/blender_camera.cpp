#include "libcam/convert/blender_camera.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "libcam/error.hpp"

namespace libcam {

namespace {

void require_positive(const char* field, double value) {
    require_finite(field, value);
    if (!(value > 0)) throw InvalidArgument(std::string(field) + ": must be > 0, got " + format_number(value));
}

// Which side the sensor size measures (blender/camera.cpp): AUTO fits the longer side
// but measures it with sensor_width either way.
struct Fit {
    bool horizontal;
    double sensor_mm;
};

Fit fit_of(const BlenderCamera& blender) {
    const auto width = static_cast<double>(blender.size.width), height = static_cast<double>(blender.size.height);
    switch (blender.sensor_fit) {
        case SensorFit::Auto: return {width > height, blender.sensor_width_mm};
        case SensorFit::Horizontal: return {true, blender.sensor_width_mm};
        case SensorFit::Vertical: return {false, blender.sensor_height_mm};
    }
    throw InvalidArgument("sensor_fit: unknown value");
}

// Pixels per millimetre of the sensor fitted to the image (the same across and down:
// square pixels).
double pixels_per_mm(const BlenderCamera& blender) {
    const Fit fit = fit_of(blender);
    require_positive(fit.horizontal ? "sensor_width" : "sensor_height", fit.sensor_mm);
    return static_cast<double>(fit.horizontal ? blender.size.width : blender.size.height) / fit.sensor_mm;
}

// A panoramic camera's K, its principal point where the optical axis falls: at Cycles'
// (U, V) = (axis_u, axis_v) (V up from the bottom edge; the image centre for the
// fisheyes), moved by the shift in units of the image's width and height, in libcam's
// pixels (centres at integers, rows from the top).
Intrinsics panoramic_intrinsics(const BlenderCamera& blender, double fx, double fy, double axis_u = 0.5,
                                double axis_v = 0.5) {
    const auto width = static_cast<double>(blender.size.width), height = static_cast<double>(blender.size.height);
    return {fx, fy, width * axis_u - 0.5 - blender.shift_x * width,
            height * (1 - axis_v) - 0.5 + blender.shift_y * height, 0.0};
}

void require_field_of_view(double fov) {
    require_finite("fisheye_fov", fov);
    if (!(fov > 0 && fov <= 2 * std::numbers::pi)) {
        throw InvalidArgument("fisheye_fov: must be in (0, 2 pi] radians, got " + format_number(fov));
    }
}

}  // namespace

Camera camera_from_blender(const BlenderCamera& blender) {
    blender.size.validate();
    require_finite("shift_x", blender.shift_x);
    require_finite("shift_y", blender.shift_y);
    const auto width = static_cast<double>(blender.size.width), height = static_cast<double>(blender.size.height);
    Camera camera;
    camera.size = blender.size;
    switch (blender.type) {
        case BlenderCameraType::Perspective: {
            require_positive("lens", blender.lens_mm);
            const Fit fit = fit_of(blender);
            const double f = blender.lens_mm * pixels_per_mm(blender);
            const double side = fit.horizontal ? width : height;  // the perspective shift's unit
            camera.intrinsics = {f, f, width / 2 - 0.5 - blender.shift_x * side, height / 2 - 0.5 + blender.shift_y * side,
                                 0.0};
            camera.lens = {LensType::Pinhole, {}};
            break;
        }
        case BlenderCameraType::FisheyeEquidistant:
            // theta = r fov / 2 with r = 1 at the image's edges: the ellipse inscribed in it.
            require_field_of_view(blender.fisheye_fov);
            camera.intrinsics = panoramic_intrinsics(blender, width / blender.fisheye_fov, height / blender.fisheye_fov);
            camera.lens = {LensType::Fisheye, {0.0, 0.0, 0.0, 0.0}};
            break;
        case BlenderCameraType::FisheyeEquisolid: {
            require_field_of_view(blender.fisheye_fov);
            require_positive("fisheye_lens", blender.fisheye_lens_mm);
            const double f = blender.fisheye_lens_mm * pixels_per_mm(blender);
            camera.intrinsics = panoramic_intrinsics(blender, f, f);
            camera.lens = {LensType::Equisolid, {}};
            break;
        }
        case BlenderCameraType::FisheyeLensPolynomial: {
            const std::vector<double> k(blender.fisheye_polynomial.begin(), blender.fisheye_polynomial.end());
            for (std::size_t i = 0; i < k.size(); ++i) {
                require_finite(("fisheye_polynomial_k" + std::to_string(i)).c_str(), k[i]);
            }
            if (k[1] == 0) {
                throw InvalidArgument("fisheye_polynomial_k1: must not be 0 (the angle must grow with the radius), got 0");
            }
            const double f = pixels_per_mm(blender);
            camera.intrinsics = panoramic_intrinsics(blender, f, f);
            camera.lens = {LensType::LensPolynomial, k};
            break;
        }
        case BlenderCameraType::Equirectangular: {
            const double lon_range = blender.longitude_max - blender.longitude_min;
            const double lat_range = blender.latitude_max - blender.latitude_min;
            require_positive("longitude_max - longitude_min", lon_range);
            require_positive("latitude_max - latitude_min", lat_range);
            // Longitude lon_min at the left edge, latitude lat_min at the bottom edge: the
            // axis (0, 0) lies at U = -lon_min / lon range, V = -lat_min / lat range.
            camera.intrinsics = panoramic_intrinsics(blender, width / lon_range, height / lat_range,
                                                     -blender.longitude_min / lon_range,
                                                     -blender.latitude_min / lat_range);
            camera.lens = {LensType::Lonlat, {}};
            break;
        }
    }
    camera.validate();
    return camera;
}

}  // namespace libcam
