#pragma once
// Hugin's project file (.pto, PanoTools' script format as Hugin writes it): one camera
// per image line
//
//   i w1500 h1000 f0 v60 a0.01 b-0.02 c0.005 d0 e0 g0 t0 r0 p0 y0 TrX0 TrY0 TrZ0 ... n"image.jpg"
//
// w h the image size, f the projection, v the horizontal field of view in degrees, a b c
// PanoTools' radial polynomial, d e the centre's shift in pixels (g t, shear, must be 0);
// a value "=N" is image N's. The other lines (p, m, v, c, o, #) are not cameras.
//
// PanoTools' lens correction maps the ideal image radius rho (pixels from the centre) to
// the source image's: with R = min(w, h) / 2 and r = rho / R,
//   r_src = r (a r^3 + b r^2 + c r + d_),   d_ = 1 - a - b - c,
// the centre at ((w - 1) / 2 + d, (h - 1) / 2 + e) in OpenCV's pixels (the top-left pixel's
// centre at (0, 0): measured with Hugin's pano_trafo, tests/io/test_hugin.cpp). The ideal
// radius is the projection's with the focal length the field of view gives over the width
// w: rectilinear (f0) rho = F tan(theta), F = (w / 2) / tan(v / 2); fisheye (f2 circular,
// f3 full frame) rho = F theta, F = w / v; equisolid (f21) rho = 2 F sin(theta / 2),
// F = (w / 2) / (2 sin(v / 4)); stereographic (f10) rho = 2 F tan(theta / 2), F = (w / 2) /
// (2 tan(v / 4)); equirectangular (f4) and cylindrical (f1) F = w / v.
//
// As a libcam camera: with s = F / R, fx = fy = F d_ and, in the projection's own
// coordinate (x/z for a rectilinear lens, theta for a fisheye), m = u (1 + c' |u| + b' |u|^2
// + a' |u|^3), a' = a s^3 / d_, b' = b s^2 / d_, c' = c s / d_, u the projection's own
// point (x/z for a rectilinear lens, rho / F for a fisheye): PTLENS, or OPENCV4 (k1 = b')
// when a = c = 0; for a fisheye EQUIDISTANT_RADIAL, or FISHEYE (k1 = b') when a = c = 0;
// EQUISOLID_RADIAL and STEREOGRAPHIC_RADIAL (EQUISOLID and STEREOGRAPHIC when a = b = c =
// 0). Equirectangular and cylindrical images have no coefficients in libcam: they are
// read when a = b = c = 0, else refused.
//
// The image's pose in the panorama. The world is the panorama's: origin its centre, z
// towards yaw 0 pitch 0, x towards yaw 90 (the right), y towards the nadir (the axes of an
// image with y = p = r = 0). y p r (degrees) give the camera-to-world rotation Ry(y) Rx(p)
// Rz(r), right-handed about those axes: yaw turns the image right, pitch up, roll its x
// axis down. TrX TrY TrZ (Hugin's mosaic translation, in units of the distance to the
// mosaic plane) put the camera's centre at (TrX, TrY, -TrZ). Measured with pano_trafo on
// an equirectangular panorama (tests/io/test_hugin.cpp).

#include <string_view>
#include <vector>

#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> read_hugin_pto(std::string_view text, const ReadContext& context);

}  // namespace libcam
