#include "libcam/convert/blender_camera.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "libcam/error.hpp"
#include "libcam/lens/lens_polynomial.hpp"

// Every switch over LensType here names every model, with no default: a new model stops
// the build until someone decides what this file does with it.
#pragma GCC diagnostic error "-Wswitch"

namespace libcam {

namespace {

// Blender's default sensor width, given to the cameras whose sensor size is free.
constexpr double kDefaultSensorWidthMm = 36.0;
// The ranges bpy clamps these settings to (silently: a value outside would be drawn as
// the nearest end): render.pixel_aspect_x and _y from 1 to 200, sensor_width and lens from 1 mm,
// the fisheye's fisheye_fov from 10 degrees (0.1745 rad, as Blender 3.4 states it) and its
// fisheye_lens up to 100 mm.
constexpr double kMaxPixelAspect = 200.0;
constexpr double kMinSensorMm = 1.0;
constexpr double kMinLensMm = 1.0;
constexpr double kMinFisheyeFov = 0.1745;
constexpr double kMaxFisheyeLensMm = 100.0;

void require_positive(const char* field, double value) {
    require_finite(field, value);
    if (!(value > 0)) throw InvalidArgument(std::string(field) + ": must be > 0, got " + format_number(value));
}

// Which side the sensor size measures (blender/camera.cpp): AUTO fits the longer side
// (in pixels times their aspect) but measures it with sensor_width either way.
struct Fit {
    bool horizontal;
    double sensor_mm;
};

Fit fit_of(const BlenderCamera& blender) {
    const auto width = static_cast<double>(blender.size.width), height = static_cast<double>(blender.size.height);
    switch (blender.sensor_fit) {
        case SensorFit::Auto:
            return {width * blender.pixel_aspect_x > height * blender.pixel_aspect_y, blender.sensor_width_mm};
        case SensorFit::Horizontal: return {true, blender.sensor_width_mm};
        case SensorFit::Vertical: return {false, blender.sensor_height_mm};
    }
    throw InvalidArgument("sensor_fit: unknown value");
}

// Pixels per millimetre of the sensor fitted to the image, along the fitted side.
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
    if (!(fov >= kMinFisheyeFov && fov <= 2 * std::numbers::pi)) {
        throw InvalidArgument("fisheye_fov: must be in [0.1745, 2 pi] radians (Blender takes 10 degrees or more), got " +
                              format_number(fov));
    }
}

void require_pixel_aspect(const BlenderCamera& blender) {
    for (const auto& [field, value] : {std::pair{"pixel_aspect_x", blender.pixel_aspect_x},
                                       std::pair{"pixel_aspect_y", blender.pixel_aspect_y}}) {
        require_finite(field, value);
        if (!(value >= 1 && value <= kMaxPixelAspect)) {
            throw InvalidArgument(std::string(field) + ": Blender takes 1 to 200, got " + format_number(value));
        }
    }
}

// The focal lengths in pixels of a lens of `focal_mm` on Blender's fitted sensor: the fitted
// side's lens side / S, the other side's by the pixel aspect (fy / fx = pixel_aspect_x /
// pixel_aspect_y). Blender's perspective camera, and Cycles' FISHEYE_EQUISOLID and
// FISHEYE_LENS_POLYNOMIAL, whose sensor blender/camera.cpp makes S by S (H pixel_aspect_y) /
// (W pixel_aspect_x) for a horizontal fit (S (W pixel_aspect_x) / (H pixel_aspect_y) by S
// for a vertical one): their sensor_height counts only as the S of a vertical fit.
std::pair<double, double> fitted_focal_lengths(const BlenderCamera& blender, double focal_mm) {
    const double fitted = focal_mm * pixels_per_mm(blender);
    const double aspect = blender.pixel_aspect_x / blender.pixel_aspect_y;  // fy / fx
    return fit_of(blender).horizontal ? std::pair{fitted, fitted * aspect} : std::pair{fitted / aspect, fitted};
}

// The pixel aspect that gives fy / fx (the smaller of the two 1), for a camera whose
// sensor is fitted horizontally.
void set_pixel_aspect(BlenderCamera& blender, const Intrinsics& k, const char* camera) {
    blender.pixel_aspect_x = std::max(k.fy / k.fx, 1.0);
    blender.pixel_aspect_y = std::max(k.fx / k.fy, 1.0);
    if (blender.pixel_aspect_x > kMaxPixelAspect || blender.pixel_aspect_y > kMaxPixelAspect) {
        throw InvalidArgument(std::string("intrinsics: Blender draws ") + camera + " with fy / fx from 1/200 to 200 " +
                              "(its pixel aspect), got fx " + format_number(k.fx) + ", fy " + format_number(k.fy));
    }
}

void require_no_skew(const Camera& camera, const char* model) {
    if (camera.intrinsics.skew != 0.0) {
        throw InvalidArgument(std::string("intrinsics: Blender's ") + model + " has no skew, got " +
                              format_number(camera.intrinsics.skew));
    }
}

// The shift that moves a panoramic camera's axis from (axis_u, axis_v) to K's principal
// point: the inverse of panoramic_intrinsics.
void set_panoramic_shift(BlenderCamera& blender, const Intrinsics& k, double axis_u = 0.5, double axis_v = 0.5) {
    const auto width = static_cast<double>(blender.size.width), height = static_cast<double>(blender.size.height);
    blender.shift_x = (width * axis_u - 0.5 - k.cx) / width;
    blender.shift_y = (k.cy - height * (1 - axis_v) + 0.5) / height;
}

// FISHEYE_EQUISOLID's lens and sensor for fx / W = lens / sensor width: the 36 mm sensor,
// or the nearest width that keeps the lens within Blender's 0.01 to 100 mm.
void set_equisolid_lens(BlenderCamera& blender, double lens_per_sensor) {
    blender.sensor_width_mm =
        std::clamp(kDefaultSensorWidthMm, 0.01 / lens_per_sensor, kMaxFisheyeLensMm / lens_per_sensor);
    if (blender.sensor_width_mm < kMinSensorMm) {
        throw InvalidArgument("intrinsics: Blender's FISHEYE_EQUISOLID draws fx / W up to 100 (a 100 mm lens on its "
                              "narrowest, 1 mm sensor), got " + format_number(lens_per_sensor));
    }
    blender.fisheye_lens_mm = lens_per_sensor * blender.sensor_width_mm;
}

// FISHEYE_LENS_POLYNOMIAL's sensor, W / fx mm wide so that its radius in mm is libcam's m;
// narrower than Blender's 1 mm minimum, the sensor is 1 mm and the polynomial takes the
// radius in those larger millimetres: m = (W / fx) r, so k_i becomes k_i (W / fx)^i.
void set_polynomial_sensor(BlenderCamera& blender, const std::vector<double>& k, double fx_over_width) {
    blender.sensor_width_mm = 1 / fx_over_width;
    double unit = 1;  // libcam's m per Blender's mm of the radius
    if (blender.sensor_width_mm < kMinSensorMm) {
        unit = blender.sensor_width_mm / kMinSensorMm;
        blender.sensor_width_mm = kMinSensorMm;
    }
    double power = 1;
    for (std::size_t i = 0; i < k.size(); ++i, power *= unit) blender.fisheye_polynomial[i] = k[i] * power;
}

}  // namespace

