#pragma once
// libcam's JSON camera file.
//
// {
//   "model": "PINHOLE",                 lens model (lens/lens_model.hpp)
//   "image_size": [W, H],
//   "K": [[fx, s, cx], [0, fy, cy], [0, 0, 1]],
//   "dist": [],                         distortion coefficients, OpenCV's order
//   "R": 3x3, "t": [3], "rvec": [3],    world -> camera (OpenCV axes)
//   "P": 3x4 = K [R | t],
//   "camera_center": [3],
//   "fov_deg": {"horizontal": h, "vertical": v, "diagonal": d},
//   "frustum": {"left", "right", "bottom", "top"}   at z = 1, y up
//   "eye", "gaze", "up": [3]            the look-at camera's as given (gaze normalised); for
//                                       another camera its centre, axis and own up
//   "fov_axis": "both",                 when written from a look-at camera
//   "fov_axes": [...], "not_fov_because": [...]
// }
//
// On input, "model", "image_size", "K", "t" and one of "R" or "rvec" are required;
// "dist" may be left out for PINHOLE. "R" and "rvec", and "P" when present, must agree
// with each other (a damaged file is refused, not guessed at). The other keys are
// derived and only read back when "fov_axis" asks for the look-at camera.
//
// The "gl" format is JSON too: {"projection": 4x4, "view": 4x4, "viewport": [0,0,W,H],
// "near", "far", "depth_range"}, row-major.

#include <optional>
#include <string>
#include <string_view>

#include "libcam/io/format_table.hpp"

namespace libcam {

std::string format_json(const Camera& camera, const std::optional<LookAtCamera>& look_at_camera);
std::string format_gl_json(const GlCamera& gl, const ImageSize& size);

// Parses libcam JSON or gl JSON (chosen by the presence of "projection").
CameraFile parse_json_camera(std::string_view text, const std::string& source);

class Field;
// A camera inside another JSON document: its own keys alone ("model", "image_size", "K",
// "dist", "R", "t"; no derived key), on one line, every number to the last bit; and the
// camera read back from such an object (as parse_json_camera reads the same keys, the
// messages naming the object's field).
std::string format_json_camera_object(const Camera& camera);
Camera read_json_camera_object(const Field& object);

}  // namespace libcam
