#!/usr/bin/env python3
"""libcam's remap maps against mrcal's, on the mrcal files of the real cameras.

For each lens, `libcam remap` chooses two cameras for it ("valid": a pinhole with no
black borders; "all": a pinhole or LONLAT camera that keeps every pixel of the lens) and
writes each map (.npy, float32) and camera (.cameramodel); mrcal's
image_transformation_map(lens, camera, intrinsics_only=True) makes the same map from
the same two files. Where both give a source pixel they must agree to 1e-3 px (both
maps are float32: a coordinate near 6000 px is rounded to 2.4e-4 px); and libcam must
give one exactly where mrcal's lands on the lens's image, but within 1e-3 px of its edge
and but where libcam says the lens has no pixel for the ray and mrcal gives one anyway:
a splined lens's ray outside the spline's knots (mrcal extrapolates the spline there),
or a ray mrcal projects where its projection folds over (its Jacobian's determinant is
<= 0: the image is mirrored there, and the pixel mrcal gives also sees another ray).

Usage: remap_vs_mrcal.py LIBCAM REAL_CAMERAS_FOLDER WORK_FOLDER
Exits 77 (skipped) when mrcal's Python module or the real-cameras folder is absent.
"""

import os
import subprocess
import sys

SKIP = 77
TOLERANCE_PX = 1e-3
LENSES = [  # the mrcal files of the real cameras, with the model each holds
    ("mrcal/splined-0.cameramodel", "LENSMODEL_SPLINED_STEREOGRAPHIC"),
    ("mrcal/opencv8-0.cameramodel", "LENSMODEL_OPENCV8"),
    ("mrcal/cam0.splined.cameramodel", "LENSMODEL_SPLINED_STEREOGRAPHIC"),
    ("mrcal/splined-0.scale0.6.cahvor", "LENSMODEL_PINHOLE"),  # C, A, H, V alone: no distortion terms
]
TARGET_SIZE = "600x400"


def outside_spline(lens, target, mrcal, np):
    """Per target pixel: whether its ray is outside the rectangle of stereographic
    coordinates where the lens's spline interpolates (between its second and
    second-to-last knots for a cubic, half a knot in for a quadratic), as mrcal lays
    the knots out. All False for a lens that is not splined."""
    width, height = target.imagersize()
    model = lens.intrinsics()[0]
    if not model.startswith("LENSMODEL_SPLINED_STEREOGRAPHIC"):
        return np.zeros((height, width), dtype=bool)
    order = int(model.split("order=")[1].split("_")[0])
    low = 1.0 if order == 3 else 0.5
    knots_x, knots_y = mrcal.knots_for_splined_models(model)

    def bounds(knots):
        step = knots[1] - knots[0]
        return knots[0] + low * step, knots[-1] - low * step

    pixels = np.ascontiguousarray(np.stack(np.meshgrid(np.arange(width), np.arange(height)), axis=-1).astype(float))
    u = mrcal.project_stereographic(mrcal.unproject(pixels, *target.intrinsics()))
    (x0, x1), (y0, y1) = bounds(knots_x), bounds(knots_y)
    return (u[..., 0] < x0) | (u[..., 0] > x1) | (u[..., 1] < y0) | (u[..., 1] > y1)


def folded(lens, target, mask, mrcal, np):
    """Per target pixel in `mask`: whether mrcal's projection of its ray folds over, its
    Jacobian with respect to the ray's stereographic coordinates having a determinant
    <= 0 (the image mirrored there: the pixel mrcal gives is also the pixel of another
    ray, the one libcam gives it to)."""
    out = np.zeros(mask.shape, dtype=bool)
    ys, xs = np.nonzero(mask)
    if xs.size == 0:
        return out
    pixels = np.ascontiguousarray(np.stack([xs, ys], axis=-1).astype(float))
    u = mrcal.project_stereographic(mrcal.unproject(pixels, *target.intrinsics()))
    rays, d_ray_d_u = mrcal.unproject_stereographic(u, get_gradients=True)
    _, d_pixel_d_ray, _ = mrcal.project(rays, *lens.intrinsics(), get_gradients=True)
    out[ys, xs] = np.linalg.det(np.einsum("nij,njk->nik", d_pixel_d_ray, d_ray_d_u)) <= 0
    return out


