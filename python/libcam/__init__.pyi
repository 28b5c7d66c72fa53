"""Type stubs for libcam: graphics cameras and calibrated cameras, exact both ways."""

import os
from typing import Any, Dict, Literal, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

from . import dataset as dataset

__version__: str

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.floating[Any]]
BoolArray = npt.NDArray[np.bool_]
Method = Literal["exact", "fast", "lut"]
Frame = Literal["camera", "world"]

class Error(ValueError):
    """A value out of range or inconsistent; the message names the field and the value."""

class FileError(Error):
    """A camera file that cannot be read, parsed or written; the message names the file and field."""

class NotRepresentable(Error):
    """A camera that the requested form cannot hold (skew in mrcal's format, a lens Blender cannot draw)."""

class ModelInfo(TypedDict):
    name: str
    coefficients: tuple[str, ...]
    coefficient_count: int | None
    sees_behind_camera: bool
    inverse: Literal["closed-form", "solved"]
    opencv: str
    mrcal: str
    colmap: str
    kalibr: str
    basalt: str

models: dict[str, ModelInfo]
"""The lens models, by name: their coefficients and their names in other libraries."""

formats: tuple[str, ...]
"""The camera file formats read and write take (format=...)."""

class Camera:
    """A calibrated camera: size, K, lens model and coefficients, pose R, t (X_cam = R X + t).

    OpenCV's conventions: x right, y down, z forward; pixel (0, 0) is the centre of the
    top-left pixel (unless made by from_fov with pixel_origin="bottom-left"). Immutable.
    """

    def __init__(
        self,
        K: ArrayLike,
        size: tuple[int, int],
        model: str = "PINHOLE",
        dist: ArrayLike | None = None,
        R: ArrayLike | None = None,
        t: ArrayLike | None = None,
        rvec: ArrayLike | None = None,
    ) -> None: ...
    def project(
        self,
        points: ArrayLike,
        frame: Frame = "world",
        threads: int = 1,
        out: tuple[FloatArray, BoolArray] | None = None,
    ) -> tuple[FloatArray, BoolArray]:
        """Pixels (..., 2) of points (..., 3) and the valid mask (...); invalid (not imaged by the lens): NaN, False.

        Points whose coordinates each lie together (a (3, N) array's .T) give pixels laid out the same way."""
    def unproject(
        self,
        pixels: ArrayLike,
        method: Method = "exact",
        frame: Frame = "camera",
        normalize: bool = False,
        threads: int = 1,
        out: tuple[FloatArray, BoolArray] | None = None,
    ) -> tuple[FloatArray, BoolArray]:
        """Ray directions (..., 3) of pixels (..., 2) and the valid mask (...); invalid (no ray): NaN, False."""
    def rays(self, pixels: ArrayLike, method: Method = "exact", threads: int = 1) -> tuple[FloatArray, BoolArray]:
        """Unit world-frame directions (..., 3) of the rays through pixels, from camera.center; and the mask."""
    def ray_image(
        self,
        method: Method = "exact",
        frame: Frame = "camera",
        normalize: bool = False,
        dtype: npt.DTypeLike = np.float64,
        threads: int = 1,
    ) -> tuple[FloatArray, BoolArray]:
        """The ray of every pixel: (height, width, 3) and the mask (height, width)."""
    @property
    def K(self) -> npt.NDArray[np.float64]:
        """The intrinsic matrix, 3x3."""
    @property
    def dist(self) -> npt.NDArray[np.float64]:
        """The lens's coefficients, in the model's order."""
    @property
    def model(self) -> str:
        """The lens model's name (a key of libcam.models)."""
    @property
    def size(self) -> tuple[int, int]:
        """(width, height) in pixels."""
    @property
    def R(self) -> npt.NDArray[np.float64]:
        """World to camera rotation, 3x3."""
    @property
    def t(self) -> npt.NDArray[np.float64]:
        """World to camera translation."""
    @property
    def rvec(self) -> npt.NDArray[np.float64]:
        """R as a Rodrigues vector."""
    @property
    def center(self) -> npt.NDArray[np.float64]:
        """The camera centre in the world, -R^T t."""
    @property
    def P(self) -> npt.NDArray[np.float64]:
        """K [R | t], 3x4."""
    @property
    def pixel_origin(self) -> Literal["top-left", "bottom-left"]:
        """The pixel convention of every pixel this camera takes and gives."""
    @property
    def fov(self) -> dict[str, float]:
        """Full fields of view in degrees: {'horizontal', 'vertical', 'diagonal'}."""
    @property
    def valid_angle(self) -> float:
        """The largest angle from the optical axis the lens images, in degrees."""
    def to_gl(self, near: float, far: float, depth_range: Literal["-1..1", "0..1"] = "-1..1") -> dict[str, Any]:
        """OpenGL's projection and view matrices (row-major) and viewport, for a PINHOLE camera."""
    def to_blender(self) -> dict[str, Any]:
        """Blender's camera settings; NotRepresentable for a lens Blender cannot draw."""
    def write(self, path: str, format: str | None = None) -> None:
        """Writes the camera file atomically; format by name (libcam.formats) or by extension."""
    def format(self, format: str) -> str:
        """The camera file's text in a format."""
    def resized(self, size: tuple[int, int]) -> Camera:
        """The camera of the image resized to (width, height)."""
    def binned(self, factor: int) -> Camera:
        """The camera of the image binned by factor x factor pixel blocks."""

