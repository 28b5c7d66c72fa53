# libcam.projection_uncertainty against mrcal's own projection_uncertainty, on a small
# solve mrcal makes itself (tests/uncertainty/mrcal_uncertainty.py) and on mrcal's real
# OPENCV8 solve: the expected values come from mrcal.

import subprocess
import sys

import mrcal
import numpy as np
import pytest

import libcam
from conftest import SOURCE_DIR, real_camera

SCRIPT = SOURCE_DIR / "tests" / "uncertainty" / "mrcal_uncertainty.py"


def mrcal_sigma(path, pixels):
    model = mrcal.cameramodel(str(path))
    v = mrcal.unproject(pixels, *model.intrinsics(), normalize=True)
    return mrcal.projection_uncertainty(v, model, atinfinity=True, what="worstdirection-stdev")


def test_projection_uncertainty_of_a_solve_mrcal_makes(tmp_path):
    model = tmp_path / "small.cameramodel"
    subprocess.run([sys.executable, str(SCRIPT), "write", str(model)], check=True)
    pixels = np.array([[319.5, 239.5], [20.0, 30.0], [600.0, 400.0]])
    got = libcam.projection_uncertainty(libcam.read_observations(str(model)), pixels)
    # The same problem (a flat board, no regularization): the same to rounding.
    np.testing.assert_allclose(got["sigma_px"], mrcal_sigma(model, pixels), rtol=1e-6)
    assert got["covariance"].shape == (3, 2, 2)
    assert [p["name"] for p in got["parameters"]] == ["fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2"]


def test_projection_uncertainty_of_mrcal_real_solve():
    path = real_camera("mrcal/opencv8-0.cameramodel")
    pixels = np.array([[3007.5, 2007.5], [0.0, 0.0], [6015.0, 2007.5]])
    got = libcam.projection_uncertainty(libcam.read_observations(str(path)), pixels)
    # mrcal freed the board's bow in this solve, and so does libcam; mrcal's regularization
    # is left: 1.6e-4 apart at most.
    np.testing.assert_allclose(got["sigma_px"], mrcal_sigma(path, pixels), rtol=1e-3)


def test_projection_uncertainty_of_each_camera_of_a_two_camera_solve(tmp_path):
    models = [tmp_path / "rig-0.cameramodel", tmp_path / "rig-1.cameramodel"]
    subprocess.run([sys.executable, str(SCRIPT), "write-rig", *map(str, models)], check=True)
    pixels = np.array([[319.5, 239.5], [20.0, 30.0]])
    for camera, model in enumerate(models):
        observations = libcam.read_observations(str(model))
        # By default the camera the model is; the whole solve counts, as in mrcal.
        got = libcam.projection_uncertainty(observations, pixels)
        np.testing.assert_allclose(got["sigma_px"], mrcal_sigma(model, pixels), rtol=1e-6)
        other = libcam.projection_uncertainty(observations, pixels, camera=1 - camera)
        np.testing.assert_allclose(other["sigma_px"], mrcal_sigma(models[1 - camera], pixels), rtol=1e-6)


def test_projection_uncertainty_refuses_a_bad_distance(tmp_path):
    model = tmp_path / "small.cameramodel"
    subprocess.run([sys.executable, str(SCRIPT), "write", str(model)], check=True)
    with pytest.raises(libcam.Error, match="distance"):
        libcam.projection_uncertainty(libcam.read_observations(str(model)), [[320.0, 240.0]], distance=-1.0)
