"""libcam.rectify, its maps and disparity_to_range / _points, against cv2 and the geometry of
3-D points worked here."""

import math

import cv2
import numpy as np
import pytest

import libcam

SIZE = (640, 480)
K1 = np.array([[520.0, 0, 318.5], [0, 516.0, 243.25], [0, 0, 1]])
K2 = np.array([[512.0, 0, 325.0], [0, 510.5, 236.5], [0, 0, 1]])
D1 = np.array([-0.21, 0.06, 8e-4, -5e-4, -0.012])
D2 = np.array([-0.19, 0.045, -3e-4, 6e-4, -0.004])
RVEC = np.array([0.012, -0.018, 0.006])
CENTRE = np.array([0.12, 0.004, -0.003])


def narrow_pair():
    R, _ = cv2.Rodrigues(RVEC)
    T = -R @ CENTRE
    first = libcam.from_opencv(K1, D1, SIZE)
    second = libcam.from_opencv(K2, D2, SIZE, rvec=RVEC, tvec=T)
    return first, second, R, T


def points_in_front(count=200, seed=3):
    rng = np.random.default_rng(seed)
    z = rng.uniform(1.5, 10.0, count)
    return np.stack([rng.uniform(-0.3, 0.3, count) * z, rng.uniform(-0.25, 0.25, count) * z, z], axis=1)


def test_pinhole_rotations_are_opencvs_and_maps_match_initUndistortRectifyMap():
    first, second, R, T = narrow_pair()
    pair = libcam.rectify(first, second, to="pinhole")
    assert pair.model == "PINHOLE"
    R1, R2, P1, P2, Q, _, _ = cv2.stereoRectify(K1, D1, K2, D2, SIZE, R, T, alpha=0)
    assert np.abs(pair.rotations[0] - R1).max() < 1e-12
    assert np.abs(pair.rotations[1] - R2).max() < 1e-12
    assert abs(pair.Q[3, 2] - Q[3, 2]) < 1e-9 * abs(Q[3, 2])
    for k, (K, D) in enumerate(((K1, D1), (K2, D2))):
        (map_xy, valid) = pair.maps()[k]
        cv_x, cv_y = cv2.initUndistortRectifyMap(K, D, pair.rotations[k], pair.cameras[k].K, SIZE, cv2.CV_32FC1)
        assert valid.all()  # no black border
        assert np.abs(map_xy[..., 0] - cv_x).max() < 2e-3
        assert np.abs(map_xy[..., 1] - cv_y).max() < 2e-3


def test_disparity_gives_depth_and_range_of_points():
    first, second, R, T = narrow_pair()
    pair = libcam.rectify(first, second)
    X = points_in_front()
    Rr = pair.rotations
    K = pair.cameras[0].K
    p0 = X @ Rr[0].T
    p1 = (X @ R.T + T) @ Rr[1].T
    q0 = (p0 @ K.T)[:, :2] / p0[:, 2:]
    q1 = (p1 @ K.T)[:, :2] / p1[:, 2:]
    assert np.abs(q0[:, 1] - q1[:, 1]).max() < 1e-6
    d = q0[:, 0] - q1[:, 0]
    points = libcam.disparity_to_points(pair, q0, d)
    assert np.abs(points[:, 2] / p0[:, 2] - 1).max() < 1e-7
    ranges = libcam.disparity_to_range(pair, q0, d)
    assert np.abs(ranges / np.linalg.norm(X, axis=1) - 1).max() < 1e-7
    assert math.isnan(libcam.disparity_to_range(pair, q0[:1], np.array([0.0]))[0])


def test_latlon_range_as_mrcal_stereo_range_defines_it():
    # Two equidistant fisheyes seeing 204 degrees across, 30 cm apart.
    first = libcam.from_opencv(np.array([[180.0, 0, 319.5], [0, 180, 239.5], [0, 0, 1]]), np.zeros(4), SIZE,
                               model="FISHEYE")
    R, _ = cv2.Rodrigues(np.array([0.01, 0.02, -0.005]))
    centre = np.array([0.3, 0.01, 0.02])
    second = libcam.from_opencv(np.array([[181.0, 0, 321.0], [0, 180.5, 238.0], [0, 0, 1]]), np.zeros(4), SIZE,
                                rvec=cv2.Rodrigues(R)[0], tvec=-R @ centre, model="FISHEYE")
    pair = libcam.rectify(first, second)
    assert pair.model == "LATLON" and pair.Q is None
    assert min(pair.kept) >= 0.95
    K = pair.cameras[0].K
    X = points_in_front()
    p0 = X @ pair.rotations[0].T
    p1 = (X @ R.T - R @ centre) @ pair.rotations[1].T
    # mrcal's LATLON: column fx asin(x / |p|) + cx, row fy atan2(y, z) + cy.
    az0, az1 = np.arcsin(p0[:, 0] / np.linalg.norm(p0, axis=1)), np.arcsin(p1[:, 0] / np.linalg.norm(p1, axis=1))
    el0, el1 = np.arctan2(p0[:, 1], p0[:, 2]), np.arctan2(p1[:, 1], p1[:, 2])
    assert np.abs(el0 - el1).max() * K[1, 1] < 1e-6
    q0 = np.stack([K[0, 0] * az0 + K[0, 2], K[1, 1] * el0 + K[1, 2]], axis=1)
    ranges = libcam.disparity_to_range(pair, q0, K[0, 0] * (az0 - az1))
    assert np.abs(ranges / np.linalg.norm(X, axis=1) - 1).max() < 1e-7


def test_bad_requests_say_why():
    first, second, _, _ = narrow_pair()
    with pytest.raises(libcam.Error, match="same centre"):
        libcam.rectify(first, first)
    with pytest.raises(libcam.Error, match="to: expected"):
        libcam.rectify(first, second, to="cylinder")
    pair = libcam.rectify(first, second)
    with pytest.raises(TypeError, match="shape"):
        libcam.disparity_to_range(pair, np.zeros((3, 2)), np.zeros(2))