def read(path: str, camera: str | None = None, format: str | None = None, size: tuple[int, int] | None = None) -> Camera:
    """One camera of a camera file (by name or position; the first by default)."""

def read_all(path: str, format: str | None = None, size: tuple[int, int] | None = None) -> dict[str, Camera]:
    """Every camera of a file, {name: Camera}, in the file's order."""

class Observations:
    """The observations a calibration or reconstruction file holds, in the file's own pixels."""
    @property
    def tool(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def pixel_offset(self) -> tuple[float, float]: ...
    @property
    def cameras(self) -> list[tuple[str, Camera]]: ...
    @property
    def views(self) -> list[dict[str, Any]]: ...
    @property
    def points(self) -> FloatArray: ...
    @property
    def point_ids(self) -> npt.NDArray[np.int64]: ...
    @property
    def view(self) -> npt.NDArray[np.int64]: ...
    @property
    def point(self) -> npt.NDArray[np.int64]: ...
    @property
    def pixel(self) -> FloatArray: ...
    @property
    def weight(self) -> FloatArray: ...
    @property
    def inlier(self) -> BoolArray: ...
    @property
    def reported(self) -> dict[str, float]: ...
    def __len__(self) -> int: ...

def read_observations(path: str, camera_file: str = "", size: tuple[int, int] | None = None) -> Observations:
    """The observations of OpenCV's calibration output, mrcal's optimization_inputs, a COLMAP model, OpenSfM, OpenMVG,
    AliceVision, VisualSfM or Bundler (size: their image size, which those two files lack), or a table."""

def calibrate(
    views: Sequence[Union[str, "os.PathLike[str]", npt.ArrayLike, Tuple[Sequence[int], npt.ArrayLike]]],
    board: str,
    image_size: Optional[Tuple[int, int]] = None,
    model: str = "auto",
    folds: int = 5,
    margin: float = 0.05,
    opencv_flags: Optional[str] = None,
    corners: str = "libcam",
    keep_outliers: bool = False,
    at: Sequence[Tuple[float, float]] = (),
    threads: int = 0,
) -> Dict[str, Any]:
    """A calibration from board images or the corners found in them: calibrate --json's dict,
    numpy arrays for chosen['K'], chosen['dist'], each view's rvec and tvec, and rvecs, tvecs (n, 3)."""
    ...

def calibrate_pair(
    left: Sequence[Union[str, "os.PathLike[str]", npt.ArrayLike, Tuple[Sequence[int], npt.ArrayLike]]],
    right: Sequence[Union[str, "os.PathLike[str]", npt.ArrayLike, Tuple[Sequence[int], npt.ArrayLike]]],
    board: str,
    image_size: Optional[Tuple[int, int]] = None,
    model: str = "auto",
    folds: int = 5,
    margin: float = 0.05,
    opencv_flags: Optional[str] = None,
    corners: str = "libcam",
    keep_outliers: bool = False,
    at: Sequence[Tuple[float, float]] = (),
    threads: int = 0,
) -> Dict[str, Any]:
    """A stereo pair from both cameras' views of the same boards: calibrate --left --right --json's
    dict, numpy arrays for R, T, each camera's K and dist and each view's board pose, each camera's
    projection uncertainty in the pair's solve at `at`, and left_camera, right_camera (Camera)."""
    ...

def projection_uncertainty(
    observations: Observations, pixels: Any, distance: float = ..., camera: Optional[int] = None
) -> dict[str, Any]: ...
def reproject(observations: Observations, threads: int = 0) -> dict[str, Any]:
    """Every residual (projected - observed) as arrays, the statistics, and the file's own numbers recomputed."""

def from_opencv(
    K: ArrayLike,
    dist: ArrayLike | None,
    size: tuple[int, int],
    rvec: ArrayLike | None = None,
    tvec: ArrayLike | None = None,
    model: str | None = None,
) -> Camera:
    """The camera of cv2's K, dist (4, 5, 8, 12 or 14 coefficients) and optional rvec, tvec."""

def from_fov(
    fov_deg: float,
    size: tuple[int, int],
    axis: Literal["horizontal", "vertical", "diagonal", "both"] = "both",
    eye: ArrayLike = (0, 0, 0),
    target: ArrayLike | None = None,
    gaze: ArrayLike | None = None,
    up: ArrayLike = (0, 1, 0),
    pixel_origin: Literal["top-left", "bottom-left"] = "top-left",
) -> Camera:
    """The graphics (look-at) camera as a PINHOLE camera."""

def simd_target() -> Literal["sse2", "avx2", "avx512"]:
    """The instruction set the batch calls run on (the best this CPU has by default)."""

def supported_simd_targets() -> list[str]:
    """The instruction sets this build has and this CPU runs, 'sse2' first."""

def set_simd_target(name: Literal["sse2", "avx2", "avx512"] | None) -> None:
    """Forces the instruction set of later batch calls; None: back to the default."""

class CheckStats(TypedDict):
    count: int
    median_px: float
    p99_px: float
    max_px: float
    rms_px: float

class VerifyCheck(TypedDict):
    name: str
    library: str
    tolerance_px: float | None
    skipped_because: str | None
    note: str
    stats: CheckStats
    pass_: bool

def verify(
    camera: Camera, grid: tuple[int, int] = (200, 150), depths: Sequence[float] = (0.5, 2.0, 10.0, 1000.0), threads: int = 0
) -> dict[str, Any]:
    """The camera checked against OpenCV and mrcal over a grid of pixels: {'pass', 'checks', ...}."""

def fit(
    camera: Camera,
    tolerance: float = 1.0,
    radius: float | None = None,
    center: tuple[float, float] | None = None,
    roi: tuple[float, float, float, float] | None = None,
    max_angle: float | None = None,
    models: Sequence[str] | None = None,
    depths: Sequence[float] = (),
    motion: Literal["none", "rotation", "rotation+shift"] = "none",
) -> dict[str, Any]:
    """The simplest lens model within tolerance pixels over a scene: {'chosen', 'candidates', ...}."""

def new_camera(
    source: Camera,
    model: Literal["PINHOLE", "LONLAT", "CYLINDRICAL"] = "PINHOLE",
    keep: Literal["valid", "all"] | None = None,
    fov: float | None = None,
    fov_axis: Literal["horizontal", "vertical", "diagonal"] = "horizontal",
    size: tuple[int, int] | None = None,
    rotation: ArrayLike | None = None,
    threads: int = 1,
) -> tuple[Camera, str]:
    """The camera to undistort the source's images into, and why it was chosen."""

def remap_map(
    target: Camera,
    source: Camera,
    method: Method = "exact",
    rotation: ArrayLike | None = None,
    dtype: npt.DTypeLike = np.float32,
    threads: int = 1,
) -> tuple[FloatArray, BoolArray]:
    """(height, width, 2) source coordinates for cv2.remap, NaN where none, and the mask."""

class RectifiedPair:
    """A rectified stereo pair (rectify): the two rectified cameras and what they keep."""
    @property
    def model(self) -> Literal["PINHOLE", "LATLON"]: ...
    @property
    def baseline(self) -> float: ...
    @property
    def cameras(self) -> tuple[Camera, Camera]: ...
    @property
    def rotations(self) -> tuple[FloatArray, FloatArray]: ...
    @property
    def kept(self) -> tuple[float, float]: ...
    @property
    def Q(self) -> FloatArray | None: ...
    @property
    def why(self) -> str: ...
    def maps(
        self, dtype: npt.DTypeLike = np.float32, threads: int = 1
    ) -> tuple[tuple[FloatArray, BoolArray], tuple[FloatArray, BoolArray]]:
        """Each source image's map into its rectified image, as remap_map gives it."""

def rectify(
    first: Camera,
    second: Camera,
    to: Literal["pinhole", "latlon", "auto"] = "auto",
    keep: Literal["valid", "all"] = "valid",
    size: tuple[int, int] | None = None,
    threads: int = 1,
) -> RectifiedPair:
    """The pair rectified: PINHOLE as OpenCV's stereoRectify, LATLON as mrcal's rectified_system."""

def disparity_to_range(pair: RectifiedPair, pixels: ArrayLike, disparity: ArrayLike) -> FloatArray:
    """(N,) distances from the first centre of the points at the first image's pixels with these disparities."""

def disparity_to_points(pair: RectifiedPair, pixels: ArrayLike, disparity: ArrayLike) -> FloatArray:
    """(N, 3) points in the first rectified camera's frame."""
