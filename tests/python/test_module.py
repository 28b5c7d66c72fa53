"""The Python module against the C++ API (the same bits), cv2 and mrcal, and its error paths."""

import math
import subprocess
import threading
import time

import cv2
import mrcal
import numpy as np
import pytest

import libcam
from conftest import MEI_LENS, WIDE_LENS, grid_pixels, real_camera


def points_in_front(count, seed=1, spread=1.5):
    rng = np.random.default_rng(seed)
    xy = rng.uniform(-spread, spread, size=(count, 2))
    depth = rng.uniform(0.5, 20.0, size=(count, 1))
    return np.hstack([xy * depth, depth])


def bits_equal(a, b):
    """Equal bit for bit, NaN included."""
    return np.array_equal(np.asarray(a).view(np.uint64 if a.dtype == np.float64 else np.uint32),
                          np.asarray(b).view(np.uint64 if b.dtype == np.float64 else np.uint32))


# ------------------------------------------------------------------ the module itself

def test_version_is_the_programs(tmp_path):
    import os
    out = subprocess.run([os.environ["LIBCAM_EXE"], "--version"], capture_output=True, text=True, check=True).stdout
    assert out.split()[1] == libcam.__version__


def test_model_table():
    # OpenCV's order of its coefficients (calib3d's documentation).
    assert libcam.models["OPENCV8"]["coefficients"] == ("k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6")
    assert libcam.models["FISHEYE"]["opencv"] == "cv2.fisheye.projectPoints"
    assert libcam.models["MEI"]["opencv"] == "cv2.omnidir.projectPoints"
    assert libcam.models["OPENCV4"]["colmap"] == "OPENCV"
    assert libcam.models["SPLINED_STEREOGRAPHIC"]["coefficient_count"] is None
    assert "opencv-yaml" in libcam.formats and "cameramodel" in libcam.formats


def test_help_says_what_invalid_means():
    assert "invalid" in libcam.Camera.unproject.__doc__ and "NaN" in libcam.Camera.unproject.__doc__
    assert "NaN" in libcam.Camera.project.__doc__


# ------------------------------------------------------- the same bits as the C++ API

def test_project_is_the_cpp_apis_bits(wide, cpp_reference):
    points = points_in_front(5000)
    points[::97] *= -1  # some behind the camera: invalid
    pixels, valid = wide.project(points)
    expected, expected_valid = cpp_reference(WIDE_LENS, "project", points, 2)
    assert np.array_equal(valid, expected_valid)
    assert not valid.all() and valid.sum() > 4000
    assert bits_equal(pixels[valid], expected[expected_valid])
    assert np.isnan(pixels[~valid]).all()


@pytest.mark.parametrize("method", ["exact", "fast", "lut"])
def test_unproject_is_the_cpp_apis_bits(wide, cpp_reference, method):
    pixels = grid_pixels(wide.size, 61, 41)
    directions, valid = wide.unproject(pixels, method=method)
    expected, expected_valid = cpp_reference(WIDE_LENS, "unproject-" + method, pixels, 3)
    assert np.array_equal(valid, expected_valid)
    assert bits_equal(directions[valid], expected[expected_valid])


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_unprojection_of_pixels_without_a_ray_gives_nan_and_false(wide, dtype):
    pixels = grid_pixels(wide.size, 61, 41).astype(dtype)
    directions, valid = wide.unproject(pixels)
    assert valid.all()
    pixels[::53] = np.nan
    pixels[7] = (-1e6, 5.0)  # far outside the image, past the lens's domain
    again, again_valid = wide.unproject(pixels)
    unsettled = np.zeros(len(pixels), bool)
    unsettled[::53] = True
    unsettled[7] = True
    assert not again_valid[unsettled].any() and np.isnan(again[unsettled]).all()
    assert again_valid[~unsettled].all() and bits_equal(again[~unsettled], directions[~unsettled])


def test_rays_are_the_cpp_apis_bits(cpp_reference, tmp_path):
    camera = libcam.from_opencv(np.array([[800.0, 0, 639.5], [0, 810, 359.5], [0, 0, 1]]), [0.1, -0.2, 1e-3, -2e-3, 0.05],
                                (1280, 720), rvec=[0.1, -0.4, 0.2], tvec=[1.0, 2.0, -3.0])
    path = tmp_path / "posed.json"
    camera.write(str(path))
    pixels = grid_pixels(camera.size, 33, 21)
    rays, valid = camera.rays(pixels)
    expected, expected_valid = cpp_reference(path, "rays", pixels, 3)
    assert np.array_equal(valid, expected_valid) and valid.all()
    assert bits_equal(rays, expected)
    assert np.allclose(np.linalg.norm(rays, axis=-1), 1.0, atol=1e-15)


