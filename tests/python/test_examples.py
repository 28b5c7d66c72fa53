"""The Python examples run, on the wide lens of the tests and on real calibration files."""

import os
import subprocess
import sys

import pytest

from conftest import REAL_CAMERAS, SOURCE_DIR, WIDE_LENS

EXAMPLE = SOURCE_DIR / "examples" / "python" / "render_camera.py"


def run_example(*args):
    result = subprocess.run([sys.executable, str(EXAMPLE), *args], capture_output=True, text=True, env=os.environ)
    assert result.returncode == 0, result.stdout + result.stderr
    return result.stdout


def test_render_camera_on_the_wide_lens():
    out = run_example(str(WIDE_LENS))
    assert "reproject through OpenCV within" in out and "project as cv2.projectPoints" in out


@pytest.mark.parametrize("relative", ["basalt/t265_kb4_calib.json", "vins-fusion/euroc/cam0_mei.yaml",
                                      "mrcal/opencv8-0.cameramodel"])
def test_render_camera_on_real_files(relative):
    path = REAL_CAMERAS / relative
    if not path.exists():
        pytest.skip(f"skipped: the real camera files are absent ({path} not found)")
    out = run_example(str(path))
    assert "warp" in out
