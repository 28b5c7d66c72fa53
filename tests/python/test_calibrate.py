# libcam.calibrate against cv2.calibrateCamera on the same corner arrays (board corners
# projected through a known OPENCV5 camera by cv2.projectPoints, with noise), and against
# the libcam program's calibrate --json on OpenCV's sample images.

import json
import os
import pathlib
import subprocess

import cv2
import numpy as np
import mrcal
import pytest

import libcam
from conftest import SOURCE_DIR

REAL_DATA = pathlib.Path(os.environ.get("LIBCAM_REAL_DATA", SOURCE_DIR.parent / "shared" / "real-data"))
SIZE = (640, 480)
K_TRUE = np.array([[520.0, 0.0, 322.0], [0.0, 518.0, 241.0], [0.0, 0.0, 1.0]])
DIST_TRUE = np.array([-0.28, 0.09, 0.0012, -0.0008, 0.0])


def board_points(columns=9, rows=6, square=0.03):
    grid = np.mgrid[0:columns, 0:rows].T.reshape(-1, 2) * square
    return np.hstack([grid, np.zeros((len(grid), 1))]).astype(np.float32)


def synthetic_corners(views=10, noise_px=0.1, seed=5):
    """Each view's 54 corners as cv2.projectPoints puts them, in the board's order, plus noise."""
    rng = np.random.default_rng(seed)
    points = board_points()
    centre = points.mean(axis=0)
    corners = []
    for v in range(views):
        rvec = np.array([0.5 * np.sin(v), 0.45 * np.cos(1.7 * v), 0.2 * np.sin(0.7 * v)])
        R, _ = cv2.Rodrigues(rvec)
        tvec = -R @ centre + np.array([0.06 * np.sin(2.1 * v), 0.05 * np.cos(1.3 * v), 0.45 + 0.03 * v])
        pixels, _ = cv2.projectPoints(points, rvec, tvec, K_TRUE, DIST_TRUE)
        corners.append(pixels.reshape(-1, 2) + rng.normal(0.0, noise_px, (len(points), 2)))
    return corners


def opencv_calibration(corners, flags=0):
    objects = [board_points()] * len(corners)
    images = [c.astype(np.float32).reshape(-1, 1, 2) for c in corners]
    K = np.eye(3)
    return cv2.calibrateCamera(objects, images, SIZE, K, None, flags=flags)


@pytest.mark.parametrize("flags", ["", "FIX_ASPECT_RATIO", "FIX_ASPECT_RATIO,ZERO_TANGENT_DIST"])
def test_calibrate_corner_arrays_as_cv2_calibrateCamera(flags):
    corners = synthetic_corners()
    got = libcam.calibrate(corners, "chessboard:9x6:0.03", image_size=SIZE, model="OPENCV5",
                           opencv_flags=flags or None, keep_outliers=True)
    opencv_flags = {"": 0, "FIX_ASPECT_RATIO": cv2.CALIB_FIX_ASPECT_RATIO,
                    "FIX_ASPECT_RATIO,ZERO_TANGENT_DIST": cv2.CALIB_FIX_ASPECT_RATIO | cv2.CALIB_ZERO_TANGENT_DIST}[flags]
    rms, K, dist, rvecs, tvecs = opencv_calibration(corners, opencv_flags)
    chosen = got["chosen"]
    assert chosen["model"] == "OPENCV5"
    assert isinstance(chosen["K"], np.ndarray) and chosen["K"].shape == (3, 3)
    np.testing.assert_allclose(chosen["K"], K, atol=1e-3)
    # OpenCV stops earlier (its k2 and k3 differ by 5e-5 from the minimum, far inside their
    # standard deviations): the same minimum, libcam's never above OpenCV's.
    np.testing.assert_allclose(chosen["dist"], dist.ravel(), atol=2e-4)
    assert chosen["rms_px"] == pytest.approx(rms, rel=1e-5)
    assert chosen["rms_px"] <= rms * (1 + 1e-9)
    assert got["rvecs"].shape == (10, 3) and got["tvecs"].shape == (10, 3)
    np.testing.assert_allclose(got["rvecs"], np.hstack(rvecs).T, atol=1e-6)
    np.testing.assert_allclose(got["tvecs"], np.hstack(tvecs).T, atol=1e-6)
    np.testing.assert_allclose(got["views"][3]["rvec"], rvecs[3].ravel(), atol=1e-6)
    if flags:
        assert chosen["K"][0, 0] == chosen["K"][1, 1]
        assert got["held"].startswith("fx = fy")


