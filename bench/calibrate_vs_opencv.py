#!/usr/bin/python3
"""Times `libcam calibrate` against OpenCV's own pipeline on the same board images, both as
whole programs, alternating, in one run.

    /usr/bin/python3 bench/calibrate_vs_opencv.py [--libcam build/tools/libcam] [--images 20]
        [--size 1280x960] [--threads 1] [--repeat 3] [--keep DIR]

The images are made here: a 9x6 chessboard (30 mm squares) through an OPENCV5 lens (f 1040
px, k1 -0.30, k2 0.10, k3 0.10, small tangential terms), in poses that spread the corners
over the image, each pixel the mean of four samples, blurred a little and with noise of 2
grey levels; PNG. The two programs:

- opencv: a Python program that reads each image (cv2.imread, greyscale), finds the board
  (cv2.findChessboardCornersSB, CALIB_CB_ACCURACY | CALIB_CB_EXHAUSTIVE, as libcam asks)
  and calibrates once (cv2.calibrateCamera, its default model: k1 k2 p1 p2 k3), with
  OpenCV's threads set to `--threads`;
- libcam: `libcam calibrate DIR --board chessboard:9x6:0.03 --model OPENCV5 --threads N
  --json`: the same detection, each corner refined again by cornerSubPix, the fit on every
  view and, as every libcam calibration does, the views held out in 5 folds (5 more fits),
  outliers looked for.

The best wall time of each over `--repeat` runs, and libcam's over OpenCV's.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time

import cv2
import numpy as np

OPENCV_PROGRAM = r"""
import sys, glob, cv2, numpy as np
cv2.setNumThreads(int(sys.argv[2]))
pattern = (9, 6)
board = np.zeros((54, 3), np.float32)
board[:, :2] = np.mgrid[0:9, 0:6].T.reshape(-1, 2) * 0.03
object_points, image_points, size = [], [], None
for path in sorted(glob.glob(sys.argv[1] + "/*.png")):
    grey = cv2.imread(path, cv2.IMREAD_GRAYSCALE)
    size = grey.shape[::-1]
    found, corners = cv2.findChessboardCornersSB(grey, pattern, flags=cv2.CALIB_CB_ACCURACY | cv2.CALIB_CB_EXHAUSTIVE)
    if found:
        object_points.append(board)
        image_points.append(corners)