BlenderCamera blender_from_camera(const Camera& camera) {
    camera.validate();
    const Intrinsics& k = camera.intrinsics;
    const auto width = static_cast<double>(camera.size.width), height = static_cast<double>(camera.size.height);
    BlenderCamera blender;
    blender.size = camera.size;
    blender.sensor_fit = SensorFit::Horizontal;
    blender.sensor_width_mm = kDefaultSensorWidthMm;
    const std::vector<double>& c = camera.lens.coefficients;
    switch (camera.lens.type) {
        case LensType::Pinhole:
            require_no_skew(camera, "perspective camera");
            blender.type = BlenderCameraType::Perspective;
            // Past 173 degrees across (fx < W / 36), a wider sensor keeps the lens at 1 mm.
            blender.sensor_width_mm = std::max(kDefaultSensorWidthMm, kMinLensMm * width / k.fx);
            blender.lens_mm = k.fx * blender.sensor_width_mm / width;
            set_pixel_aspect(blender, k, "the perspective camera");
            // A perspective shift is in units of the fitted side (the width), each axis in
            // its own pixels: W across, W fy / fx down.
            blender.shift_x = (width / 2 - 0.5 - k.cx) / width;
            blender.shift_y = (k.cy - height / 2 + 0.5) / (width * k.fy / k.fx);
            return blender;
        case LensType::Fisheye:
            if (std::any_of(c.begin(), c.end(), [](double value) { return value != 0.0; })) {
                std::string given;
                for (const double value : c) given += (given.empty() ? "" : " ") + format_number(value);
                throw InvalidArgument("lens: Blender's FISHEYE_EQUIDISTANT is FISHEYE with zero coefficients, got " + given);
            }
            require_no_skew(camera, "FISHEYE_EQUIDISTANT");
            // fisheye_to_direction spans fisheye_fov over the width and over the height alike,
            // whatever the pixel aspect: fx = W / fov and fy = H / fov, nothing else. Another
            // fx, fy is the polynomial fisheye theta = r (k1 = -1 with the same K: m = theta
            // (X, Y) / |(X, Y)| in both), whose sensor follows the pixel aspect.
            if (!(std::abs(width / k.fx - height / k.fy) <= 1e-9 * width / k.fx)) {
                Camera polynomial = camera;
                polynomial.lens = {LensType::LensPolynomial, {0.0, -1.0, 0.0, 0.0, 0.0}};
                return blender_from_camera(polynomial);
            }
            blender.type = BlenderCameraType::FisheyeEquidistant;
            blender.fisheye_fov = width / k.fx;
            require_field_of_view(blender.fisheye_fov);
            set_panoramic_shift(blender, k);
            return blender;
        case LensType::Equisolid:
            require_no_skew(camera, "FISHEYE_EQUISOLID");
            blender.type = BlenderCameraType::FisheyeEquisolid;
            set_pixel_aspect(blender, k, "FISHEYE_EQUISOLID");
            set_equisolid_lens(blender, k.fx / width);
            blender.fisheye_fov = 2 * std::numbers::pi;
            set_panoramic_shift(blender, k);
            return blender;
        case LensType::LensPolynomial: {
            require_no_skew(camera, "FISHEYE_LENS_POLYNOMIAL");
            blender.type = BlenderCameraType::FisheyeLensPolynomial;
            set_pixel_aspect(blender, k, "FISHEYE_LENS_POLYNOMIAL");
            set_polynomial_sensor(blender, c, k.fx / width);
            const double radius = LensPolynomialLens<double>::valid_radius(c);
            blender.fisheye_fov = 2 * LensPolynomialLens<double>::valid_angle(c, radius);
            set_panoramic_shift(blender, k);
            return blender;
        }
        case LensType::Lonlat: {
            require_no_skew(camera, "EQUIRECTANGULAR");
            blender.type = BlenderCameraType::Equirectangular;
            const double lon_range = width / k.fx, lat_range = height / k.fy;
            // Inverse of camera_from_blender's: cx = W axis_u - 0.5, axis_u = -lon_min / range;
            // cy = H (1 - axis_v) - 0.5, axis_v = -lat_min / range.
            blender.longitude_min = -(k.cx + 0.5) / k.fx;
            blender.longitude_max = blender.longitude_min + lon_range;
            blender.latitude_min = -(height - k.cy - 0.5) / k.fy;
            blender.latitude_max = blender.latitude_min + lat_range;
            return blender;
        }
        // Every other model is named, with no default, so that the compiler asks about a
        // new model here: does Blender draw it?
        case LensType::OpenCv4:
        case LensType::OpenCv5:
        case LensType::OpenCv8:
        case LensType::OpenCv12:
        case LensType::OpenCv14:
        case LensType::Stereographic:
        case LensType::Latlon:
        case LensType::DoubleSphere:
        case LensType::Ucm:
        case LensType::Eucm:
        case LensType::Mei:
        case LensType::Fov:
        case LensType::ThinPrismFisheye:
        case LensType::RadTanThinPrismFisheye:
        case LensType::Cahvor:
        case LensType::Cahvore:
        case LensType::SplinedStereographic:
        case LensType::Cylindrical:
        case LensType::Ptlens: break;
        case LensType::OcamCalib: break;
        case LensType::Division: break;
        case LensType::ThetaPolynomial: break;
        case LensType::FTheta: break;
        case LensType::FThetaForward: break;
        case LensType::BrownK4: break;
        case LensType::EquidistantRadial: break;
        case LensType::EquisolidRadial: break;
        case LensType::StereographicRadial: break;
    }
    throw InvalidArgument("lens: Blender has no camera for " + std::string(lens_info(camera.lens.type).name) +
                          " (it draws PINHOLE, FISHEYE with zero coefficients, EQUISOLID, "
                          "FISHEYE_LENS_POLYNOMIAL and LONLAT)");
}