def test_float32_is_the_cpp_apis_float_bits(wide, cpp_reference):
    points = points_in_front(3000).astype(np.float32)
    pixels, valid = wide.project(points, frame="camera")
    assert pixels.dtype == np.float32
    expected, expected_valid = cpp_reference(WIDE_LENS, "project-float", points, 2)
    assert np.array_equal(valid, expected_valid)
    assert bits_equal(pixels[valid], expected[expected_valid].astype(np.float32))
    grid = grid_pixels(wide.size, 41, 31).astype(np.float32)
    directions, valid = wide.unproject(grid)
    assert directions.dtype == np.float32
    expected, expected_valid = cpp_reference(WIDE_LENS, "unproject-float", grid, 3)
    assert np.array_equal(valid, expected_valid)
    assert bits_equal(directions[valid], expected[expected_valid].astype(np.float32))


def test_threads_give_the_same_bits(wide):
    points = points_in_front(100_000, seed=4)
    one, valid_one = wide.project(points, threads=1)
    two, valid_two = wide.project(points, threads=2)
    assert bits_equal(one, two) and np.array_equal(valid_one, valid_two)
    pixels = grid_pixels(wide.size, 300, 200)
    one, _ = wide.unproject(pixels, threads=1)
    every, _ = wide.unproject(pixels, threads=0)
    assert bits_equal(one, every)


# ---------------------------------------------------------------------- against cv2

def test_wide_lens_against_cv2(wide):
    points = points_in_front(20000, seed=2, spread=1.2)
    pixels, valid = wide.project(points)
    reference, _ = cv2.projectPoints(points, np.zeros(3), np.zeros(3), wide.K, wide.dist)
    reference = reference.reshape(-1, 2)
    assert valid.all()
    assert np.abs(pixels - reference).max() < 1e-8
    # Unprojected by libcam, reprojected by OpenCV: back on the pixel.
    grid = grid_pixels(wide.size, 121, 81)
    directions, valid = wide.unproject(grid)
    assert valid.all()
    back, _ = cv2.projectPoints(directions, np.zeros(3), np.zeros(3), wide.K, wide.dist)
    assert np.abs(back.reshape(-1, 2) - grid).max() < 1e-8
    # cv2.undistortPoints run to convergence lands on the same rays where it converges.
    undistorted = cv2.undistortPointsIter(grid.reshape(-1, 1, 2), wide.K, wide.dist, None, None,
                                          (cv2.TERM_CRITERIA_COUNT, 100, 0)).reshape(-1, 2)
    ray_error = np.linalg.norm(undistorted - directions[:, :2], axis=-1) * wide.K[0, 0]
    assert np.median(ray_error) < 1e-6


def test_fisheye_against_cv2(fisheye):
    rng = np.random.default_rng(3)
    # cv2.fisheye takes the angle as atan(r / z): only points in front of the camera.
    theta = rng.uniform(0, math.radians(89), 5000)
    phi = rng.uniform(0, 2 * math.pi, 5000)
    directions = np.stack([np.sin(theta) * np.cos(phi), np.sin(theta) * np.sin(phi), np.cos(theta)], axis=-1)
    points = directions * rng.uniform(0.5, 5, (5000, 1))
    pixels, valid = fisheye.project(points)
    assert valid.all()
    reference, _ = cv2.fisheye.projectPoints(points.reshape(-1, 1, 3), np.zeros(3), np.zeros(3), fisheye.K, fisheye.dist)
    assert np.abs(pixels - reference.reshape(-1, 2)).max() < 1e-9
    back, valid = fisheye.unproject(pixels, normalize=True)
    assert valid.all()
    angle = np.linalg.norm(back - directions, axis=-1)  # the chord: the angle, to rounding
    assert angle.max() * fisheye.K[0, 0] < 1e-9
    # cv2.fisheye.projectPoints of libcam's rays through a grid (those in front): the pixels again.
    grid = grid_pixels(fisheye.size, 85, 80)
    rays, valid = fisheye.unproject(grid)
    front = valid & (rays[:, 2] > 0)
    assert front.sum() > 3000
    reprojected, _ = cv2.fisheye.projectPoints(rays[front].reshape(-1, 1, 3), np.zeros(3), np.zeros(3), fisheye.K, fisheye.dist)
    assert np.abs(reprojected.reshape(-1, 2) - grid[front]).max() < 1e-8
    # A pixel past the lens's widest angle has no ray: NaN and False.
    far, far_valid = fisheye.unproject([[-30000.0, -30000.0], [421.3, 398.9]])
    assert far_valid.tolist() == [False, True]
    assert np.isnan(far[0]).all() and not np.isnan(far[1]).any()