rms, K, dist, _, _ = cv2.calibrateCamera(object_points, image_points, size, None, None)
print(len(image_points), rms, K[0, 0], K[1, 1], K[0, 2], K[1, 2])
"""


def rotation(tilt):
    return cv2.Rodrigues(np.asarray(tilt, np.float64))[0]


def render(size, K, dist, R, t, square):
    """The 9x6-corner board (10x7 squares and a white margin) at board-to-camera (R, t)."""
    width, height = size
    # Every sub-pixel's ray (two by two per pixel), through the lens's exact inverse.
    xs = (np.arange(2 * width) + 0.5) / 2 - 0.5
    ys = (np.arange(2 * height) + 0.5) / 2 - 0.5
    grid = np.stack(np.meshgrid(xs, ys), -1).reshape(-1, 1, 2).astype(np.float64)
    rays = cv2.undistortPointsIter(grid, K, dist, None, None,
                                   (cv2.TERM_CRITERIA_COUNT | cv2.TERM_CRITERIA_EPS, 50, 1e-12)).reshape(-1, 2)
    rays = np.concatenate([rays, np.ones((len(rays), 1))], 1)
    # The board's plane z = 0: X = R^T (s ray - t), its z zero.
    Rt = R.T
    centre = -Rt @ t
    directions = rays @ Rt.T
    s = -centre[2] / directions[:, 2]
    on_board = centre[None, :2] + s[:, None] * directions[:, :2]
    # Inner corner (i, j) at (i, j) squares: the squares -1..8 across and -1..5 down, in
    # a white margin of one square, grey beyond it and behind the camera.
    u = np.floor(on_board[:, 0] / square)
    v = np.floor(on_board[:, 1] / square)
    colour = np.where((u + v) % 2 == 0, 20.0, 255.0)
    colour[(u < -1) | (u > 8) | (v < -1) | (v > 5)] = 255.0
    colour[(u < -2) | (u > 9) | (v < -2) | (v > 6) | (s <= 0)] = 128.0
    image = colour.reshape(2 * height, 2 * width)
    image = image.reshape(height, 2, width, 2).mean(axis=(1, 3))
    image = cv2.GaussianBlur(image, (0, 0), 0.7)
    image += np.random.default_rng(1).normal(0, 2.0, image.shape)
    return np.clip(image, 0, 255).astype(np.uint8)


def make_images(folder, count, size):
    width, height = size
    K = np.array([[1040.0, 0, width / 2 - 0.5 + 4.6], [0, 1044.0, height / 2 - 0.5 + 3.4], [0, 0, 1]])
    dist = np.array([-0.30, 0.10, 0.0012, -0.0008, 0.10])
    rng = np.random.default_rng(7)
    made = 0
    while made < count:
        tilt = rng.uniform(-0.5, 0.5, 3) * np.array([1, 1, 0.4])
        centre = np.array([rng.uniform(-0.1, 0.1), rng.uniform(-0.07, 0.07), rng.uniform(0.4, 0.6)])
        R = rotation(tilt)
        # The board's middle at `centre`.
        t = centre - R @ np.array([4 * 0.03, 2.5 * 0.03, 0])
        corners = np.mgrid[0:9, 0:6].T.reshape(-1, 2) * 0.03
        projected, _ = cv2.projectPoints(np.concatenate([corners, np.zeros((54, 1))], 1), cv2.Rodrigues(R)[0], t, K, dist)
        projected = projected.reshape(-1, 2)
        if (projected.min() < 20 or projected[:, 0].max() > width - 20 or projected[:, 1].max() > height - 20):
            continue
        cv2.imwrite(os.path.join(folder, "view%02d.png" % made), render(size, K, dist, R, t, 0.03))
        made += 1


def timed(command):
    start = time.perf_counter()
    result = subprocess.run(command, capture_output=True, text=True)
    elapsed = time.perf_counter() - start
    if result.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(command), result.stderr))
    return elapsed, result.stdout


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--libcam", default="build/tools/libcam")
    parser.add_argument("--images", type=int, default=20)
    parser.add_argument("--size", default="1280x960")
    parser.add_argument("--threads", type=int, default=1)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--keep", help="make the images in this folder and keep them")
    args = parser.parse_args()
    size = tuple(int(n) for n in args.size.split("x"))
    folder = args.keep or tempfile.mkdtemp(prefix="libcam_calibrate_bench_")
    os.makedirs(folder, exist_ok=True)
    try:
        if not any(name.endswith(".png") for name in os.listdir(folder)):
            make_images(folder, args.images, size)
        libcam = [args.libcam, "calibrate", folder, "--board", "chessboard:9x6:0.03", "--model", "OPENCV5",
                  "--threads", str(args.threads), "--json", "--progress", "never"]
        opencv = [sys.executable, "-c", OPENCV_PROGRAM, folder, str(args.threads)]
        best = {"libcam": float("inf"), "opencv": float("inf")}
        for _ in range(args.repeat):
            for name, command in (("opencv", opencv), ("libcam", libcam)):
                elapsed, out = timed(command)
                best[name] = min(best[name], elapsed)
        print("opencv: %s" % out_line(opencv))
        print("%d images of %s, %d thread(s), best of %d" % (args.images, args.size, args.threads, args.repeat))
        print("opencv (findChessboardCornersSB + calibrateCamera)  %.2f s" % best["opencv"])
        print("libcam calibrate --model OPENCV5                    %.2f s  (%.2fx OpenCV's)"
              % (best["libcam"], best["libcam"] / best["opencv"]))
    finally:
        if not args.keep:
            shutil.rmtree(folder)


def out_line(command):
    return subprocess.run(command, capture_output=True, text=True).stdout.strip()


if __name__ == "__main__":
    main()
