#pragma once
// OCamCalib's files (Scaramuzza's omnidirectional model, libcam's OCAMCALIB lens,
// lens/ocamcalib.hpp):
//
// - calib_results.txt, as the MATLAB toolbox's export_data(ocam_model) writes it: five
//   sections, each a # comment line and a line of numbers, blank lines between (LF or
//   CRLF):
//     "n a0 a1 ... a(n-1)"   pol, the DIRECT mapping (ocam_model.ss): z = pol(rho), pixels
//     "m b0 b1 ... b(m-1)"   invpol, its fitted inverse (ocam_model.invpol), used by the C world2cam
//     "xc yc"                the centre as row and column, from 0 (C convention)
//     "c d e"                the affine [c d; e 1] acting on (row, column)
//     "height width"
//   Its axes: x down the rows, y along the columns, z backwards (a0 < 0). Read into
//   libcam's: fx = fy = -a0, cx = yc, cy = xc, the lens's c d e as they are and k_i =
//   -a_i (-a0)^(i - 1). Written back the same way, with an invpol fitted as the toolbox
//   fits it (findinvpoly: rho as a polynomial of atan(z / |(x, y)|), the degree raised
//   until it misses by less than 0.01 px over the image). No pose.
// - py-OCamCalib's calibration JSON (jakarto3d/py-OCamCalib, Camera.load_parameters):
//   taylor_coefficient a0..aN in OpenCV's axes (z forward, so a0 > 0),
//   distortion_center (x, y) = (column, row), stretch_matrix [[c, d], [e, 1]] acting on
//   (x, y), inverse_poly highest degree first (rho of the angle from the axis). It stores
//   no image size: the reader takes the one given (ReadOptions::size, --image-size) and
//   refuses the file without it. Read only.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> read_ocamcalib(std::string_view text, const ReadContext& context);
std::string write_ocamcalib(const Camera& camera, const WriteOptions& options);

bool claims_py_ocamcalib(const DocumentNode& root);
std::vector<NamedCamera> read_py_ocamcalib(std::string_view text, const ReadContext& context);

// The camera of py-OCamCalib's and camodocal's (SCARAMUZZA) form: `forward` the ray's
// component along the optical axis as a polynomial of the sensor radius, lowest degree
// first (P(0) > 0); the stretch [[c, d], [e, 1]] acting on (x, y) = (column, row) about
// the centre (x, y). `where` names the file and the polynomial's field for messages.
Camera ocamcalib_camera_on_xy(std::span<const double> forward, double c, double d, double e, Vec2 centre,
                              ImageSize size, const std::string& where);

// Whether text looks like a calib_results.txt: one of the toolbox's comments ("... DIRECT
// mapping function (ocam_model.ss ...") among its first lines, or, with its comments
// gone, its five lines of numbers: a counted polynomial, another, the centre (2), the
// affine (3) and the size (2). COLMAP's cameras.txt, whose lines name a model, is neither.
bool looks_like_ocamcalib(std::string_view text);

}  // namespace libcam