def test_mei_against_cv2_omnidir():
    camera = libcam.read(str(MEI_LENS))
    assert camera.model == "MEI"
    xi, k1, k2, p1, p2 = camera.dist
    points = points_in_front(3000, seed=5, spread=1.0)
    pixels, valid = camera.project(points)
    reference, _ = cv2.omnidir.projectPoints(points.reshape(1, -1, 3), np.zeros(3), np.zeros(3), camera.K, float(xi),
                                             np.array([[k1, k2, p1, p2]]))
    assert np.abs(pixels[valid] - reference.reshape(-1, 2)[valid]).max() < 1e-8
    assert valid.mean() > 0.9


# --------------------------------------------------------------------- against mrcal

def test_wide_lens_against_mrcal(wide):
    intrinsics = np.concatenate([[wide.K[0, 0], wide.K[1, 1], wide.K[0, 2], wide.K[1, 2]], wide.dist])
    points = points_in_front(20000, seed=6, spread=1.2)
    pixels, valid = wide.project(points)
    reference = mrcal.project(points, "LENSMODEL_OPENCV8", intrinsics)
    assert valid.all()
    assert np.abs(pixels - reference).max() < 1e-8
    grid = grid_pixels(wide.size, 61, 41)
    rays, valid = wide.unproject(grid, normalize=True)
    mrcal_rays = mrcal.unproject(grid, "LENSMODEL_OPENCV8", intrinsics, normalize=True)
    assert valid.all()
    # Both reproject to the pixel; libcam's exactly.
    assert np.abs(mrcal.project(rays, "LENSMODEL_OPENCV8", intrinsics) - grid).max() < 1e-8
    assert np.median(np.linalg.norm(rays - mrcal_rays, axis=-1)) < 1e-7


def test_real_cameramodel_against_mrcal():
    path = real_camera("mrcal/opencv8-1.cameramodel")
    model = mrcal.cameramodel(str(path))
    lensmodel, intrinsics = model.intrinsics()
    camera = libcam.read(str(path))
    assert camera.model == "OPENCV8"
    assert np.array_equal(camera.dist, intrinsics[4:])
    assert (camera.K[0, 0], camera.K[1, 1], camera.K[0, 2], camera.K[1, 2]) == tuple(intrinsics[:4])
    # World points (the model has extrinsics: rt_cam_ref) through both.
    points = points_in_front(2000, seed=7, spread=1.0) + np.array([2.0, 0.1, 0.0])
    pixels, valid = camera.project(points)
    reference = mrcal.project(mrcal.transform_point_rt(model.extrinsics_rt_fromref(), points), lensmodel, intrinsics)
    assert np.abs(pixels[valid] - reference[valid]).max() < 1e-7
    assert valid.mean() > 0.9


def test_real_opencv_xml_against_cv2_filestorage():
    path = real_camera("opencv-calib-sample-outputs/fisheye_cali/out_camera_data.xml")
    storage = cv2.FileStorage(str(path), cv2.FILE_STORAGE_READ)
    K = storage.getNode("camera_matrix").mat()
    dist = storage.getNode("distortion_coefficients").mat().ravel()
    size = (int(storage.getNode("image_width").real()), int(storage.getNode("image_height").real()))
    camera = libcam.read(str(path))
    assert np.array_equal(camera.K, K)
    assert np.array_equal(camera.dist, dist)
    assert camera.size == size


def test_real_kannala_brandt_against_cv2_fisheye():
    camera = libcam.read(str(real_camera("basalt/t265_kb4_calib.json")), camera="1")
    assert camera.model == "FISHEYE"
    grid = grid_pixels(camera.size, 60, 60)
    rays, valid = camera.unproject(grid)
    front = valid & (rays[:, 2] > 0)  # cv2.fisheye: points in front of the camera only
    assert front.sum() > 2000
    back, _ = cv2.fisheye.projectPoints(rays[front].reshape(-1, 1, 3), np.zeros(3), np.zeros(3), camera.K, camera.dist)
    assert np.abs(back.reshape(-1, 2) - grid[front]).max() < 1e-8


