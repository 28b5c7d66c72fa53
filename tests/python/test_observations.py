"""libcam.read_observations and libcam.reproject against the file's own numbers (read with
cv2.FileStorage) and cv2.projectPoints, and on a COLMAP model written here by hand."""

import math
import os
import pathlib

import cv2
import numpy as np
import pytest

import libcam
from conftest import SOURCE_DIR, real_camera

REAL_DATA = pathlib.Path(os.environ.get("LIBCAM_REAL_DATA", SOURCE_DIR.parent / "shared" / "real-data"))


def real_data(relative):
    path = REAL_DATA / relative
    if not path.exists():
        pytest.skip(f"skipped: the real data are absent ({path} not found)")
    return path


def test_opencv_calibration_output_reproduces_its_stored_error_and_cv2s_projection():
    path = real_data("opencv-calib-outputs2/scanvan/out_camera_data.xml")
    observations = libcam.read_observations(str(path))
    stored = cv2.FileStorage(str(path), cv2.FILE_STORAGE_READ)
    avg = stored.getNode("avg_reprojection_error").real()
    per_view = stored.getNode("per_view_reprojection_errors").mat().ravel()
    result = libcam.reproject(observations)
    assert result["reported"]["avg_reprojection_error"] == avg
    assert result["recomputed"]["avg_reprojection_error"] == pytest.approx(avg, rel=1e-5)
    assert [v["rms_px"] for v in result["per_view"]] == pytest.approx(list(per_view), rel=1e-5, abs=2e-5)
    # The same residuals through cv2.projectPoints on the same board, poses, K and dist.
    (_, camera), = observations.cameras
    projected = np.empty((len(observations), 2))
    for index, view in enumerate(observations.views):
        rows = observations.view == index
        rvec, _ = cv2.Rodrigues(view["R"])
        points = observations.points[observations.point[rows]]
        pixels, _ = cv2.projectPoints(points, rvec, view["t"], camera.K, camera.dist)
        projected[rows] = pixels.reshape(-1, 2)
    assert np.abs(result["projected"] - projected).max() < 1e-9
    assert np.allclose(result["residual"], result["projected"] - observations.pixel, atol=1e-12)
    assert result["summary"]["count"] == len(observations) == 486


def test_colmap_model_in_its_own_pixels_and_the_half_pixel_check(tmp_path):
    # One pinhole image of three points, in COLMAP's pixels (the principal point (50, 40)
    # is COLMAP's): projected at (100 X / Z + 50, 100 Y / Z + 40), observed 1 px to the
    # right of each.
    (tmp_path / "cameras.txt").write_text("1 PINHOLE 100 80 100 100 50 40\n")
    (tmp_path / "images.txt").write_text(
        "1 1 0 0 0 0 0 0 1 a.png\n51 40 7 61 50 8 41 30 9\n")
    (tmp_path / "points3D.txt").write_text(
        "7 0 0 1 0 0 0 1 1 0\n8 0.1 0.1 1 0 0 0 1 1 1\n9 -0.1 -0.1 1 0 0 0 1 1 2\n")
    observations = libcam.read_observations(str(tmp_path))
    assert observations.pixel_offset == (0.5, 0.5)
    assert observations.pixel.tolist() == [[51, 40], [61, 50], [41, 30]]
    result = libcam.reproject(observations)
    assert np.abs(result["projected"] - [[50, 40], [60, 50], [40, 30]]).max() < 1e-12
    assert result["error_px"].tolist() == pytest.approx([1.0, 1.0, 1.0])
    assert result["point_id"].tolist() == [7, 8, 9]
    assert result["reported"]["mean_point_error_px"] == 1.0
    assert result["recomputed"]["mean_point_error_px"] == pytest.approx(1.0)
    assert result["convention_check"]["best_shift_px"] == pytest.approx((1.0, 0.0))
    assert result["summary"]["rms_px"] == pytest.approx(1.0)


def test_a_camera_file_without_observations_is_refused():
    with pytest.raises(libcam.FileError, match="holds no observations"):
        libcam.read_observations(str(SOURCE_DIR / "tests" / "fuzz" / "corpus" / "json" / "opencv8.json"))


def test_a_bundle_file_needs_its_image_size_and_reads_with_it():
    # Bundler's bundle.out stores no image size; the seed of its fuzz target: camera 0 at
    # R = I, t = (0, 0, -5), f 800, k1 -0.1, k2 0.02 sees (0.5, 0.25, 0) at (79.90025,
    # 39.950125) from the centre, y up (tests/observations/test_nvm_bundler.cpp works it out).
    bundle = SOURCE_DIR / "tests" / "fuzz" / "corpus" / "bundler" / "bundle.out"
    with pytest.raises(libcam.FileError, match="stores no image size"):
        libcam.read_observations(str(bundle))
    observations = libcam.read_observations(str(bundle), size=(640, 480))
    result = libcam.reproject(observations)
    assert result["observed"][0] == pytest.approx((319.5 + 79.90025, 239.5 - 39.950125), abs=1e-9)
    assert result["error_px"][0] == pytest.approx(0.0, abs=1e-9)


def test_opencv_fisheye_cali_stored_error_by_opencvs_rule_against_cv2():
    """A wide lens fitted as OPENCV5 whose distortion folds over inside the image: 3 of its
    1200 corners lie past libcam's valid domain. cv2.projectPoints counts every corner."""
    path = real_camera("opencv-calib-sample-outputs/fisheye_cali/out_camera_data.xml")
    stored = cv2.FileStorage(str(path), cv2.FILE_STORAGE_READ)
    K = stored.getNode("camera_matrix").mat()
    dist = stored.getNode("distortion_coefficients").mat()
    extrinsics = stored.getNode("extrinsic_parameters").mat()
    image_points = stored.getNode("image_points").mat().reshape(extrinsics.shape[0], -1, 2).astype(np.float64)
    width, height = int(stored.getNode("board_width").real()), int(stored.getNode("board_height").real())
    square = stored.getNode("square_size").real()
    board = np.array([[j * square, i * square, 0.0] for i in range(height) for j in range(width)])
    squares = []
    for view, corners in enumerate(image_points):
        projected, _ = cv2.projectPoints(board, extrinsics[view, :3], extrinsics[view, 3:], K, dist)
        squares.append(((projected.reshape(-1, 2) - corners) ** 2).sum(axis=1))
    squares = np.array(squares)
    opencv_avg = math.sqrt(squares.mean())
    opencv_per_view = np.sqrt(squares.mean(axis=1))

    result = libcam.reproject(libcam.read_observations(str(path)))
    assert result["summary"]["count"] == 1197  # libcam's own statistics set 3 apart
    assert result["recomputed_past_domain"] == 3
    assert result["recomputed"]["avg_reprojection_error"] == pytest.approx(opencv_avg, rel=1e-12)
    assert result["reported"]["avg_reprojection_error"] == pytest.approx(opencv_avg, rel=1e-5)
    per_view = stored.getNode("per_view_reprojection_errors").mat().ravel()
    assert opencv_per_view == pytest.approx(list(per_view), rel=1e-5, abs=2e-5)
    assert result["per_view_reported"]["max_abs_difference_px"] < 1e-5
