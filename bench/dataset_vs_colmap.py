#!/usr/bin/python3
"""Times `libcam dataset` against `colmap image_undistorter` on the same dataset, in one run,
beside the images' own decoding and encoding alone (the floor both stand on).

    /usr/bin/python3 bench/dataset_vs_colmap.py [--libcam build/tools/libcam] [--images 24]
        [--size 1920x1080] [--threads 2] [--repeat 3] [--keep DIR]

The dataset is written here: one OPENCV camera (fx != fy, off-centre principal point,
k1 -0.12), N JPEG photos of a textured pattern (OpenCV's JPEG quality 95, what libcam
writes back), a COLMAP text model with the images' poses and no points. Each program runs
`--repeat` times, alternating; the best time of each is kept, with its peak memory
(/usr/bin/time's maximum resident set). Rows:

- codec: every image read and written again with OpenCV's imread/imencode (the same
  codec and settings as libcam), on `--threads` threads: no remap, no model; timed from
  the first image to the last (the Python interpreter's start is not counted, so this
  row is a little faster than a program doing the same would be).
- libcam (linear) and libcam (cubic): `libcam dataset MODEL --images DIR -o OUT
  --threads N [--interpolation linear]`. COLMAP's undistorter blends bilinearly.
- colmap: `colmap image_undistorter` (it runs one worker per core).

Images per second, and each row's time over codec's and over colmap's.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

import cv2
import numpy as np


def make_dataset(folder, count, width, height):
    images = os.path.join(folder, "images")
    model = os.path.join(folder, "model")
    os.makedirs(images, exist_ok=True)
    os.makedirs(model, exist_ok=True)
    rng = np.random.default_rng(7)
    y, x = np.mgrid[0:height, 0:width].astype(np.float32)
    for i in range(count):
        phase = 0.3 * i
        base = 128 + 50 * np.sin(x / 23.0 + phase) * np.cos(y / 31.0) + 40 * np.sin((x + y) / 7.0 + phase)
        noise = rng.normal(0, 12, (height, width)).astype(np.float32)
        picture = np.clip(np.stack([base + noise, base * 0.8 + noise, 255 - base + noise], axis=2), 0, 255)
        cv2.imwrite(os.path.join(images, "photo_%04d.jpg" % i), picture.astype(np.uint8), [cv2.IMWRITE_JPEG_QUALITY, 95])
    fx, fy = 0.8 * width, 0.78 * width
    with open(os.path.join(model, "cameras.txt"), "w") as out:
        out.write("1 OPENCV %d %d %.10g %.10g %.10g %.10g -0.12 0.03 0.0005 -0.0004\n"
                  % (width, height, fx, fy, 0.52 * width, 0.49 * height))
    with open(os.path.join(model, "images.txt"), "w") as out:
        for i in range(count):
            out.write("%d 1 0 0 0 %g 0 0 1 photo_%04d.jpg\n\n" % (i + 1, 0.1 * i, i))
    open(os.path.join(model, "points3D.txt"), "w").close()
    return model, images


def codec_pass(images, output, threads):
    os.makedirs(output, exist_ok=True)
    names = sorted(os.listdir(images))

    def one(name):
        image = cv2.imread(os.path.join(images, name), cv2.IMREAD_UNCHANGED)
        ok, data = cv2.imencode(os.path.splitext(name)[1], image)
        with open(os.path.join(output, name), "wb") as out:
            out.write(data.tobytes())

    cv2.setNumThreads(1)
    started = time.perf_counter()
    with ThreadPoolExecutor(threads) as pool:
        list(pool.map(one, names))
    # The interpreter's own start (importing numpy and OpenCV) is not the codec's time.
    sys.stderr.write("codec seconds %.6f\n" % (time.perf_counter() - started))


def timed(command):
    """Seconds and peak resident megabytes of one command (/usr/bin/time); a command that
    prints its own "codec seconds S" is timed by that."""
    started = time.perf_counter()
    result = subprocess.run(["/usr/bin/time", "-f", "%M"] + command, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    seconds = time.perf_counter() - started
    if result.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(command), result.stderr))
    lines = result.stderr.strip().splitlines()
    for line in lines:
        if line.startswith("codec seconds "):
            seconds = float(line.split()[-1])
    return seconds, int(lines[-1]) / 1024.0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--libcam", default="build/tools/libcam")
    parser.add_argument("--colmap", default=shutil.which("colmap") or "colmap")
    parser.add_argument("--images", type=int, default=24)
    parser.add_argument("--size", default="1920x1080")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--keep", help="make the dataset and outputs in this folder and keep them")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))
    folder = args.keep or tempfile.mkdtemp(prefix="libcam_dataset_bench_")
    try:
        model, images = make_dataset(folder, args.images, width, height)
        runs = {
            "codec": lambda out: [sys.executable, os.path.abspath(__file__), "--codec-only", images, out,
                                  str(args.threads)],
            "libcam (linear)": lambda out: [args.libcam, "dataset", model, "--images", images, "-o", out,
                                            "--threads", str(args.threads), "--interpolation", "linear"],
            "libcam (cubic)": lambda out: [args.libcam, "dataset", model, "--images", images, "-o", out,
                                           "--threads", str(args.threads)],
            "colmap": lambda out: [args.colmap, "image_undistorter", "--image_path", images, "--input_path", model,
                                   "--output_path", out, "--output_type", "COLMAP"],
        }
        best = {}
        for repeat in range(args.repeat):
            for name, command in runs.items():
                out = os.path.join(folder, "out_" + name.split()[0] + "_" + name.split()[-1].strip("()"))
                shutil.rmtree(out, ignore_errors=True)
                seconds, peak = timed(command(out))
                if name not in best or seconds < best[name][0]:
                    best[name] = (seconds, peak)
        print("%d images of %dx%d (JPEG), %d threads, best of %d runs each"
              % (args.images, width, height, args.threads, args.repeat))
        print("%-16s %8s %9s %9s %9s %10s" % ("", "seconds", "images/s", "/ codec", "/ colmap", "peak MB"))
        for name, (seconds, peak) in best.items():
            print("%-16s %8.2f %9.2f %9.2f %9.2f %10.0f" % (name, seconds, args.images / seconds,
                                                          seconds / best["codec"][0], seconds / best["colmap"][0], peak))
    finally:
        if not args.keep:
            shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    if len(sys.argv) == 5 and sys.argv[1] == "--codec-only":
        codec_pass(sys.argv[2], sys.argv[3], int(sys.argv[4]))
    else:
        main()