# ---------------------------------------------------------------------------- shapes

def test_shapes(wide):
    points = points_in_front(24).reshape(2, 3, 4, 3)
    pixels, valid = wide.project(points)
    assert pixels.shape == (2, 3, 4, 2) and valid.shape == (2, 3, 4)
    flat, _ = wide.project(points.reshape(-1, 3))
    assert bits_equal(pixels.reshape(-1, 2), flat)
    one, one_valid = wide.project(points[0, 0, 0])
    assert one.shape == (2,) and one_valid.shape == () and bits_equal(one, flat[0])
    empty, empty_valid = wide.project(np.zeros((0, 3)))
    assert empty.shape == (0, 2) and empty_valid.shape == (0,)
    directions, valid = wide.unproject(np.zeros((0, 2)))
    assert directions.shape == (0, 3)


def test_views_are_read_where_they_lie(wide):
    points = points_in_front(1000)
    wider = np.zeros((1000, 5))
    wider[:, 1:4] = points
    view = wider[:, 1:4]  # rows 40 bytes apart
    assert not view.flags.c_contiguous
    pixels, _ = wide.project(view)
    expected, _ = wide.project(points)
    assert bits_equal(pixels, expected)
    every_other, _ = wide.project(points[::2])
    assert bits_equal(every_other, expected[::2])
    fortran = np.asfortranarray(points)
    assert bits_equal(wide.project(fortran)[0], expected)
    transposed = np.ascontiguousarray(points.T).T  # coordinates 8000 bytes apart
    assert bits_equal(wide.project(transposed)[0], expected)
    reversed_rows = points[::-1]
    assert bits_equal(wide.project(reversed_rows)[0], expected[::-1])
    grid = np.stack(np.meshgrid(np.arange(0, 6016, 97.0), np.arange(0, 4016, 101.0)), axis=-1)  # (H, W, 2)
    rays, valid = wide.unproject(grid.transpose(1, 0, 2))  # not collapsible: copied
    flat, _ = wide.unproject(grid.transpose(1, 0, 2).reshape(-1, 2))
    assert bits_equal(rays.reshape(-1, 3), flat)


def test_points_in_columns_give_pixels_in_columns(wide):
    """A (3, N) array's .T is read where it lies, and its pixels come back laid out the same way."""
    points = points_in_front(3000, seed=11)
    points[::7] = (0.3, 0.1, -1.0)  # behind the camera: invalid
    for frame in ("camera", "world"):  # in place; and through the pose
        expected, expected_valid = wide.project(points, frame=frame)
        assert not expected_valid.all()
        rows = np.ascontiguousarray(points.T)
        pixels, valid = wide.project(rows.T, frame=frame)
        assert pixels.shape == (3000, 2) and pixels.T.flags.c_contiguous
        assert bits_equal(pixels, expected) and np.array_equal(valid, expected_valid)
        assert np.isnan(pixels[~valid]).all()
        single, _ = wide.project(np.asfortranarray(points.astype(np.float32)), frame=frame)
        assert single.T.flags.c_contiguous
        assert bits_equal(single, wide.project(points.astype(np.float32), frame=frame)[0])
    # An image of points as a (3, H, W) array: pixels as a (2, H, W) array, moved.
    expected, _ = wide.project(points, frame="camera")
    planes = np.ascontiguousarray(np.moveaxis(points.reshape(50, 60, 3), -1, 0))
    pixels, valid = wide.project(np.moveaxis(planes, 0, -1), frame="camera")
    assert pixels.shape == (50, 60, 2) and np.moveaxis(pixels, -1, 0).flags.c_contiguous
    assert bits_equal(pixels, expected.reshape(50, 60, 2))
    # out= in either layout, from points in either layout.
    for given in (points, rows.T):
        for out in (np.empty((3000, 2)), np.empty((2, 3000)).T):
            mask = np.empty(3000, dtype=bool)
            wide.project(given, frame="camera", out=(out, mask))
            assert bits_equal(out, expected)
    # A bottom-left pixel origin flips the rows' column too.
    flipped = libcam.from_fov(70, (640, 480), pixel_origin="bottom-left")
    near = points_in_front(500, seed=3, spread=0.5)
    expected, expected_valid = flipped.project(near, frame="camera")
    assert expected_valid.all()
    assert bits_equal(flipped.project(np.ascontiguousarray(near.T).T, frame="camera")[0], expected)


