#pragma once
// RealityCapture's (RealityScan's) XMP sidecar: one file per image, beside it with the
// image's name and the ending .xmp, written by its "Export > Registration > Metadata (XMP)"
// and read back as a pose and calibration prior. One rdf:Description in the namespace
// http://www.capturingreality.com/ns/xcr/1.1# (prefix "xcr"), its values as attributes or
// child elements:
//
//   xcr:Version, xcr:PosePrior, xcr:Coordinates, xcr:CalibrationPrior, ... (not needed)
//   xcr:DistortionModel   perspective, brown3, brown4, brown3t2, brown4t2 or division
//   xcr:FocalLength35mm   the focal length as if the image's longer side were 36 mm
//   xcr:Skew, xcr:AspectRatio (fy / fx)
//   xcr:PrincipalPointU, xcr:PrincipalPointV   the principal point's offset from the
//                         image's centre over the longer side
//   xcr:DistortionCoeficients (sic)  k1 k2 k3 k4 t1 t2
//   xcr:Rotation          3x3 row by row, world to camera (x_cam = R (X - Position))
//   xcr:Position          the camera's centre in the world
//
// The conventions, from RealityCapture's support article "RealityCapture XMP Camera Math"
// and the open converters that read and write these files (camorph's RealityCapture
// handler, EasyVolcap's RealityCapture export, pyalicevision's rc2sfm): with S the
// image's longer side in pixels, fx = FocalLength35mm S / 36, fy = AspectRatio fx, and
// image coordinates from -0.5 to 0.5 along the longer side, so the principal point is at
// the image's centre plus (U S, V S), the centre being (W / 2, H / 2) from the top-left
// corner: libcam's cx = W / 2 - 0.5 + U S, cy = H / 2 - 0.5 + V S. The camera looks
// along +z with y down (OpenCV's axes). Brown's terms act on (X/Z, Y/Z) as OpenCV's, with
// the tangential pair the other way round: OpenCV's p1 is RealityCapture's t2, p2 its t1
// (as Metashape's P1 P2); k4 (r^8) makes the lens BROWN_K4 (OPENCV5 or simpler without it).
//
// The image size is not in the file: the reader takes it from ReadOptions::size (the
// command line's --image-size WxH) and refuses the file without it. A skew other than 0
// (its unit is not documented) and RealityCapture's division model with a coefficient
// other than 0 (the sources above do not say in which units its k is) are refused rather
// than guessed. Read only.

#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> read_realitycapture_xmp(std::string_view text, const ReadContext& context);

// What RealityCapture's XMP and its CSV (realitycapture_csv.hpp) share, as the header above
// says: the intrinsics from the 35 mm focal length, the aspect ratio (fy / fx) and the
// principal point's offset (u, v) over the longer side; Brown's k1 k2 k3 k4 and t1 t2 as
// BROWN_K4 (p1 = t2, p2 = t1), or the simplest OpenCV model that is the same lens.
Intrinsics realitycapture_intrinsics(double focal_35mm, double aspect, double u, double v, ImageSize size);
Lens realitycapture_brown_lens(double k1, double k2, double k3, double k4, double t1, double t2);

// Whether an XML file's outline (parse_xml_outline) is an XMP packet: <x:xmpmeta> or
// <rdf:RDF> at the root.
bool claims_realitycapture_xmp(const DocumentNode& outline);

}  // namespace libcam
