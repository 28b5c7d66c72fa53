#pragma once
// lensfun's lens database (data/db/*.xml, <lensdatabase>): lenses, not images. One lens
// at one focal length, on a sensor of one crop factor, imaging one image size, is a
// camera; ReadOptions says which (lens, focal_mm, crop_factor, size).
//
//   lensdatabase > lens (maker, model [several, some with lang=], mount, focal min max
//                  or value, type, cropfactor, aspect-ratio, center x y,
//                  calibration > distortion model focal [real-focal] k1 k2 | a b c)
//
// What lensfun's lfModifier does (libs/lensfun/modifier.cpp, mod-coord.cpp, lens.cpp at
// lensfun 0.3.95+), and so what this reader does:
//
// - The focal length: lfLens::InterpolateDistortion. The calibrated focal lengths
//   nearest below and above (two more beyond them where there are) make a cubic Hermite
//   spline of each term times its focal length (then divided by the focal length asked
//   for: the terms fall roughly as 1 / f) and of the real focal length (_lf_interpolate: the tangents are
//   the centred differences, or the one-sided difference at an end); outside the
//   calibrated range the nearest calibration is used as it is. Only the lens's first
//   distortion model counts (lensfun warns and skips entries of another model). A
//   distortion, tca or vignetting model lensfun does not know is refused: lensfun's
//   parser refuses the whole database then (database.cpp, "Bad attribute value").
// - The real focal length f_r: real-focal= where the file gives it, else focal (1 - a -
//   b - c) for ptlens and focal (1 - k1) for poly3, focal for poly5.
// - Pixels: lensfun's normalised coordinates are in units of f_r, so fx = fy =
//   f_r hypot(w, h) crop / hypot(36, 24) pixels; the centre is ((w - 1) / 2, (h - 1) / 2)
//   moved by <center x y> times min(w - 1, h - 1) / 2 (lensfun's pixels are OpenCV's,
//   the top-left pixel's centre at (0, 0)).
// - The terms are the Hugin/PanoTools polynomial r_src = r (a r^3 + b r^2 + c r + d),
//   d = 1 - a - b - c, whose r = 1 is half the shorter side of the sensor the lens was
//   calibrated on (crop factor C, aspect ratio A >= 1: h_mm = hypot(36, 24) / C /
//   hypot(A, 1) / 2). lensfun rescales them to its normalised radius, s = f_r / h_mm
//   (rescale_polynomial_coefficients): poly3 k1' = k1 s^2 / (1 - k1)^3; poly5 k1' = k1 s^2,
//   k2' = k2 s^4; ptlens a' = a s^3 / d^4, b' = b s^2 / d^3, c' = c s / d^2. Then, in
//   normalised coordinates, r_distorted = r_ideal (1 + a' r^3 + b' r^2 + c' r) (poly3:
//   1 + k1' r^2; poly5: 1 + k1' r^2 + k2' r^4). poly3 and poly5 are OpenCV's k1, k2
//   exactly (OPENCV4, no tangential terms); ptlens has odd powers of r, which no OpenCV
//   model has: it is PTLENS (a' b' c'; OPENCV4 when a and c are 0).
// - The lens type: rectilinear distorts the pinhole point (OpenCV's models); fisheye
//   (equidistant) distorts theta, which is Kannala-Brandt (FISHEYE, k1 k2; ptlens's odd
//   terms are refused there); equisolid,
//   stereographic, equirectangular and panoramic are EQUISOLID, STEREOGRAPHIC, LONLAT and
//   CYLINDRICAL, which libcam has without distortion only: such a lens is read with
//   lens_projection_only, or refused; orthographic and fisheye_thoby are refused.
//
// A lens is chosen by one of its model names (any case), else by a part of a name that
// names no other lens; several lenses of one name (calibrated on different sensors) are
// told apart by the crop factor, as lensfun's rule below does.
//
// The crop factor picks the calibration as lensfun does (GetClosestCalibrationSet): the
// image's crop factor over the calibration's must be at least 0.96 (a sensor no more than
// 4% bigger than the one calibrated), else lensfun corrects nothing and libcam refuses.

#include <optional>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> read_lensfun(std::string_view text, const ReadContext& context);

// Whether an XML file's outline (parse_xml_outline) is lensfun's: <lensdatabase>.
bool claims_lensfun(const DocumentNode& outline);

namespace detail {

// lensfun's spline of four values at t in [0, 1] between y2 and y3 (y1 or y4 absent: nullopt).
double lensfun_interpolate(std::optional<double> y1, double y2, double y3, std::optional<double> y4, double t);

}  // namespace detail

}  // namespace libcam