def test_calibrate_partial_views_by_id():
    corners = synthetic_corners()
    ids = list(range(9, 54))  # the first row unseen
    views = [(ids, c[9:]) for c in corners]
    got = libcam.calibrate(views, "chessboard:9x6:0.03", image_size=SIZE, model="OPENCV5", keep_outliers=True)
    objects = [board_points()[9:]] * len(corners)
    rms, K, dist, _, _ = cv2.calibrateCamera(objects, [c[9:].astype(np.float32) for c in corners], SIZE, np.eye(3), None)
    assert got["corners"] == 10 * 45
    np.testing.assert_allclose(got["chosen"]["K"], K, atol=1e-3)
    assert got["chosen"]["rms_px"] == pytest.approx(rms, rel=1e-5)


def test_calibrate_refuses_bad_views():
    corners = synthetic_corners(views=3)
    with pytest.raises(libcam.Error, match="image_size"):
        libcam.calibrate(corners, "chessboard:9x6:0.03")
    with pytest.raises(libcam.Error, match="corner id 54 is not one of the 54"):
        libcam.calibrate([(list(range(7, 61)), c) for c in corners], "chessboard:9x6:0.03", image_size=SIZE)
    with pytest.raises(libcam.Error, match="--opencv-flags"):
        libcam.calibrate(corners, "chessboard:9x6:0.03", image_size=SIZE, opencv_flags="FIX_PRINCIPAL_POINT")
    with pytest.raises(libcam.Error, match="board"):
        libcam.calibrate(corners, "chessboard:9x6", image_size=SIZE)


def test_calibrate_images_as_the_program_does():
    folder = REAL_DATA / "opencv-stereo-samples"
    if not folder.is_dir():
        pytest.skip(f"skipped: OpenCV's sample images are absent ({folder} not found)")
    images = [str(folder / f"left{n:02d}.jpg") for n in (1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14)]
    args = ["--board", "chessboard:9x6:0.025", "--model", "OPENCV4,OPENCV5", "--opencv-flags", "2", "--at", "20,30"]
    program = subprocess.run([os.environ["LIBCAM_EXE"], "calibrate", *images, *args, "--json", "--progress", "never"],
                             check=True, capture_output=True, text=True)
    expected = json.loads(program.stdout)
    got = libcam.calibrate(images, "chessboard:9x6:0.025", model="OPENCV4,OPENCV5", opencv_flags="2", at=[(20, 30)])
    for key in ("rvecs", "tvecs"):
        got.pop(key)
    as_lists = json.loads(json.dumps(got, default=lambda a: a.tolist()))
    assert as_lists == expected


K_RIGHT = np.array([[515.0, 0.0, 318.0], [0.0, 514.0, 244.0], [0.0, 0.0, 1.0]])
DIST_RIGHT = np.array([-0.25, 0.07, -0.0005, 0.001, 0.0])
RVEC_PAIR = np.array([0.01, -0.02, 0.005])  # X_right = R X_left + T
T_PAIR = np.array([-0.06, 0.002, 0.001])


def synthetic_pair(views=10, noise_px=0.1, seed=7):
    """Each view's corners in both cameras (the board posed in the left camera as in
    synthetic_corners, carried into the right one by the pair's pose), plus noise."""
    rng = np.random.default_rng(seed)
    points = board_points()
    centre = points.mean(axis=0)
    R_pair, _ = cv2.Rodrigues(RVEC_PAIR)
    left, right = [], []
    for v in range(views):
        rvec = np.array([0.5 * np.sin(v), 0.45 * np.cos(1.7 * v), 0.2 * np.sin(0.7 * v)])
        R, _ = cv2.Rodrigues(rvec)
        tvec = -R @ centre + np.array([0.03 + 0.05 * np.sin(2.1 * v), 0.05 * np.cos(1.3 * v), 0.45 + 0.03 * v])
        rvec_right, _ = cv2.Rodrigues(R_pair @ R)
        tvec_right = R_pair @ tvec + T_PAIR
        for out, rv, tv, K, dist in ((left, rvec, tvec, K_TRUE, DIST_TRUE),
                                     (right, rvec_right, tvec_right, K_RIGHT, DIST_RIGHT)):
            pixels, _ = cv2.projectPoints(points, rv, tv, K, dist)
            pixels = pixels.reshape(-1, 2)
            assert (pixels > 0).all() and (pixels < SIZE).all(), "every corner in both images"
            out.append(pixels + rng.normal(0.0, noise_px, (len(points), 2)))
    return left, right


