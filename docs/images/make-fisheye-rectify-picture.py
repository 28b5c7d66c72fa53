#!/usr/bin/env python3
"""docs/images/rectify-fisheye.png: a T265-like fisheye pair rectified two ways, side by side:
the left fisheye image, OpenCV's rectification of it (cv2.fisheye.stereoRectify, then
initUndistortRectifyMap and remap, as OpenCV's documentation does it), and libcam's LATLON
rectification (`libcam rectify --to latlon`). Each picture's caption says the share of the
fisheye's pixels whose view lands in it.

The pair (Kannala-Brandt lenses of 848x800 as a RealSense T265's factory calibration, 6.4 cm
apart) stands inside a room of checkered walls (fisheye_room.py: every pixel's ray traced to
the wall it meets).

Usage: make-fisheye-rectify-picture.py LIBCAM [OUTPUT_PNG]
"""

import json
import os
import subprocess
import sys
import tempfile

import cv2
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from fisheye_room import kannala_brandt_rays, room_image  # noqa: E402

SIZE = (848, 800)
K = [[286.2, 286.0, 421.5, 398.2], [285.4, 285.3, 425.1, 401.0]]
D = [[-0.0085, 0.047, -0.044, 0.0084], [-0.0071, 0.043, -0.041, 0.0078]]
RVEC_RIGHT = [0.002, -0.003, 0.001]       # the right camera's turn
CENTRE_RIGHT = [0.064, 0.0002, -0.0003]   # and its centre, in the left camera's frame (m)


def rays(k, d):
    """Each pixel's ray (H, W, 3) through one of the pair's lenses."""
    return kannala_brandt_rays(SIZE[0], SIZE[1], k[0], k[1], k[2], k[3], d)


def render(k, d, R_cam_from_left, centre):
    """The room seen through one lens from `centre` (in the left camera's frame)."""
    return room_image(rays(k, d) @ R_cam_from_left, centre)  # rows: R^T v, the rays in the left camera's frame


def kalibr_camchain(R, t):
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, t
    text = ""
    for i in range(2):
        text += f"cam{i}:\n"
        if i == 1:
            text += "  T_cn_cnm1:\n" + "".join(f"  - [{', '.join(repr(float(v)) for v in row)}]\n" for row in T)
        text += ("  camera_model: pinhole\n  distortion_model: equidistant\n"
                 f"  distortion_coeffs: [{', '.join(repr(v) for v in D[i])}]\n"
                 f"  intrinsics: [{', '.join(repr(v) for v in K[i])}]\n  resolution: [{SIZE[0]}, {SIZE[1]}]\n")
    return text


def share_kept(k, d, R_rect, P):
    """The share of the fisheye's pixels looking in front of the lens whose rays land in
    the rectified pinhole image (libcam's `kept`, worked the same way for OpenCV's)."""
    v = rays(k, d) @ R_rect.T  # each ray in the rectified frame
    in_front = rays(k, d)[..., 2] > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        x = P[0, 0] * v[..., 0] / v[..., 2] + P[0, 2]
        y = P[1, 1] * v[..., 1] / v[..., 2] + P[1, 2]
    lands = (v[..., 2] > 0) & (x >= -0.5) & (x < SIZE[0] - 0.5) & (y >= -0.5) & (y < SIZE[1] - 0.5)
    return (lands & in_front).sum() / in_front.sum()


def captioned(image, lines, height, width=400):
    """The image scaled to HEIGHT, centred in a panel at least WIDTH wide, lines below it."""
    scale = height / image.shape[0]
    image = cv2.resize(image, (round(image.shape[1] * scale), height), interpolation=cv2.INTER_AREA)
    panel = np.full((height + 22 * len(lines) + 10, max(width, image.shape[1]), 3), 255, np.uint8)
    left = (panel.shape[1] - image.shape[1]) // 2
    panel[:height, left:left + image.shape[1]] = image
    for i, line in enumerate(lines):
        cv2.putText(panel, line, (6, height + 20 + 22 * i), cv2.FONT_HERSHEY_SIMPLEX, 0.5, (0, 0, 0), 1, cv2.LINE_AA)
    return panel


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    libcam = sys.argv[1]
    output = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), "rectify-fisheye.png")
    work = tempfile.mkdtemp(prefix="fisheye-rectify-picture-")
    R, _ = cv2.Rodrigues(np.array(RVEC_RIGHT))
    centre = np.array(CENTRE_RIGHT)
    t = -R @ centre  # X_right = R X_left + t, OpenCV's and Kalibr's convention
    images = [render(K[0], D[0], np.eye(3), np.zeros(3)), render(K[1], D[1], R, centre)]
    paths = [os.path.join(work, f"{side}.png") for side in ("left", "right")]
    for path, image in zip(paths, images):
        cv2.imwrite(path, image)

    # OpenCV: its fisheye stereo rectification, as its documentation uses it.
    Ks = [np.array([[k[0], 0, k[2]], [0, k[1], k[3]], [0, 0, 1.0]]) for k in K]
    Ds = [np.array(d, float) for d in D]
    R1, R2, P1, P2, _ = cv2.fisheye.stereoRectify(Ks[0], Ds[0], Ks[1], Ds[1], SIZE, R, t.reshape(3, 1),
                                                  cv2.CALIB_ZERO_DISPARITY)
    map_x, map_y = cv2.fisheye.initUndistortRectifyMap(Ks[0], Ds[0], R1, P1, SIZE, cv2.CV_32FC1)
    opencv_left = cv2.remap(images[0], map_x, map_y, cv2.INTER_LINEAR)
    opencv_kept = share_kept(K[0], D[0], R1, P1)

    # libcam: LATLON, as mrcal rectifies a wide pair.
    chain = os.path.join(work, "camchain.yaml")
    with open(chain, "w") as f:
        f.write(kalibr_camchain(R, t))
    out = os.path.join(work, "rectified")
    report = json.loads(subprocess.run([libcam, "rectify", chain, "--to", "latlon", "--json", "--images", *paths,
                                        "-o", out], check=True, capture_output=True, text=True).stdout)
    libcam_left = cv2.imread(os.path.join(out, "left.png"), cv2.IMREAD_COLOR)
    libcam_kept = report["cameras"][0]["kept"]
    Kr = np.array(report["cameras"][0]["K"])
    width, height = report["cameras"][0]["image_size"]

    panels = [
        captioned(images[0], ["The left fisheye (848x800, T265-like)", "a room of checkered walls"], 400),
        captioned(opencv_left, ["OpenCV: cv2.fisheye.stereoRectify, f " f"{P1[0, 0]:.1f} px",
                                f"{100 * opencv_kept:.0f}% kept, the centre {K[0][0] / P1[0, 0]:.1f}x smaller"], 400),
        captioned(libcam_left, [f"libcam rectify --to latlon, {width}x{height}",
                                f"{100 * libcam_kept:.1f}% kept, the centre at full size"], 400),
    ]
    gap = np.full((panels[0].shape[0], 10, 3), 255, np.uint8)
    picture = np.hstack([panels[0], gap, panels[1], gap, panels[2]])
    cv2.imwrite(output, picture, [cv2.IMWRITE_PNG_COMPRESSION, 9])
    print(f"wrote {output}: OpenCV's f {P1[0, 0]:.2f} px, its left view sees {100 * opencv_kept:.1f}% of the "
          f"fisheye's pixels; libcam's LATLON {width}x{height}, fx {Kr[0, 0]:.2f} fy {Kr[1, 1]:.2f} px per radian, keeps {100 * libcam_kept:.2f}%")


if __name__ == "__main__":
    main()
