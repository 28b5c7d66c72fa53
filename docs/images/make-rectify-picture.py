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

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "peers"))
from opencv_stereo import calibrate_sample_pairs, write_stereo_files  # noqa: E402


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    libcam, folder = sys.argv[1:3]
    output = sys.argv[3] if len(sys.argv) > 3 else os.path.join(os.path.dirname(__file__), "rectify-opencv-sample.png")
    K1, D1, K2, D2, R, T, _, _, _ = calibrate_sample_pairs(cv2, np, folder)
    work = tempfile.mkdtemp(prefix="rectify-picture-")
    intrinsics, extrinsics = write_stereo_files(cv2, work, "sample", K1, D1, K2, D2, R, T)
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