def test_calibrate_pair_corner_arrays_as_cv2_stereoCalibrate():
    left, right = synthetic_pair()
    got = libcam.calibrate_pair(left, right, "chessboard:9x6:0.03", image_size=SIZE, model="OPENCV5",
                                keep_outliers=True)
    # cv2 on the same corners, as OpenCV's stereo_calib refines a pair: each camera alone,
    # then both with the pair's pose (intrinsics free, from each camera's own calibration).
    objects = [board_points()] * len(left)
    L = [c.astype(np.float32).reshape(-1, 1, 2) for c in left]
    R_ = [c.astype(np.float32).reshape(-1, 1, 2) for c in right]
    _, K1, D1, _, _ = cv2.calibrateCamera(objects, L, SIZE, None, None)
    _, K2, D2, _, _ = cv2.calibrateCamera(objects, R_, SIZE, None, None)
    tight = (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 200, 1e-12)
    rms, K1, D1, K2, D2, R, T, _, _ = cv2.stereoCalibrate(objects, L, R_, K1, D1, K2, D2, SIZE,
                                                          flags=cv2.CALIB_USE_INTRINSIC_GUESS, criteria=tight)
    assert got["pairs"] == list(range(len(left)))
    assert got["R"].shape == (3, 3) and got["T"].shape == (3,)
    assert got["rms_px"] == pytest.approx(rms, rel=1e-4)
    turn = np.linalg.norm(cv2.Rodrigues(got["R"] @ R.T)[0])
    assert turn < 1e-6
    np.testing.assert_allclose(got["T"], T.ravel(), atol=1e-6)
    np.testing.assert_allclose(got["cameras"][0]["K"], K1, atol=1e-3)
    np.testing.assert_allclose(got["cameras"][1]["K"], K2, atol=1e-3)
    np.testing.assert_allclose(got["cameras"][1]["dist"], D2.ravel(), atol=2e-4)
    # And the truth the corners were made from, within what 0.1 px of noise allows.
    truth_turn = np.linalg.norm(cv2.Rodrigues(got["R"] @ cv2.Rodrigues(RVEC_PAIR)[0].T)[0])
    assert truth_turn < 2e-3
    np.testing.assert_allclose(got["T"], T_PAIR, atol=2e-3)
    # Each camera alone, as calibrate() reports it; the refined cameras, posed, rectify.
    assert got["left"]["chosen"]["model"] == "OPENCV5" and got["right"]["rvecs"].shape == (10, 3)
    rectified = libcam.rectify(got["left_camera"], got["right_camera"])
    assert rectified.model == "PINHOLE"
    assert rectified.baseline == pytest.approx(np.linalg.norm(got["T"]), rel=1e-12)


def test_calibrate_pair_refuses_in_one_line():
    left, right = synthetic_pair(views=3)
    with pytest.raises(libcam.Error, match="image_size"):
        libcam.calibrate_pair(left, right, "chessboard:9x6:0.03")
    with pytest.raises(libcam.Error, match="right view 1: corners must be an"):
        libcam.calibrate_pair(left, [right[0], right[1][:, :1], right[2]], "chessboard:9x6:0.03", image_size=SIZE)
    with pytest.raises(libcam.Error) as refused:
        libcam.calibrate_pair(left, right[:2], "chessboard:9x6:0.03", image_size=SIZE)
    assert "\n" not in str(refused.value)


def test_calibrate_pair_images_as_the_program_does():
    folder = REAL_DATA / "opencv-stereo-samples"
    if not folder.is_dir():
        pytest.skip(f"skipped: OpenCV's sample images are absent ({folder} not found)")
    sides = {side: [str(folder / f"{side}{n:02d}.jpg") for n in (1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14)]
             for side in ("left", "right")}
    args = ["--board", "chessboard:9x6:0.025", "--model", "OPENCV5", "--corners", "opencv-sample", "--at", "20,30"]
    program = subprocess.run([os.environ["LIBCAM_EXE"], "calibrate", "--left", *sides["left"], "--right",
                              *sides["right"], *args, "--json", "--progress", "never"],
                             check=True, capture_output=True, text=True)
    expected = json.loads(program.stdout)
    got = libcam.calibrate_pair(sides["left"], sides["right"], "chessboard:9x6:0.025", model="OPENCV5",
                                corners="opencv-sample", at=[(20, 30)])
    assert [u["pixel"] for u in expected["cameras"][1]["uncertainty"]] == [[20, 30]]
    for key in ("left_camera", "right_camera"):
        assert isinstance(got.pop(key), libcam.Camera)
    for side in ("left", "right"):
        for key in ("rvecs", "tvecs"):
            got[side].pop(key)
    as_lists = json.loads(json.dumps(got, default=lambda a: a.tolist()))
    assert as_lists == expected


