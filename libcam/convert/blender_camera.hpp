#pragma once
// Blender's cameras (Cycles) as libcam cameras: the perspective camera and the panoramic
// FISHEYE_EQUIDISTANT, FISHEYE_EQUISOLID, FISHEYE_LENS_POLYNOMIAL and EQUIRECTANGULAR,
// with Blender's own parameters (lens and sensor in millimetres, sensor fit, shift, pixel
// aspect, the fisheye's field of view and lens, the equirectangular latitude and longitude
// ranges), as Cycles 3.4 maps a pixel to a ray (intern/cycles/kernel/camera/projection.h,
// scene/camera.cpp and blender/camera.cpp in Blender's source). Each is exactly a libcam
// model; which of fx, fy, cx, cy each can draw (S the fitted sensor size, W x H pixels,
// a = pixel_aspect_x / pixel_aspect_y):
//
//   perspective          PINHOLE: fx, fy, cx, cy, no skew. The fitted side's f = lens side / S,
//                        fy = a fx; cx, cy by the shift.
//   FISHEYE_EQUIDISTANT  FISHEYE with zero coefficients: fx = W / fov and fy = H / fov
//                        (theta = fov / 2 at each edge, the pixel aspect plays no part),
//                        so only W / fx = H / fy, 10 to 360 degrees; cx, cy by the shift.
//                        (Another fx, fy: FISHEYE_LENS_POLYNOMIAL with theta = r draws it.)
//   FISHEYE_EQUISOLID    EQUISOLID: fx, fy, cx, cy, no skew. fx = lens W / sensor width,
//                        fy = lens H / sensor height, where Cycles' sensor is S wide and
//                        S (H pixel_aspect_y) / (W pixel_aspect_x) high (horizontal fit;
//                        vertical: S high and S (W pixel_aspect_x) / (H pixel_aspect_y) wide),
//                        so fy = a fx as for the perspective camera: the sensor_height
//                        setting counts only as S of a vertical fit.
//   FISHEYE_LENS_POLYNOMIAL  FISHEYE_LENS_POLYNOMIAL (k0..k4): fx, fy, cx, cy, no skew, on
//                        the same sensor: fx = W / sensor width, fy = a fx, pixels per
//                        millimetre, so that m is the radius in mm.
//   EQUIRECTANGULAR      LONLAT: fx, fy, cx, cy, no skew: fx = W / (lon max - lon min),
//                        fy = H / (lat max - lat min), the axis by the ranges and the shift
//                        (the pixel aspect plays no part).
//
// Pixels: Cycles samples pixel (i, j) at its centre (i + 0.5, j + 0.5), counting rows
// from the bottom; libcam (as OpenCV) puts pixel centres at integers, rows from the top.
// A panoramic camera's shift moves the image by shift_x W and shift_y H; a perspective
// camera's by shift times the fitted side (W for a horizontal fit), each axis's measured
// in its own pixels: shift_x fx S / lens and shift_y fy S / lens.
//
// Pixel aspect (render.pixel_aspect_x, pixel_aspect_y; Blender takes 1 to 200): it shapes
// the sensor (above), never the panoramic cameras' pixel-to-(U, V) mapping, which divides
// by W and H alone.
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
    double pixel_aspect_x = 1.0;  // the render's pixel aspect: a perspective, equisolid or
    double pixel_aspect_y = 1.0;  //   lens polynomial camera's fy / fx = pixel_aspect_x / pixel_aspect_y
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
// Cycles does. Throws InvalidArgument naming a setting that is out of range (a lens or
// sensor size <= 0, an empty angle range, a fisheye field of view outside [10 degrees,
// 2 pi], a pixel aspect outside [1, 200]).
Camera camera_from_blender(const BlenderCamera& blender);

// The Blender camera that draws `camera`'s intrinsics and lens (its pose is not a
// setting of Blender's camera data): the inverse of camera_from_blender, with the sensor
// fitted horizontally and, for fx != fy, the pixel aspect (the larger of the two 1).
// Perspective: PINHOLE without skew, a 36 mm sensor (wider where the lens would be under
// Blender's 1 mm: past 173 degrees across).
// FISHEYE_EQUIDISTANT: FISHEYE with zero coefficients and W / fx = H / fy. The same lens
// with W / fx != H / fy (fields of view over the width and the height that differ) is the
// polynomial fisheye theta = r, k1 = -1 (FISHEYE_LENS_POLYNOMIAL below, with the same K),
// whose sensor follows the pixel aspect.
// FISHEYE_EQUISOLID: EQUISOLID, a 36 mm sensor (or the width that keeps the lens within
// Blender's 0.01 to 100 mm) and the field of view of its whole domain (2 pi).
// FISHEYE_LENS_POLYNOMIAL: the sensor W / fx mm wide (at least Blender's 1 mm: narrower,
// the coefficients are rescaled to a 1 mm sensor), fisheye_fov twice the largest angle
// the polynomial images. EQUIRECTANGULAR: LONLAT.
// Throws InvalidArgument saying why for a camera Blender cannot draw (another model, skew,
// fy / fx beyond the pixel aspect's 1/200 to 200); W / fx = H / fy means within a relative
// 1e-9.
BlenderCamera blender_from_camera(const Camera& camera);

}  // namespace libcam
