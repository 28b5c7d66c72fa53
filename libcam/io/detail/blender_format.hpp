#pragma once
// Blender's cameras as files: a JSON of Blender's own camera settings (the property names
// of bpy), which libcam reads and writes, and a Python script that sets a scene's camera
// to them, which libcam writes:
//
//   {"format": "libcam Blender cameras", "cameras": [
//     {"name": "Camera", "frame": 1,                    (frame: optional)
//      "resolution_x": 1920, "resolution_y": 1080, "resolution_percentage": 100,
//      "pixel_aspect_x": 1, "pixel_aspect_y": 1,
//      "type": "PERSP" | "PANO",
//      "panorama_type": "FISHEYE_EQUIDISTANT" | "FISHEYE_EQUISOLID" | "FISHEYE_LENS_POLYNOMIAL" | "EQUIRECTANGULAR",
//      "lens": 50, "sensor_width": 36, "sensor_height": 24, "sensor_fit": "AUTO" | "HORIZONTAL" | "VERTICAL",
//      "shift_x": 0, "shift_y": 0, "clip_start": 0.1, "clip_end": 1000,
//      "fisheye_fov": ..., "fisheye_lens": ..., "fisheye_polynomial_k0": ... "fisheye_polynomial_k4": ...,
//      "latitude_min": ..., "latitude_max": ..., "longitude_min": ..., "longitude_max": ...,
//      "matrix_world": [[4 numbers], [..], [..], [0, 0, 0, 1]]}]}
//
// Lengths in millimetres, angles in radians, as bpy gives them; the panoramic settings
// only for type PANO (Blender 3.4 keeps them on camera.data.cycles, later versions on
// camera.data: the script sets whichever the running Blender has). matrix_world is the
// camera object's, rows first: Blender's camera looks along its -Z with Y up, so with
// libcam's pose (p = R X + t, OpenCV's axes) it is [R^T diag(1, -1, -1) | -R^T t].
// tools/blender/export_cameras.py writes this file from a .blend (every camera, and
// every frame of an animated one: named "Camera@12").
//
// The script (`libcam convert --to blender -o camera.py`; `blender -b scene.blend -P
// camera.py`) holds the same JSON and applies it to the scene's camera (making one if the
// scene has none): render resolution at 100%, pixel aspect, lens, sensor and an explicit
// sensor fit (never AUTO, which measures against the sensor width whatever the fit),
// shift, clip range, the panorama settings (and Cycles as the render engine, the only one
// that draws them) and the world matrix.

#include <string>
#include <string_view>
#include <vector>

#include "libcam/io/detail/document.hpp"
#include "libcam/convert/blender_camera.hpp"
#include "libcam/io/format_table.hpp"

namespace libcam {

// Reads every camera of the JSON above.
std::vector<NamedCamera> parse_blender_cameras(std::string_view text, const std::string& source);
// The JSON of one camera (clip range: options.gl_near and gl_far).
std::string format_blender_json(const Camera& camera, const WriteOptions& options);
// The Python script that sets a scene's camera to it.
std::string format_blender_script(const Camera& camera, const WriteOptions& options);

// Whether a parsed JSON file is this one.
bool claims_blender_cameras(const DocumentNode& root);

}  // namespace libcam
