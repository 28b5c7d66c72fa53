#!/usr/bin/env python3
"""libcam's undistortion against COLMAP's image_undistorter, on a real COLMAP camera.

COLMAP's program undistorts one synthetic image (smooth stripes, so that a shift of a
tenth of a pixel changes it by about a grey level) with the camera of a real COLMAP
model, choosing its own pinhole camera; `libcam remap --to` that camera (read from the
model COLMAP wrote) undistorts the same image. The two images must agree to the
rounding of their interpolations (COLMAP's bilinear weights are exact, cv::remap's come
in steps of 1/32 px): at most 2 grey levels on any pixel away from the border, 0.25 on
average.

Usage: remap_vs_colmap.py LIBCAM COLMAP REAL_CAMERAS_FOLDER WORK_FOLDER
Exits 77 (skipped) when COLMAP's program, numpy, cv2 or the real-cameras folder is absent.
"""

import os
import shutil
import subprocess
import sys

SKIP = 77
CAMERAS = "colmap-fiord-fisheye/cameras.txt"  # OPENCV_FISHEYE, 3264 x 3264
BORDER = 3          # pixels next to the image's edge, where the two clamp differently
MAX_LEVELS = 2.0
MEAN_LEVELS = 0.25


def stripes(width, height, np):
    """Smooth stripes across both axes, 0..255, as an 8-bit BGR image."""
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    value = 127.5 + 60 * np.sin(2 * np.pi * x / 37.0) + 60 * np.sin(2 * np.pi * y / 53.0 + 0.3)
    grey = np.clip(np.rint(value), 0, 255).astype(np.uint8)
    return np.dstack([grey, grey, grey])


def main():
    libcam, colmap, real_cameras, work = sys.argv[1:5]
    try:
        import numpy as np
        import cv2
    except ImportError as error:
        print(f"skipped: numpy and OpenCV's Python module are needed (python3-numpy, python3-opencv): {error}")
        return SKIP
    if not (os.path.isfile(colmap) and os.access(colmap, os.X_OK)):
        print(f"skipped: COLMAP's program is not installed (Debian's colmap package): {colmap}")
        return SKIP
    cameras_txt = os.path.join(real_cameras, CAMERAS)
    if not os.path.isfile(cameras_txt):
        print(f"skipped: the real-cameras folder {real_cameras} is absent")
        return SKIP
    shutil.rmtree(work, ignore_errors=True)
    model, images, colmap_out, libcam_out = (os.path.join(work, name) for name in ("model", "images", "colmap", "libcam"))
    for folder in (model, images):
        os.makedirs(folder)

    # A one-image COLMAP model with the real camera (its id and size from the file).
    camera_line = next(line for line in open(cameras_txt) if line.strip() and not line.startswith("#"))
    camera_id, _, width, height = camera_line.split()[:4]
    shutil.copy(cameras_txt, os.path.join(model, "cameras.txt"))
    with open(os.path.join(model, "images.txt"), "w") as out:
        out.write(f"1 1 0 0 0 0 0 0 {camera_id} stripes.png\n\n")
    open(os.path.join(model, "points3D.txt"), "w").close()
    cv2.imwrite(os.path.join(images, "stripes.png"), stripes(int(width), int(height), np))

    subprocess.run([colmap, "image_undistorter", "--image_path", images, "--input_path", model, "--output_path",
                    colmap_out, "--output_type", "COLMAP"], check=True, stdout=subprocess.DEVNULL)
    subprocess.run([libcam, "remap", "--from", cameras_txt, "--to", os.path.join(colmap_out, "sparse"),
                    "--interpolation", "linear", os.path.join(images, "stripes.png"), "-o", libcam_out],
                   check=True, stdout=subprocess.DEVNULL)
    theirs = cv2.imread(os.path.join(colmap_out, "images", "stripes.png"), cv2.IMREAD_UNCHANGED)
    ours = cv2.imread(os.path.join(libcam_out, "stripes.png"), cv2.IMREAD_UNCHANGED)
    if theirs is None or ours is None or theirs.shape != ours.shape:
        print(f"the images differ in size: COLMAP {None if theirs is None else theirs.shape}, "
              f"libcam {None if ours is None else ours.shape}")
        return 1
    inner = (slice(BORDER, -BORDER), slice(BORDER, -BORDER), 0)
    difference = np.abs(theirs[inner].astype(np.float64) - ours[inner].astype(np.float64))
    worst, mean = float(difference.max()), float(difference.mean())
    p999 = float(np.quantile(difference, 0.999))
    print(f"{CAMERAS}: undistorted to COLMAP's {ours.shape[1]}x{ours.shape[0]} pinhole; grey levels apart: "
          f"mean {mean:.3g}, 99.9% {p999:.3g}, worst {worst:.3g} (tolerance mean {MEAN_LEVELS}, worst {MAX_LEVELS})")
    return 0 if worst <= MAX_LEVELS and mean <= MEAN_LEVELS else 1


if __name__ == "__main__":
    sys.exit(main())