def test_lists_and_integers_become_float64(wide):
    from_list, _ = wide.project([[0.1, 0.2, 1.0], [0.0, 0.0, 2.0]])
    assert from_list.dtype == np.float64
    pixels_int = np.array([[0, 0], [3000, 2000]], dtype=np.int32)
    rays_int, _ = wide.unproject(pixels_int)
    rays_float, _ = wide.unproject(pixels_int.astype(np.float64))
    assert bits_equal(rays_int, rays_float)


def test_ray_image(wide):
    small = wide.binned(16)  # 376x251
    rays, valid = small.ray_image()
    assert rays.shape == (251, 376, 3) and valid.shape == (251, 376)
    ys, xs = np.mgrid[0:251, 0:376]
    expected, expected_valid = small.unproject(np.stack([xs, ys], axis=-1).astype(np.float64))
    assert bits_equal(rays, expected) and np.array_equal(valid, expected_valid)
    world, _ = small.ray_image(frame="world", dtype=np.float32)
    assert world.dtype == np.float32 and np.allclose(np.linalg.norm(world, axis=-1), 1, atol=1e-6)


def test_gil_is_released_during_a_batch(wide):
    pixels = grid_pixels(wide.size, 1500, 1000)
    wide.unproject(pixels[:10])  # the table, built once
    progress = []
    done = threading.Event()

    def count():
        while not done.is_set():
            progress.append(time.perf_counter())
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    # As many batches as it takes to last a tenth of a second, however fast the machine. A
    # thread that holds the GIL through a batch lets the counter in at most once per batch
    # (between two bytecodes around the call); a batch that releases it, once a millisecond.
    calls = []
    while sum(end - start for start, end in calls) < 0.1:
        start = time.perf_counter()
        wide.unproject(pixels, method="exact")
        calls.append((start, time.perf_counter()))
    done.set()
    counter.join()
    inside = sum(1 for t in progress if any(start < t < end for start, end in calls))
    assert inside > 2 * len(calls) + 5, "another Python thread did not run while libcam computed"


# ----------------------------------------------------------------------- conventions

def test_from_fov_is_the_look_at_formula():
    # The worked example: eye (0, 5, 5) looking at the origin, 90 degrees, 3x3. The look-at
    # formula's d at pixel (0, 0), rows counted from the bottom, is
    # (-2/3, -sqrt2/3 - 1/sqrt2, sqrt2/3 - 1/sqrt2) (worked by hand).
    camera = libcam.from_fov(90, (3, 3), eye=(0, 5, 5), target=(0, 0, 0), pixel_origin="bottom-left")
    rays, valid = camera.rays([[0.0, 0.0]])
    s = math.sqrt(2)
    d = np.array([-2 / 3, -s / 3 - 1 / s, s / 3 - 1 / s])
    assert valid.all() and np.abs(rays[0] - d / np.linalg.norm(d)).max() < 1e-15
    # The same camera in OpenCV's pixels: that pixel is (0, 2).
    opencv = libcam.from_fov(90, (3, 3), eye=(0, 5, 5), target=(0, 0, 0))
    assert np.abs(opencv.rays([[0.0, 2.0]])[0][0] - rays[0]).max() == 0
    # And projecting the eye's forward point gives the centre; in both conventions.
    centre, _ = camera.project([0.0, 0.0, 0.0])
    assert np.abs(centre - [1.0, 1.0]).max() < 1e-12
    assert camera.pixel_origin == "bottom-left"
    # A horizontal 60 degrees on 1920x1080: fx = 960 / tan(30 degrees).
    render = libcam.from_fov(60, (1920, 1080), axis="horizontal")
    assert abs(render.K[0, 0] - 960 / math.tan(math.radians(30))) < 1e-9
    assert abs(render.fov["horizontal"] - 60) < 1e-12


def test_from_opencv_and_pose():
    K = np.array([[500.0, 0, 319.5], [0, 500, 239.5], [0, 0, 1]])
    rvec, tvec = np.array([0.2, -0.1, 0.3]), np.array([0.5, -1.0, 4.0])
    camera = libcam.from_opencv(K, np.array([[0.1, -0.05, 0.001, 0.002, 0.01]]), (640, 480), rvec=rvec, tvec=tvec)
    assert camera.model == "OPENCV5"
    R, _ = cv2.Rodrigues(rvec)
    assert np.abs(camera.R - R).max() < 1e-15 and np.array_equal(camera.t, tvec)
    assert np.abs(camera.center + R.T @ tvec).max() < 1e-15
    points = points_in_front(500, seed=8, spread=0.5)
    reference, _ = cv2.projectPoints(points, rvec, tvec, K, camera.dist)
    pixels, valid = camera.project(points)
    assert np.abs(pixels[valid] - reference.reshape(-1, 2)[valid]).max() < 1e-9


