#!/usr/bin/env python3
"""`libcam rectify` with images beside a Python script doing the same with cv2, both as
whole programs: read OpenCV's stereo files and the two PNGs, rectify (cv2.stereoRectify,
two cv2.initUndistortRectifyMap, two cv2.remap), write the two rectified PNGs.

The pair: OpenCV's sample stereo images (left01.jpg, right01.jpg) scaled to 1280x960, with a
narrow OPENCV5 pair's calibration at that size; random noise images when the samples are
absent. A benchmark, not a test: it prints the times.

Usage: rectify_vs_cv2.py LIBCAM [OPENCV_STEREO_SAMPLES_FOLDER] [RUNS]
"""

import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import cv2
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "peers"))
from opencv_stereo import write_stereo_files  # noqa: E402

CV2_SCRIPT = r'''
import sys
import cv2
intrinsics, extrinsics, left, right, out = sys.argv[1:]
fs = cv2.FileStorage(intrinsics, cv2.FILE_STORAGE_READ)
K1, D1, K2, D2 = (fs.getNode(k).mat() for k in ("M1", "D1", "M2", "D2"))
fs = cv2.FileStorage(extrinsics, cv2.FILE_STORAGE_READ)
R, T = fs.getNode("R").mat(), fs.getNode("T").mat()
images = [cv2.imread(p, cv2.IMREAD_UNCHANGED) for p in (left, right)]
size = (images[0].shape[1], images[0].shape[0])
R1, R2, P1, P2, Q, _, _ = cv2.stereoRectify(K1, D1, K2, D2, size, R, T, alpha=0)
for image, K, D, Rk, Pk, name in ((images[0], K1, D1, R1, P1, "left.png"), (images[1], K2, D2, R2, P2, "right.png")):
    map_x, map_y = cv2.initUndistortRectifyMap(K, D, Rk, Pk, size, cv2.CV_32FC1)
    cv2.imwrite(out + "/" + name, cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR))
'''


def timed(command, runs):
    """Median and best wall time, and median CPU time (user + system), of whole runs."""
    times, cpu = [], []
    for _ in range(runs):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        times.append(time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
    return statistics.median(times), min(times), statistics.median(cpu)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    libcam = sys.argv[1]
    samples = sys.argv[2] if len(sys.argv) > 2 else ""
    runs = int(sys.argv[3]) if len(sys.argv) > 3 else 10
    work = tempfile.mkdtemp(prefix="rectify-bench-")
    size = (1280, 960)
    images = []
    for side in ("left", "right"):
        path = os.path.join(samples, f"{side}01.jpg")
        if os.path.isfile(path):
            image = cv2.resize(cv2.imread(path, cv2.IMREAD_UNCHANGED), size, interpolation=cv2.INTER_CUBIC)
        else:
            image = np.random.default_rng(1).integers(0, 255, (size[1], size[0]), dtype=np.uint8)
        images.append(os.path.join(work, f"{side}.png"))
        cv2.imwrite(images[-1], image)
    K1 = np.array([[1040.0, 0, 637.0], [0, 1032.0, 486.5], [0, 0, 1]])
    K2 = np.array([[1024.0, 0, 650.0], [0, 1021.0, 473.0], [0, 0, 1]])
    D1 = np.array([-0.21, 0.06, 8e-4, -5e-4, -0.012])
    D2 = np.array([-0.19, 0.045, -3e-4, 6e-4, -0.004])
    R, _ = cv2.Rodrigues(np.array([0.012, -0.018, 0.006]))
    T = (-R @ np.array([0.12, 0.004, -0.003])).reshape(3, 1)
    intrinsics, extrinsics = write_stereo_files(cv2, work, "bench", K1, D1, K2, D2, R, T)
    script = os.path.join(work, "cv2_rectify.py")
    with open(script, "w") as f:
        f.write(CV2_SCRIPT)
    os.makedirs(os.path.join(work, "cv2-out"))
    commands = {
        "libcam rectify": [libcam, "rectify", intrinsics, extrinsics, "--images"] + images +
                          ["-o", os.path.join(work, "libcam-out"), "--to", "pinhole"],
        "python3 + cv2": [sys.executable, script, intrinsics, extrinsics] + images + [os.path.join(work, "cv2-out")],
    }
    print(f"{size[0]}x{size[1]} pair, {runs} runs each, load average {os.getloadavg()[0]:.2f}")
    for name, command in commands.items():
        median, best, cpu = timed(command, runs)
        print(f"{name:16s} wall median {median * 1000:7.1f} ms, best {best * 1000:7.1f} ms; CPU median {cpu * 1000:7.1f} ms")


if __name__ == "__main__":
    main()
