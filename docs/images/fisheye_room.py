"""A room of checkered walls seen through a Kannala-Brandt fisheye (OpenCV's fisheye model),
for the pictures of the docs (make-dataset-views-picture.sh, make-fisheye-rectify-picture.py):
each pixel's ray traced to the wall it meets."""

import numpy as np

TINTS = np.array([[90, 160, 230], [230, 140, 90], [120, 210, 120], [200, 200, 200], [210, 120, 210], [90, 200, 220]],
                 np.float64)


def kannala_brandt_rays(width, height, fx, fy, cx, cy, k):
    """Each pixel's ray (height, width, 3), pixels in OpenCV's convention: theta solved from
    theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8) by Newton's method,
    past 90 degrees too."""
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    a, b = (x - cx) / fx, (y - cy) / fy
    theta_d = np.hypot(a, b)
    theta = theta_d.copy()
    for _ in range(30):
        t2 = theta * theta
        f = theta * (1 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3])))) - theta_d
        df = 1 + t2 * (3 * k[0] + t2 * (5 * k[1] + t2 * (7 * k[2] + t2 * 9 * k[3])))
        theta = theta - f / df
    scale = np.where(theta_d > 0, np.sin(theta) / np.maximum(theta_d, 1e-12), 1.0)
    return np.dstack([a * scale, b * scale, np.cos(theta)])


def room_image(rays, centre, half=(2.0, 1.5, 2.5), square=0.4):
    """The colour (BGR, uint8) where each ray from `centre` leaves a box of half-sizes `half`
    around the origin: each wall checkered with squares of side `square` in its own tint."""
    centre, half = np.asarray(centre, np.float64), np.asarray(half, np.float64)
    # The wall each ray leaves the room through: the smallest positive distance over the axes.
    with np.errstate(divide="ignore", invalid="ignore"):
        dist = np.where(rays > 0, (half - centre) / rays, np.where(rays < 0, (-half - centre) / rays, np.inf))
    axis = np.argmin(dist, axis=2)
    hit = centre + rays * np.take_along_axis(dist, axis[..., None], 2)
    sign = np.take_along_axis(np.sign(rays), axis[..., None], 2)[..., 0]
    wall = axis * 2 + (sign > 0)
    u = np.where(axis == 0, hit[..., 2], hit[..., 0])
    v = np.where(axis == 1, hit[..., 2], hit[..., 1])
    board = ((np.floor(u / square) + np.floor(v / square)) % 2).astype(np.float64)
    return np.clip(TINTS[wall] * (0.45 + 0.55 * board[..., None]), 0, 255).astype(np.uint8)
