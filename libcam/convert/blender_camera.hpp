#pragma once
// Blender's cameras (Cycles) as libcam cameras: the perspective camera and the panoramic
// FISHEYE_EQUIDISTANT, FISHEYE_EQUISOLID, FISHEYE_LENS_POLYNOMIAL and EQUIRECTANGULAR,
// with Blender's own
// parameters (lens and sensor in millimetres, sensor fit, shift, the fisheye's field of
// view and lens, the equirectangular latitude and longitude ranges), as Cycles maps a
// pixel to a ray (intern/cycles/kernel/camera/projection.h, scene/camera.cpp and
// blender/camera.cpp in Blender's source). Each is exactly a libcam model:
//
//   perspective          PINHOLE
//   FISHEYE_EQUIDISTANT  FISHEYE with zero coefficients: fx = W / fov, fy = H / fov
//   FISHEYE_EQUISOLID    EQUISOLID: fx = lens W / sensor width, fy = lens H / sensor height
//   FISHEYE_LENS_POLYNOMIAL  FISHEYE_LENS_POLYNOMIAL (k0..k4): fx = fy = W / sensor width,
//                        pixels per millimetre of the fitted sensor, so that m is in mm
//   EQUIRECTANGULAR      LONLAT: fx = W / (lon max - lon min), fy = H / (lat max - lat min)
//
// Pixels: Cycles samples pixel (i, j) at its centre (i + 0.5, j + 0.5), counting rows
// from the bottom; libcam (as OpenCV) puts pixel centres at integers, rows from the top.
// A panoramic camera's shift moves the image by shift_x W and shift_y H; a perspective
// camera's by shift times the fitted side (W for a horizontal fit), each axis's measured
// in its own pixels: shift_x fx S / lens and shift_y fy S / lens, S the fitted sensor size.
//
// Pixel aspect (render.pixel_aspect_x, pixel_aspect_y; Blender wants both >= 1): a
// perspective camera's fy = fx pixel_aspect_x / pixel_aspect_y (the fitted side keeps
// lens W / S, or lens H / S). The panoramic cameras here take square pixels.
//
// Blender's fisheyes render only inside the image circle theta <= fov / 2 (black
// outside; for FISHEYE_LENS_POLYNOMIAL, |theta| <= fov / 2); the libcam camera images the
// lens model's whole domain.
//
// Axes: Blender's camera looks along its -Z with Y up; libcam's (OpenCV's) along +z with
// y down: p_libcam = (X, -Y, -Z) of Blender's camera frame.

#include <array>
#include <numbers>

#include "libcam/camera/camera.hpp"
#include "libcam/geometry/image_size.hpp"

namespace libcam {

enum class BlenderCameraType { Perspective, FisheyeEquidistant, FisheyeEquisolid, FisheyeLensPolynomial, Equirectangular };

// Blender's sensor_fit: which side of the image the sensor size measures.
enum class SensorFit { Auto, Horizontal, Vertical };

// A Blender camera's settings (bpy names; Blender 3.4 keeps the panoramic ones on
// camera.data.cycles). Angles in radians, lengths in millimetres. Defaults: Blender's.
struct BlenderCamera {
    BlenderCameraType type = BlenderCameraType::Perspective;
    ImageSize size{1920, 1080};  // render resolution times its percentage
    double lens_mm = 50.0;       // perspective focal length
    double sensor_width_mm = 36.0;
    double sensor_height_mm = 24.0;
    SensorFit sensor_fit = SensorFit::Auto;
    double pixel_aspect_x = 1.0;  // the render's pixel aspect: a perspective camera's fy / fx
    double pixel_aspect_y = 1.0;  //   = pixel_aspect_x / pixel_aspect_y
    double shift_x = 0.0;
    double shift_y = 0.0;
    double fisheye_fov = std::numbers::pi;  // FISHEYE_EQUIDISTANT and FISHEYE_EQUISOLID
    double fisheye_lens_mm = 10.5;          // FISHEYE_EQUISOLID
    // FISHEYE_LENS_POLYNOMIAL's fisheye_polynomial_k0..k4 (theta in radians of the radius in
    // mm); Blender's defaults fit its default 50 mm perspective camera.
    std::array<double, 5> fisheye_polynomial{-1.1735143712967577e-05, -0.019988736953434998, -3.3525322965709175e-06,
                                             3.099275275886036e-06, -2.6064646454854524e-08};
    double latitude_min = -std::numbers::pi / 2, latitude_max = std::numbers::pi / 2;  // EQUIRECTANGULAR
    double longitude_min = -std::numbers::pi, longitude_max = std::numbers::pi;
};

// The libcam camera (intrinsics and lens; identity pose) that maps pixels to rays as
// Cycles does (pixel aspect 1 for the panoramic cameras). Throws InvalidArgument naming a
// setting that is out of range (a lens or sensor size <= 0, an empty angle range, a field
// of view outside (0, 2 pi]).
Camera camera_from_blender(const BlenderCamera& blender);

// The Blender camera that draws `camera`'s intrinsics and lens (its pose is not a
// setting of Blender's camera data): the inverse of camera_from_blender, with the sensor
// fitted horizontally. Perspective: PINHOLE without skew, a 36 mm sensor, and for
// fx != fy the pixel aspect (the larger of the two 1).
// FISHEYE_EQUIDISTANT: FISHEYE with zero coefficients and W / fx = H / fy.
// FISHEYE_EQUISOLID: EQUISOLID with fx = fy, a 36 mm sensor and the field of view of its
// whole domain (2 pi). FISHEYE_LENS_POLYNOMIAL: fx = fy, the sensor W / fx mm wide,
// fisheye_fov twice the largest angle the polynomial images. EQUIRECTANGULAR: LONLAT.
// Throws InvalidArgument saying why for a camera Blender cannot draw (another model,
// non-square pixels, skew); fx = fy means within a relative 1e-9.
BlenderCamera blender_from_camera(const Camera& camera);

}  // namespace libcam
