#pragma once
// The old name of the graphics camera, kept for one release: it is LookAtCamera, in
// libcam/graphics/look_at_camera.hpp ("FOV" also names a lens model and the angles a
// camera sees, which this is not).

#include "libcam/convert/fov_convert.hpp"
#include "libcam/graphics/look_at_camera.hpp"

namespace libcam {

using FovCamera [[deprecated("FovCamera is LookAtCamera (libcam/graphics/look_at_camera.hpp)")]] = LookAtCamera;

[[deprecated("to_fov_camera is to_look_at_camera")]] inline LookAtCamera to_fov_camera(const Camera& camera,
                                                                                      FovAxis axis) {
    return to_look_at_camera(camera, axis);
}

}  // namespace libcam