def test_to_gl_is_the_projection_worked_by_hand():
    camera = libcam.from_opencv(np.array([[400.0, 0, 300], [0, 420, 200], [0, 0, 1]]), None, (640, 480))
    gl = camera.to_gl(0.1, 100)
    n, f = 0.1, 100.0
    W, H = 640, 480
    expected = np.array([[2 * 400 / W, 0, 1 - (2 * 300 + 1) / W, 0],
                         [0, 2 * 420 / H, (2 * 200 + 1) / H - 1, 0],
                         [0, 0, -(f + n) / (f - n), -2 * f * n / (f - n)],
                         [0, 0, -1, 0]])
    assert np.abs(gl["projection"] - expected).max() < 1e-15
    assert gl["viewport"] == (0, 0, 640, 480)


def test_to_blender():
    camera = libcam.from_fov(60, (1920, 1080), axis="horizontal")
    blender = camera.to_blender()["cameras"][0]
    assert blender["type"] == "PERSP" and blender["resolution_x"] == 1920
    # Blender's angle across the sensor width: 2 atan(sensor / (2 lens)).
    assert abs(2 * math.degrees(math.atan(blender["sensor_width"] / (2 * blender["lens"]))) - 60) < 1e-9


def test_write_and_read_back(wide, tmp_path):
    for name, format in [("wide.yaml", None), ("wide.xml", None), ("wide.cameramodel", None), ("wide.txt", "json")]:
        path = tmp_path / name
        wide.write(str(path), format=format)
        assert libcam.read(str(path), format=format) == wide
    text = wide.format("opencv-yaml")
    assert "camera_matrix" in text


def test_read_all_names_each_camera():
    cameras = libcam.read_all(str(real_camera("open_vins/euroc_mav/kalibr_imucam_chain.yaml")))
    assert list(cameras) == ["cam0", "cam1"]


