"""libcam: graphics cameras and calibrated cameras, exact both ways.

    import libcam
    cam = libcam.read("calibration.yaml")          # OpenCV, mrcal, Kalibr, COLMAP, NeRF...
    pixels, valid = cam.project(points)            # (..., 3) -> (..., 2), NaN where invalid
    rays, valid = cam.unproject(pixels)            # exact: within 1e-9 px
    render = libcam.from_fov(60, (1920, 1080), axis="horizontal", eye=(0, 0, 5), target=(0, 0, 0))

Conventions are OpenCV's: X_cam = R X_world + t, camera axes x right, y down, z forward,
pixel (0, 0) the centre of the top-left pixel. Every batch call takes numpy arrays of any
leading shape, float32 or float64, releases the GIL, and returns a boolean mask beside
its result: entries the lens cannot map are NaN and False, never a silent number.
"""

from ._libcam import (
    Camera,
    Error,
    FileError,
    NotRepresentable,
    Observations,
    RectifiedPair,
    __version__,
    calibrate,
    calibrate_pair,
    disparity_to_points,
    disparity_to_range,
    fit,
    formats,
    from_fov,
    from_opencv,
    models,
    new_camera,
    projection_uncertainty,
    read,
    read_all,
    read_observations,
    rectify,
    remap_map,
    reproject,
    set_simd_target,
    simd_target,
    supported_simd_targets,
    verify,
)
from . import dataset  # libcam.dataset: `libcam dataset` in-process, or as tasks for other processes

__all__ = [
    "Camera",
    "Error",
    "FileError",
    "NotRepresentable",
    "Observations",
    "RectifiedPair",
    "__version__",
    "calibrate",
    "calibrate_pair",
    "disparity_to_points",
    "disparity_to_range",
    "fit",
    "formats",
    "from_fov",
    "from_opencv",
    "models",
    "new_camera",
    "projection_uncertainty",
    "read",
    "read_all",
    "read_observations",
    "rectify",
    "remap_map",
    "reproject",
    "set_simd_target",
    "simd_target",
    "supported_simd_targets",
    "verify",
]
