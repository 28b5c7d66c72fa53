#pragma once
// The old names of the graphics camera, kept for one release: it is LookAtCamera
// (libcam/graphics/look_at_camera.hpp), converted by libcam/convert/look_at_convert.hpp
// ("FOV" also names a lens model and the angles a camera sees, which this is not).

#include "libcam/convert/look_at_convert.hpp"

namespace libcam {

using FovCamera [[deprecated("FovCamera is LookAtCamera (libcam/graphics/look_at_camera.hpp)")]] = LookAtCamera;

[[deprecated("to_fov_camera is to_look_at_camera (libcam/convert/look_at_convert.hpp)")]] inline LookAtCamera
to_fov_camera(const Camera& camera, FovAxis axis) {
    return to_look_at_camera(camera, axis);
}

}  // namespace libcam