Camera camera_from_blender(const BlenderCamera& blender) {
    blender.size.validate();
    require_pixel_aspect(blender);
    require_finite("shift_x", blender.shift_x);
    require_finite("shift_y", blender.shift_y);
    const auto width = static_cast<double>(blender.size.width), height = static_cast<double>(blender.size.height);
    Camera camera;
    camera.size = blender.size;
    switch (blender.type) {
        case BlenderCameraType::Perspective: {
            require_positive("lens", blender.lens_mm);
            const auto [fx, fy] = fitted_focal_lengths(blender, blender.lens_mm);
            // The shift's unit: the fitted sensor's size in each axis's own pixels.
            const double sensor_over_lens = fit_of(blender).sensor_mm / blender.lens_mm;
            camera.intrinsics = {fx, fy, width / 2 - 0.5 - blender.shift_x * fx * sensor_over_lens,
                                 height / 2 - 0.5 + blender.shift_y * fy * sensor_over_lens, 0.0};
            camera.lens = {LensType::Pinhole, {}};
            break;
        }
        case BlenderCameraType::FisheyeEquidistant:
            // theta = r fov / 2 with r = 1 at the image's edges: the ellipse inscribed in it.
            // Neither the sensor nor the pixel aspect plays a part.
            require_field_of_view(blender.fisheye_fov);
            camera.intrinsics = panoramic_intrinsics(blender, width / blender.fisheye_fov, height / blender.fisheye_fov);
            camera.lens = {LensType::Fisheye, {0.0, 0.0, 0.0, 0.0}};
            break;
        case BlenderCameraType::FisheyeEquisolid: {
            require_field_of_view(blender.fisheye_fov);
            require_positive("fisheye_lens", blender.fisheye_lens_mm);
            const auto [fx, fy] = fitted_focal_lengths(blender, blender.fisheye_lens_mm);
            camera.intrinsics = panoramic_intrinsics(blender, fx, fy);
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
            // Pixels per millimetre of the sensor: the radius in mm is libcam's m.
            const auto [fx, fy] = fitted_focal_lengths(blender, 1.0);
            camera.intrinsics = panoramic_intrinsics(blender, fx, fy);
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
