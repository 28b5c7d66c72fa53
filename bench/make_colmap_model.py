#!/usr/bin/env python3
"""Writes a synthetic COLMAP binary model (cameras.bin, images.bin, points3D.bin) for timing
the observation reader against `colmap model_analyzer`.

    python3 bench/make_colmap_model.py OUT_FOLDER [--images 2000] [--points 250000] [--track 4]

One SIMPLE_RADIAL camera; images on a line looking down +Z; points in front of them, each
seen by `--track` distinct images at its exact projection (so every observation is counted
by the reprojection, as in a real model), ERROR 0. Observations: points * track. Layout as
COLMAP's src/colmap/scene/reconstruction_io_binary.cc writes it, little-endian.
"""
import argparse
import os
import struct

import numpy as np

WIDTH, HEIGHT = 3072, 2304
F, CX, CY, K = 2500.0, 1536.0, 1152.0, -0.02  # COLMAP's pixels
SIMPLE_RADIAL = 2


def project(points_cam):
    x = points_cam[:, 0] / points_cam[:, 2]
    y = points_cam[:, 1] / points_cam[:, 2]
    radial = 1.0 + K * (x * x + y * y)
    return F * x * radial + CX, F * y * radial + CY


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--images", type=int, default=2000)
    parser.add_argument("--points", type=int, default=250000)
    parser.add_argument("--track", type=int, default=4)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    os.makedirs(args.out, exist_ok=True)

    # Camera i at (i * 0.01, 0, 0), identity rotation: t = -centre.
    centres = np.zeros((args.images, 3))
    centres[:, 0] = np.arange(args.images) * 0.01
    xyz = np.column_stack([rng.uniform(-2, 2 + args.images * 0.01, args.points),
                           rng.uniform(-2, 2, args.points), rng.uniform(8, 12, args.points)])
    # Each point's track: `track` distinct images near it in x (so it projects inside them).
    nearest = np.clip((xyz[:, 0] / 0.01).astype(np.int64), 0, args.images - 1)
    offsets = np.stack([rng.permutation(40)[:args.track] - 20 for _ in range(64)])
    track_images = np.clip(nearest[:, None] + offsets[rng.integers(0, 64, args.points)], 0, args.images - 1)
    # Duplicates after clipping at the ends: shift them to distinct images.
    track_images = np.sort(track_images, axis=1)
    for j in range(1, args.track):
        clash = track_images[:, j] <= track_images[:, j - 1]
        track_images[clash, j] = track_images[clash, j - 1] + 1
    track_images = np.minimum(track_images, args.images - 1 - (args.track - 1 - np.arange(args.track)))
    track_images = np.sort(track_images, axis=1)

    flat_images = track_images.ravel()
    flat_points = np.repeat(np.arange(args.points), args.track)
    order = np.argsort(flat_images, kind="stable")
    flat_images, flat_points = flat_images[order], flat_points[order]
    counts = np.bincount(flat_images, minlength=args.images)
    starts = np.concatenate([[0], np.cumsum(counts)])
    index_in_image = np.arange(flat_images.size) - starts[flat_images]
    u, v = project(xyz[flat_points] - centres[flat_images])

    with open(os.path.join(args.out, "cameras.bin"), "wb") as out:
        out.write(struct.pack("<QIiQQ4d", 1, 1, SIMPLE_RADIAL, WIDTH, HEIGHT, F, CX, CY, K))

    point2d = np.dtype([("x", "<f8"), ("y", "<f8"), ("id", "<u8")])
    with open(os.path.join(args.out, "images.bin"), "wb") as out:
        out.write(struct.pack("<Q", args.images))
        for i in range(args.images):
            out.write(struct.pack("<I7dI", i + 1, 1.0, 0.0, 0.0, 0.0, *(-centres[i]), 1))
            out.write(b"image%06d.jpg\0" % (i + 1))
            rows = np.empty(counts[i], dtype=point2d)
            rows["x"], rows["y"] = u[starts[i]:starts[i + 1]], v[starts[i]:starts[i + 1]]
            rows["id"] = flat_points[starts[i]:starts[i + 1]] + 1
            out.write(struct.pack("<Q", counts[i]))
            out.write(rows.tobytes())

    # Each track element's POINT2D_IDX: the observation's position in its image.
    point2d_idx = np.empty(flat_images.size, dtype=np.int64)
    point2d_idx[order] = index_in_image
    record = np.dtype([("id", "<u8"), ("xyz", "<f8", 3), ("rgb", "u1", 3), ("error", "<f8"), ("length", "<u8"),
                       ("track", "<u4", (args.track, 2))])
    rows = np.zeros(args.points, dtype=record)
    rows["id"] = np.arange(args.points) + 1
    rows["xyz"] = xyz
    rows["rgb"] = 128
    rows["length"] = args.track
    rows["track"][:, :, 0] = track_images + 1
    rows["track"][:, :, 1] = point2d_idx.reshape(args.points, args.track)
    with open(os.path.join(args.out, "points3D.bin"), "wb") as out:
        out.write(struct.pack("<Q", args.points))
        out.write(rows.tobytes())
    print(f"{args.out}: {args.images} images, {args.points} points, {flat_images.size} observations")


if __name__ == "__main__":
    main()
