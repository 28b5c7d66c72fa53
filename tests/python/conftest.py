"""Shared fixtures of the Python module's tests: the cameras, the C++ reference program and
the folder of real calibration files (tests that need it skip, saying so, where it is absent)."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

import libcam

SOURCE_DIR = pathlib.Path(os.environ.get("LIBCAM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
REAL_CAMERAS = pathlib.Path(os.environ.get("LIBCAM_REAL_CAMERAS", SOURCE_DIR.parent / "shared" / "real-cameras"))
# The wide lens of the README and the benchmarks: a 6016x4016 OPENCV8 calibration of a
# 12 mm fisheye lens on a full-frame camera (mrcal's example), 180 degrees corner to corner.
WIDE_LENS = SOURCE_DIR / "tests" / "fuzz" / "corpus" / "json" / "opencv8.json"
MEI_LENS = SOURCE_DIR / "tests" / "fuzz" / "corpus" / "json" / "mei.json"


def real_camera(relative):
    path = REAL_CAMERAS / relative
    if not path.exists():
        pytest.skip(f"skipped: the real camera files are absent ({path} not found)")
    return path


@pytest.fixture
def wide():
    return libcam.read(str(WIDE_LENS))


@pytest.fixture
def fisheye():
    """A Kannala-Brandt fisheye (cv2.fisheye's model), 190 degrees across its image circle."""
    K = np.array([[285.7, 0, 421.3], [0, 286.1, 398.9], [0, 0, 1]])
    return libcam.from_opencv(K, [-0.0068, 0.0406, -0.0386, 0.0067], (848, 800), model="FISHEYE")


class CppReference:
    """The C++ API's answer for the same camera file and inputs (tests/python/cpp_reference.cpp)."""

    def __init__(self, program, folder):
        self.program = program
        self.folder = folder

    def __call__(self, camera_path, operation, inputs, width):
        source = self.folder / "in.f64"
        target = self.folder / "out.f64"
        np.ascontiguousarray(inputs, dtype=np.float64).tofile(source)
        subprocess.run([self.program, str(camera_path), operation, str(source), str(target)], check=True)
        out = np.fromfile(target, dtype=np.float64).reshape(-1, width + 1)
        return out[:, :width], out[:, width] == 1


@pytest.fixture
def cpp_reference(tmp_path):
    program = os.environ.get("LIBCAM_CPP_REFERENCE")
    if not program:
        pytest.fail("LIBCAM_CPP_REFERENCE is not set: run these tests through ctest")
    return CppReference(program, tmp_path)


def grid_pixels(size, columns, rows):
    """Pixels of a grid covering the whole image, corners included, row by row."""
    width, height = size
    xs = np.linspace(0, width - 1, columns)
    ys = np.linspace(0, height - 1, rows)
    return np.stack(np.meshgrid(xs, ys), axis=-1).reshape(-1, 2)