def main():
    libcam, real_cameras, work = sys.argv[1:4]
    try:
        import numpy as np
        import mrcal
    except ImportError as error:
        print(f"skipped: mrcal's Python module is not installed (python3-mrcal): {error}")
        return SKIP
    if not os.path.isdir(real_cameras):
        print(f"skipped: the real-cameras folder {real_cameras} is absent")
        return SKIP
    os.makedirs(work, exist_ok=True)
    failed = False
    print(f"{'lens':34} {'model':24} {'target':22} {'both':>7} {'worst px':>9} {'disagree':>8} {'outside':>8} {'folded':>7}")
    for relative, expected_model in LENSES:
        lens_path = os.path.join(real_cameras, relative)
        lens = mrcal.cameramodel(lens_path)
        model = lens.intrinsics()[0]
        if not model.startswith(expected_model):
            print(f"{relative}: mrcal reads it as {model}, expected {expected_model}")
            failed = True
            continue
        for keep in ("valid", "all"):
            stem = os.path.join(work, os.path.basename(relative).replace(".", "_") + "-" + keep)
            subprocess.run([libcam, "remap", "--from", lens_path, "--to-pinhole", keep, "--size", TARGET_SIZE,
                            "--map-out", stem + ".npy", "--camera-out", stem + ".cameramodel", "--camera-format",
                            "cameramodel"], check=True, stdout=subprocess.DEVNULL)
            target = mrcal.cameramodel(stem + ".cameramodel")
            ours = np.load(stem + ".npy").astype(np.float64)
            theirs = mrcal.image_transformation_map(lens, target, intrinsics_only=True).astype(np.float64)
            if ours.shape != theirs.shape:
                print(f"{relative}: map shapes differ: libcam {ours.shape}, mrcal {theirs.shape}")
                failed = True
                continue
            width, height = lens.imagersize()

            def on_image(margin):
                x, y = theirs[..., 0], theirs[..., 1]
                with np.errstate(invalid="ignore"):
                    return (np.isfinite(theirs).all(axis=-1) & (x >= -0.5 - margin) & (y >= -0.5 - margin) &
                            (x <= width - 0.5 + margin) & (y <= height - 0.5 + margin))

            ours_has = np.isfinite(ours).all(axis=-1)
            both = ours_has & on_image(0.0)
            worst = float(np.max(np.linalg.norm(ours[both] - theirs[both], axis=-1))) if both.any() else float("nan")
            # Whether a target pixel has a source, libcam and mrcal must say the same, but
            # within rounding of the image's edge, and but where a splined lens's ray is
            # outside the spline's knots: libcam flags those rays, mrcal extrapolates.
            edge = 1e-3
            only_mrcal = ~ours_has & on_image(-edge)
            outside = only_mrcal & outside_spline(lens, target, mrcal, np)
            fold = folded(lens, target, only_mrcal & ~outside, mrcal, np)
            disagree = int(np.count_nonzero(ours_has & ~on_image(edge)) +
                           np.count_nonzero(only_mrcal & ~outside & ~fold))
            target_name = f"{target.intrinsics()[0].replace('LENSMODEL_', '')} {keep}"
            print(f"{relative:34} {model[10:].split('_order')[0]:24} {target_name:22} {int(both.sum()):7} {worst:9.3g} {disagree:8} "
                  f"{int(outside.sum()):8} {int(fold.sum()):7}")
            if not both.any() or not worst <= TOLERANCE_PX or disagree:
                failed = True
    print(f"both: target pixels both maps give a source; worst: the largest distance between their sources "
          f"(tolerance {TOLERANCE_PX} px); disagree: pixels one gives a source and the other none; outside: pixels "
          f"whose ray is outside a splined lens's knots, where mrcal extrapolates the spline and libcam gives none; "
          f"folded: pixels whose ray mrcal projects where its projection folds over (mirrored, the Jacobian's "
          f"determinant <= 0), so that its pixel also sees another ray, and libcam gives none")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
