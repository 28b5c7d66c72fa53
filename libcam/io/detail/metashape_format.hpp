#pragma once
// Agisoft Metashape's (formerly PhotoScan's) camera XML: the document its "Export
// Cameras" writes (cameras.xml, <document version="1.5.0"> and 2.x) and the calibration
// file its "Export Calibration" writes (<calibration><projection>frame</projection>...).
//
//   document > chunk > sensors > sensor (id, label, type; resolution width height;
//              calibration class="adjusted" or "initial": f cx cy b1 b2 k1..k4 p1 p2)
//   document > chunk > components > component (id; transform: rotation, translation, scale)
//   document > chunk > cameras > camera (id, sensor_id, component_id, label; transform:
//              16 numbers, row-major, camera to chunk, or to its component)
//   document > chunk > transform (rotation, translation, scale: chunk to world)
//
// Metashape's frame camera (its manual's appendix "Camera models"): x = X/Z, y = Y/Z,
// r^2 = x^2 + y^2, x' = x (1 + K1 r^2 + K2 r^4 + K3 r^6 + K4 r^8) + P1 (r^2 + 2 x^2) +
// 2 P2 x y, y' = y (1 + ...) + P2 (r^2 + 2 y^2) + 2 P1 x y, u = w/2 + cx + x' (f + B1) +
// y' B2, v = h/2 + cy + y' f, where pixel (0, 0) is the image's top-left corner (the
// top-left pixel's centre is (0.5, 0.5)). So, in OpenCV's terms: fx = f + B1, fy = f,
// skew = B2, cx = w/2 + cx - 0.5, cy = h/2 + cy - 0.5, and OpenCV's p1 is Metashape's P2,
// its p2 Metashape's P1 (the tangential terms are swapped). Read as BROWN_K4 (brown_k4.hpp),
// or when K4 is 0 as OPENCV5 or the simplest OpenCV model that is the same lens. A fisheye sensor first maps x by atan(r)/r, which with P1 = P2 = 0 is
// Kannala-Brandt (FISHEYE, k1..k4 = K1..K4); a spherical one is LONLAT (u = w/2 + f lon,
// v = h/2 + f lat). Any other type, and tangential terms on a fisheye, are refused.
//
// Reading gives one camera per aligned camera (one with a transform), named by its label,
// its sensor's label as intrinsics_name, and its pose in the chunk's world frame; then one
// per camera not aligned, with its sensor's calibration, said to be unposed. Cameras of a
// sensor with no calibration (Metashape then guesses from EXIF) give none. A chunk without
// such cameras gives one camera per calibrated sensor, named by its label, without a pose.
// A calibration file gives one camera without a pose and without a name.
//
// PhotoScan before 1.0 (0.9's Export Cameras) wrote <collection> instead: each camera
// with its own <calibration> (width, height, fx, fy, cx, cy, skew, k1 k2 k3, p1 p2) and
// <transform> (4x4, camera to the collection's frame), and the collection's <transform>
// ([s R | t; 0 0 0 1], to the world). That calibration is Agisoft Lens's (its manual 0.4,
// "Camera model"): u = cx + x' fx + y' skew, v = cy + y' fy, x' = x (1 + K1 r^2 + K2 r^4 +
// K3 r^6) + P2 (r^2 + 2 x^2) + 2 P1 x y, y' = y (...) + P1 (r^2 + 2 y^2) + 2 P2 x y: cx, cy
// absolute, and P1, P2 in OpenCV's order (not swapped, as Metashape's later are). Agisoft's
// pixel (0, 0) is taken as the top-left pixel's corner, as its later manuals define it (the
// file does not say): cx - 0.5, cy - 0.5 in OpenCV's pixels. Read as OPENCV5 (or the
// simplest OpenCV model that is the same lens), named by each camera's label, posed as
// the document's cameras are; a camera without a <transform>, unposed.
//
// Written (format_metashape) the same way back: cameras.xml, a <document version="1.5.0">
// with one chunk, one sensor and its adjusted calibration (f = fy, b1 = fx - fy, b2 = skew,
// cx and cy from the centre as above, p1 and p2 swapped back) and one camera whose
// <transform> is camera to world; with WriteOptions::drop_pose, Export Calibration's
// <calibration> file instead. OPENCV4, OPENCV5, BROWN_K4 and PINHOLE are frame sensors, FISHEYE a
// fisheye one, LONLAT with fx = fy and no skew a spherical one; any other lens is refused.

#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

std::vector<NamedCamera> read_metashape(std::string_view text, const ReadContext& context);

std::string format_metashape(const Camera& camera, const WriteOptions& options);

// Whether an XML file's outline (parse_xml_outline) is Metashape's: <document> holding a
// <chunk>, <calibration> holding a <projection>, or PhotoScan's <collection> holding
// <cameras>.
bool claims_metashape(const DocumentNode& outline);

}  // namespace libcam