def test_calibrate_pair_uncertainty_is_mrcals_of_the_same_solve():
    """Each camera's projection uncertainty in the pair's solve, against mrcal's of the same
    solve: the pair's cameras, pose and board poses as libcam returns them, with the same
    corners, written as mrcal's optimization_inputs (no regularization, as libcam)."""
    left, right = synthetic_pair(views=8, noise_px=0.3)
    # Inside the corners' reach: 8 noisy views fit a k3 that folds the lens back near the
    # image's corners, where libcam gives no ray (and so no sigma).
    pixels = np.array([[319.5, 239.5], [160.0, 120.0], [500.0, 380.0], [100.0, 60.0]])
    got = libcam.calibrate_pair(left, right, "chessboard:9x6:0.03", image_size=SIZE, model="OPENCV5",
                                keep_outliers=True, at=pixels)
    assert got["pairs"] == list(range(8))
    assert len(got["views"]) == 8
    corners = np.stack([np.stack([left[i], right[i]]) for i in got["pairs"]])  # (frame, camera, corner, 2)
    observations = np.concatenate([corners, np.ones(corners.shape[:-1] + (1,))], axis=-1)
    observations = observations.reshape(len(got["pairs"]) * 2, 6, 9, 3)  # the board's rows, columns
    intrinsics = np.array([[c["K"][0, 0], c["K"][1, 1], c["K"][0, 2], c["K"][1, 2], *c["dist"]]
                           for c in got["cameras"]])
    inputs = dict(
        intrinsics=intrinsics,
        extrinsics_rt_fromref=np.concatenate([cv2.Rodrigues(got["R"])[0].ravel(), got["T"]])[None, :],
        frames_rt_toref=np.array([np.concatenate([v["rvec"], v["tvec"]]) for v in got["views"]]),
        points=None, observations_board=observations,
        indices_frame_camintrinsics_camextrinsics=np.array(
            [[f, c, c - 1] for f in range(len(got["pairs"])) for c in range(2)], dtype=np.int32),
        observations_point=None, indices_point_camintrinsics_camextrinsics=None, lensmodel="LENSMODEL_OPENCV5",
        imagersizes=np.array([SIZE, SIZE], dtype=np.int32), calobject_warp=None,
        do_optimize_intrinsics_core=True, do_optimize_intrinsics_distortions=True, do_optimize_extrinsics=True,
        do_optimize_frames=True, do_optimize_calobject_warp=False, calibration_object_spacing=0.03,
        do_apply_outlier_rejection=False, do_apply_regularization=False, verbose=False)
    # mrcal's residuals at libcam's solve are libcam's: its RMS over both cameras.
    x = mrcal.optimizer_callback(**inputs, no_jacobian=True, no_factorization=True)[1]
    residuals = mrcal.residuals_chessboard(inputs, residuals=x).ravel()
    assert np.sqrt(np.mean(residuals ** 2) * 2) == pytest.approx(got["rms_px"], rel=1e-9)
    assert got["noise_px"] == pytest.approx(np.std(residuals), rel=1e-9)
    for camera in range(2):
        model = mrcal.cameramodel(optimization_inputs=inputs, icam_intrinsics=camera)
        v = mrcal.unproject(pixels, *model.intrinsics(), normalize=True)
        expected = mrcal.projection_uncertainty(v, model, atinfinity=True, what="worstdirection-stdev")
        sigma = [entry["sigma_px"] for entry in got["cameras"][camera]["uncertainty"]]
        assert [entry["pixel"] for entry in got["cameras"][camera]["uncertainty"]] == pixels.tolist()
        np.testing.assert_allclose(sigma, expected, rtol=1e-6)


def mrcal_sigma_at(model, pixels):
    v = mrcal.unproject(np.asarray(pixels, dtype=float), *model.intrinsics(), normalize=True)
    return mrcal.projection_uncertainty(v, model, atinfinity=True, what="worstdirection-stdev")


