#!/usr/bin/env python3
"""docs/images/rectify-opencv-sample.png: OpenCV's sample stereo pair (left01, right01)
rectified by `libcam rectify`, side by side, with a line every 40 rows: each chessboard
corner sits on the same row in both images.

The pair is calibrated here as OpenCV's stereo_calib sample does it (9x6 chessboard,
cv2.calibrateCamera for each camera, then cv2.stereoCalibrate), written as its
intrinsics.yml and extrinsics.yml, and rectified by libcam from those two files.

Usage: make-rectify-picture.py LIBCAM OPENCV_STEREO_SAMPLES_FOLDER [OUTPUT_PNG]
"""

import os
import subprocess
import sys
import tempfile

import cv2
import numpy as np


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    libcam, folder = sys.argv[1:3]
    output = sys.argv[3] if len(sys.argv) > 3 else os.path.join(os.path.dirname(__file__), "rectify-opencv-sample.png")
    pattern = (9, 6)
    board = np.zeros((pattern[0] * pattern[1], 3), np.float32)
    board[:, :2] = np.mgrid[0:pattern[0], 0:pattern[1]].T.reshape(-1, 2)
    objects, corners = [], ([], [])
    size = None
    for i in range(1, 15):
        names = [os.path.join(folder, f"{side}{i:02d}.jpg") for side in ("left", "right")]
        if not all(os.path.isfile(n) for n in names):
            continue
        found = []
        for name in names:
            gray = cv2.imread(name, cv2.IMREAD_GRAYSCALE)
            size = gray.shape[::-1]
            ok, c = cv2.findChessboardCorners(gray, pattern)
            found.append(cv2.cornerSubPix(gray, c, (11, 11), (-1, -1), (3, 30, 0.01)) if ok else None)
        if all(f is not None for f in found):
            objects.append(board)
            corners[0].append(found[0])
            corners[1].append(found[1])
    _, K1, D1, _, _ = cv2.calibrateCamera(objects, corners[0], size, None, None)
    _, K2, D2, _, _ = cv2.calibrateCamera(objects, corners[1], size, None, None)
    _, K1, D1, K2, D2, R, T, _, _ = cv2.stereoCalibrate(objects, corners[0], corners[1], K1, D1, K2, D2, size,
                                                        flags=cv2.CALIB_FIX_INTRINSIC)
    work = tempfile.mkdtemp(prefix="rectify-picture-")
    intrinsics, extrinsics = os.path.join(work, "intrinsics.yml"), os.path.join(work, "extrinsics.yml")
    fs = cv2.FileStorage(intrinsics, cv2.FILE_STORAGE_WRITE)
    for key, value in (("M1", K1), ("D1", D1), ("M2", K2), ("D2", D2)):
        fs.write(key, value)
    fs.release()
    fs = cv2.FileStorage(extrinsics, cv2.FILE_STORAGE_WRITE)
    fs.write("R", R)
    fs.write("T", T)
    fs.release()
    out = os.path.join(work, "rectified")
    subprocess.run([libcam, "rectify", intrinsics, extrinsics, "--images", os.path.join(folder, "left01.jpg"),
                    os.path.join(folder, "right01.jpg"), "-o", out], check=True)
    images = [cv2.imread(os.path.join(out, name), cv2.IMREAD_COLOR) for name in ("left.png", "right.png")]
    picture = np.hstack([images[0], np.full((images[0].shape[0], 8, 3), 255, np.uint8), images[1]])
    for y in range(20, picture.shape[0], 40):
        cv2.line(picture, (0, y), (picture.shape[1] - 1, y), (0, 200, 0), 1)
    # Three fifths of the size: the rows still show, the file stays small.
    picture = cv2.resize(picture, (picture.shape[1] * 3 // 5, picture.shape[0] * 3 // 5), interpolation=cv2.INTER_AREA)
    cv2.imwrite(output, picture, [cv2.IMWRITE_PNG_COMPRESSION, 9])
    print(f"wrote {output}")


if __name__ == "__main__":
    main()
