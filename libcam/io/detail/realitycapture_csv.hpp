#pragma once
// RealityCapture's (RealityScan's) CSV of cameras, "Internal/External camera parameters"
// (Alignment > Export > Registration): one line per image under a header naming the
// columns,
//
//   #name,x,y,alt,heading,pitch,roll,f,px,py,k1,k2,k3,k4,t1,t2
//   IMG_0001.JPG,0.348,-0.457,1.875,-26.486,87.227,14.715,16.808,5.65e-003,0,-0.237,...
//
// (an optional "#cameras N" line before the header; RealityCapture writes exponents with
// three digits). The columns are read by the header's names, so a customised template's
// order is read too; name, x, y, alt, heading, pitch, roll and f are required, the others
// are 0 when absent, and a column libcam does not know is refused rather than dropped.
//
// The intrinsics are the XMP sidecar's (realitycapture_format.hpp, one implementation):
// f is the 35 mm-equivalent focal length over the image's longer side S (fx = fy =
// f S / 36), px the principal point's offset from the image's centre over S (cx = W / 2 -
// 0.5 + px S), k1 k2 k3 k4 Brown's radial and t1 t2 its tangential terms with OpenCV's p1 =
// t2, p2 = t1 (BROWN_K4, or OPENCV5 or simpler when k4 is 0). The CSV names no distortion model: its
// coefficients are read as Brown's (RealityCapture's default, brown3).
//
// py is refused unless 0: the open readers of this file disagree on its sign (the
// Blender add-on Camera Projection Painter reads it as minus the XMP's PrincipalPointV,
// brush's RealityCapture loader as PrincipalPointV itself), and RealityCapture's
// documentation does not say; the XMP sidecars hold the same calibration unambiguously.
//
// The pose: (x, y, alt) is the camera's centre in RealityCapture's world (x east, y
// north, z up: its local or projected coordinate system, in that system's unit), and
// heading, pitch, roll are degrees. The world-to-camera rotation (OpenCV's camera axes)
// is R = (Rz(-heading) Rx(pitch) Ry(roll) diag(1, -1, -1))^T with the right-handed
// rotations about the world's axes: heading 0, pitch 0, roll 0 looks straight down with
// the image's top towards +y (north). This is RealityCapture's own formula (its
// EulerRotation, posted by its support in the knowledge base "Registration export and
// camera orientations") and nerfstudio's realitycapture_utils.py, and gives the XMP's
// Rotation for the same image (tests/io/test_realitycapture_csv.cpp: RealityCapture's
// numbers from its forum).
//
// A geographic export (x and y longitude and latitude in degrees) cannot be placed in a
// metric world: a file of several cameras whose x and y are in those ranges and lie within
// 0.01 (but not 0) of each other while |alt| reaches 1000 times that is refused as one. A
// file of one such camera cannot be told from a local one and is read as metric.
//
// The image size is not in the file: the reader takes it from ReadOptions::size
// (--image-size WxH), the same for every image, and refuses the file without it. Read only.

#include <string_view>
#include <vector>

#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> read_realitycapture_csv(std::string_view text, const ReadContext& context);

// The world-to-camera rotation of heading, pitch and roll in degrees (the header's formula).
Mat3 realitycapture_rotation(double heading_deg, double pitch_deg, double roll_deg);

}  // namespace libcam