def test_calibrate_writes_its_solve_for_mrcal(tmp_path):
    """`libcam calibrate -o x.cameramodel` keeps the solve in the model as mrcal keeps its own
    (optimization_inputs): mrcal reads it, its residuals give libcam's RMS and its projection
    uncertainty is the one libcam reported, for one camera and for each camera of a pair."""
    folder = REAL_DATA / "opencv-stereo-samples"
    if not folder.is_dir():
        pytest.skip(f"skipped: OpenCV's sample images are absent ({folder} not found)")
    numbers = (1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14)
    sides = {side: [str(folder / f"{side}{n:02d}.jpg") for n in numbers] for side in ("left", "right")}
    board = ["--board", "chessboard:9x6:0.025", "--model", "OPENCV5", "--progress", "never", "--json"]
    pixels = [[319.5, 239.5], [100.0, 80.0]]
    at = [arg for p in pixels for arg in ("--at", f"{p[0]},{p[1]}")]

    one = tmp_path / "left.cameramodel"
    run = subprocess.run([os.environ["LIBCAM_EXE"], "calibrate", *sides["left"], *board, *at, "-o", str(one)],
                         check=True, capture_output=True, text=True)
    report = json.loads(run.stdout)
    model = mrcal.cameramodel(str(one))
    inputs = model.optimization_inputs()
    assert inputs is not None and model.icam_intrinsics() == 0
    assert inputs["observations_board"].shape == (report["used"], 6, 9, 3)
    x = mrcal.optimizer_callback(**inputs, no_jacobian=True, no_factorization=True)[1]
    residuals = mrcal.residuals_chessboard(inputs, residuals=x).ravel()
    assert np.sqrt(np.mean(residuals ** 2) * 2) == pytest.approx(report["chosen"]["rms_px"], rel=1e-9)
    np.testing.assert_allclose(mrcal_sigma_at(model, pixels), [u["sigma_px"] for u in report["uncertainty"]],
                               rtol=1e-6)

    pair = tmp_path / "pair"
    run = subprocess.run([os.environ["LIBCAM_EXE"], "calibrate", "--left", *sides["left"], "--right",
                          *sides["right"], *board, *at, "-o", str(pair)],
                         check=True, capture_output=True, text=True)
    report = json.loads(run.stdout)
    for camera, name in enumerate(("left", "right")):
        model = mrcal.cameramodel(str(pair / f"{name}.cameramodel"))
        assert model.icam_intrinsics() == camera
        inputs = model.optimization_inputs()
        assert inputs["intrinsics"].shape == (2, 9) and inputs["extrinsics_rt_fromref"].shape == (1, 6)
        np.testing.assert_allclose(mrcal_sigma_at(model, pixels),
                                   [u["sigma_px"] for u in report["cameras"][camera]["uncertainty"]], rtol=1e-6)
        # And libcam's own reader of mrcal's solves takes it back whole.
        got = libcam.projection_uncertainty(libcam.read_observations(str(pair / f"{name}.cameramodel")),
                                            np.array(pixels))
        np.testing.assert_allclose(got["sigma_px"], [u["sigma_px"] for u in report["cameras"][camera]["uncertainty"]],
                                   rtol=1e-9)
    x = mrcal.optimizer_callback(**inputs, no_jacobian=True, no_factorization=True)[1]
    residuals = mrcal.residuals_chessboard(inputs, residuals=x).ravel()
    assert np.sqrt(np.mean(residuals ** 2) * 2) == pytest.approx(report["rms_px"], rel=1e-9)


def test_calibrate_says_when_mrcal_cannot_hold_its_solve(tmp_path):
    """A fit that held fx = fy is not mrcal's problem (mrcal frees every intrinsic or none):
    the model is written without the solve, and stderr says why in one line."""
    folder = REAL_DATA / "opencv-stereo-samples"
    if not folder.is_dir():
        pytest.skip(f"skipped: OpenCV's sample images are absent ({folder} not found)")
    images = [str(folder / f"left{n:02d}.jpg") for n in (1, 2, 3, 4, 5, 6)]
    out = tmp_path / "held.cameramodel"
    run = subprocess.run([os.environ["LIBCAM_EXE"], "calibrate", *images, "--board", "chessboard:9x6:0.025",
                          "--model", "OPENCV5", "--opencv-flags", "FIX_ASPECT_RATIO", "--progress", "never",
                          "-o", str(out)], check=True, capture_output=True, text=True)
    assert mrcal.cameramodel(str(out)).optimization_inputs() is None
    lines = run.stderr.splitlines()
    assert len(lines) == 1 and "written without the solve" in lines[0] and "fx = fy" in lines[0]