def test_remap_map_for_cv2_remap(fisheye):
    target, why = libcam.new_camera(fisheye, keep="valid")
    assert target.model == "PINHOLE" and why
    coordinates, valid = libcam.remap_map(target, fisheye)
    width, height = target.size
    assert coordinates.shape == (height, width, 2) and coordinates.dtype == np.float32
    assert valid.all()  # keep="valid": every target pixel has a source
    # Independent: the target pixel's pinhole ray (K^-1 by numpy) through cv2.fisheye.
    ys, xs = np.mgrid[0:height:37, 0:width:41]
    rays = np.stack([(xs - target.K[0, 2]) / target.K[0, 0], (ys - target.K[1, 2]) / target.K[1, 1], np.ones(xs.shape)], -1)
    expected, _ = cv2.fisheye.projectPoints(rays.reshape(-1, 1, 3), np.zeros(3), np.zeros(3), fisheye.K, fisheye.dist)
    assert np.abs(coordinates[ys, xs].reshape(-1, 2) - expected.reshape(-1, 2)).max() < 1e-3
    # cv2.remap takes it as it is; where there is no source (NaN) it gives the border value.
    wider, _ = libcam.new_camera(fisheye, keep="all")
    coordinates, valid = libcam.remap_map(wider, fisheye)
    assert not valid.all() and np.isnan(coordinates[~valid]).all()
    image = np.full((fisheye.size[1], fisheye.size[0]), 200, np.uint8)
    out = cv2.remap(image, coordinates, None, cv2.INTER_LINEAR, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    assert (out[~valid] == 0).all()
    inner = valid.copy()
    inner[1:-1, 1:-1] &= valid[:-2, 1:-1] & valid[2:, 1:-1] & valid[1:-1, :-2] & valid[1:-1, 2:]
    assert (out[inner & (cv2.erode(inner.astype(np.uint8), np.ones((5, 5))) > 0)] == 200).all()


def test_verify_and_fit(wide):
    report = libcam.verify(wide.binned(8), grid=(20, 15), threads=1)
    assert report["pass"] and report["model"] == "OPENCV8"
    names = [check["name"] for check in report["checks"]]
    assert "project-opencv" in names and "project-mrcal" in names
    project_opencv = report["checks"][names.index("project-opencv")]
    assert project_opencv["stats"]["max_px"] < project_opencv["tolerance_px"]
    # A graphics camera is exactly the look-at model: the simplest candidate reproduces it.
    render = libcam.from_fov(70, (320, 240), axis="horizontal")
    fitted = libcam.fit(render, tolerance=0.01)
    assert fitted["chosen"]["model"] == "LOOK_AT"
    assert fitted["chosen"]["max_px"] < 1e-6
    assert abs(fitted["chosen"]["camera"].fov["horizontal"] - 70) < 1e-6


# ---------------------------------------------------------------------------- errors

def test_wrong_shapes_and_types_are_type_errors(wide):
    with pytest.raises(TypeError, match=r"points: expected an array of shape \(\.\.\., 3\), got shape \(4, 2\)"):
        wide.project(np.zeros((4, 2)))
    with pytest.raises(TypeError, match=r"pixels: expected a float32 or float64 array of shape \(\.\.\., 2\), got complex128"):
        wide.unproject(np.zeros((4, 2), dtype=complex))
    with pytest.raises(TypeError, match="pixels"):
        wide.unproject("not pixels")
    with pytest.raises(TypeError, match=r"shape \(\)"):
        wide.project(np.float64(1.0))
    with pytest.raises(TypeError, match="K: expected a 3x3"):
        libcam.from_opencv(np.eye(4), None, (640, 480))
    with pytest.raises(TypeError, match="dtype"):
        wide.ray_image(dtype=np.int32)


def test_bad_values_are_libcam_errors_naming_the_field(wide, tmp_path):
    with pytest.raises(libcam.Error, match="method: expected 'exact', 'fast' or 'lut', got 'newton'"):
        wide.unproject([[0.0, 0.0]], method="newton")
    with pytest.raises(ValueError, match="K"):  # libcam.Error is a ValueError
        libcam.from_opencv(np.array([[-500.0, 0, 320], [0, 500, 240], [0, 0, 1]]), None, (640, 480))
    with pytest.raises(libcam.Error, match="dist: OpenCV takes 4, 5, 8, 12 or 14 coefficients, got 3"):
        libcam.from_opencv(np.eye(3), [0.1, 0.2, 0.3], (640, 480))
    with pytest.raises(libcam.Error, match="fov"):
        libcam.from_fov(180, (640, 480))
    with pytest.raises(libcam.Error, match="model: unknown lens model 'OPENCV9'"):
        libcam.Camera(np.eye(3), (10, 10), model="OPENCV9")
    with pytest.raises(libcam.Error, match="size"):
        libcam.from_fov(60, (0, 480))
    with pytest.raises(libcam.Error, match="threads"):
        wide.project([[0.0, 0.0, 1.0]], threads=-1)
    with pytest.raises(libcam.Error, match="frame"):
        wide.project([[0.0, 0.0, 1.0]], frame="screen")
    with pytest.raises(libcam.NotRepresentable):
        wide.to_blender()
    with pytest.raises(libcam.Error, match="PINHOLE"):
        wide.to_gl(0.1, 10)
    with pytest.raises(libcam.Error, match="keep"):
        libcam.new_camera(wide, keep="some")


def test_file_errors_name_the_file(tmp_path):
    missing = tmp_path / "missing.yaml"
    with pytest.raises(libcam.FileError, match="missing.yaml"):
        libcam.read(str(missing))
    broken = tmp_path / "broken.json"
    broken.write_text('{"model": "OPENCV5", "image_size": [640, 480], "K": [[1, 0, 0], [0, 1, 0], [0, 0, 1]], "dist": [1, 2]}')
    with pytest.raises(libcam.Error, match=r"broken\.json.*dist"):
        libcam.read(str(broken))
    camera = libcam.from_fov(60, (640, 480))
    with pytest.raises(libcam.FileError, match="no format given"):
        camera.write(str(tmp_path / "camera.unknown"))
    with pytest.raises(libcam.Error, match="format"):
        camera.write(str(tmp_path / "camera.json"), format="png")
    assert not (tmp_path / "camera.json").exists()


def test_out_arrays_are_written_in_place(wide):
    points = points_in_front(2000, seed=9)
    expected, expected_valid = wide.project(points)
    pixels, valid = np.empty((2000, 2)), np.empty(2000, dtype=bool)
    returned = wide.project(points, out=(pixels, valid))
    assert returned[0] is pixels and returned[1] is valid
    assert bits_equal(pixels, expected) and np.array_equal(valid, expected_valid)
    grid = grid_pixels(wide.size, 50, 40)
    directions = np.empty((2000, 3))
    wide.unproject(grid, out=(directions, valid))
    assert bits_equal(directions, wide.unproject(grid)[0])
    with pytest.raises(TypeError, match=r"out\[0\]: expected a writeable float64 array of shape \(2000, 2\), C-ordered or"):
        wide.project(points, out=(np.empty((2000, 3)), valid))
    with pytest.raises(TypeError, match=r"out\[0\]: expected a writeable float64 array of shape \(2000, 2\), C-ordered or"):
        wide.project(points, out=(np.empty((2000, 4))[:, 1:3], valid))  # neither layout
    with pytest.raises(TypeError, match=r"out\[0\]: expected a writeable float64 array of shape \(2000, 3\), C-ordered, got"):
        wide.unproject(grid, out=(np.empty((3, 2000)).T, valid))  # columns: projection only
    with pytest.raises(TypeError, match=r"out\[1\]: expected a C-ordered, writeable bool array"):
        wide.project(points, out=(pixels, np.empty(2000)))
    with pytest.raises(TypeError, match="out: expected"):
        wide.project(points, out=pixels)
    with pytest.raises(TypeError, match="float32"):
        wide.project(points.astype(np.float32), out=(pixels, valid))
    # Results written over their own input would be read back as input: refused.
    shared = np.zeros((2000, 3))
    shared[:] = points
    with pytest.raises(TypeError, match="must not share memory with the input"):
        wide.project(shared, out=(shared.reshape(-1)[:4000].reshape(2000, 2), valid))


def test_type_stubs_match_the_module():
    """Every function and method of the stubs exists with the same parameter names."""
    import ast
    import pathlib
    import re
    stub = ast.parse((pathlib.Path(libcam.__file__).parent / "__init__.pyi").read_text())

    def pybind_parameters(function):
        first_line = function.__doc__.splitlines()[0]
        inside = first_line[first_line.index("(") + 1:first_line.rindex(")")]
        parts, depth, current = [], 0, ""
        for character in inside:  # split at the commas outside brackets
            depth += character in "([" and 1 or 0
            depth -= character in ")]" and 1 or 0
            if character == "," and depth == 0:
                parts.append(current)
                current = ""
            else:
                current += character
        parts.append(current)
        return [re.split(r"[:=]", part.strip())[0].strip() for part in parts if part.strip()]

    def stub_parameters(node):
        return [a.arg for a in node.args.args]

    checked = 0
    for node in stub.body:
        if isinstance(node, ast.FunctionDef):
            assert stub_parameters(node) == pybind_parameters(getattr(libcam, node.name)), node.name
            checked += 1
        if isinstance(node, ast.ClassDef) and node.name == "Camera":
            for member in node.body:
                if isinstance(member, ast.FunctionDef) and not member.decorator_list:
                    function = getattr(libcam.Camera, member.name)
                    names = pybind_parameters(function)
                    assert stub_parameters(member) == names, member.name
                    checked += 1
                elif isinstance(member, ast.FunctionDef):
                    assert isinstance(getattr(libcam.Camera, member.name), property), member.name
    assert checked >= 19
    assert sorted(name for name in libcam.__all__) == sorted(
        [n.name for n in stub.body if isinstance(n, (ast.FunctionDef, ast.ClassDef)) and n.name not in ("ModelInfo", "CheckStats", "VerifyCheck")]
        + ["__version__", "models", "formats"])


def test_every_instruction_set_gives_the_same_bits(wide):
    """The batch kernels on each set this CPU runs: the same pixels and rays, bit for bit."""
    targets = libcam.supported_simd_targets()
    assert targets[0] == "sse2"
    assert libcam.simd_target() in targets
    rng = np.random.default_rng(7)
    pixels = rng.uniform(0, 1, (4000, 2)) * np.array(wide.size)
    results = []
    try:
        for target in targets:
            libcam.set_simd_target(target)
            assert libcam.simd_target() == target
            rays, valid = wide.unproject(pixels)
            projected, projected_valid = wide.project(rays[valid], frame="camera")
            results.append((rays.tobytes(), valid.tobytes(), projected.tobytes(), projected_valid.tobytes()))
    finally:
        libcam.set_simd_target(None)
    assert all(result == results[0] for result in results)
    with pytest.raises(libcam.Error, match="avx3"):
        libcam.set_simd_target("avx3")
