#!/usr/bin/env python3
"""From a real calibration to the camera a renderer needs, checked with OpenCV.

    python3 render_camera.py CALIBRATION_FILE [--camera NAME]

1. reads the calibration (any format libcam reads: OpenCV, mrcal, Kalibr, basalt, ...);
2. chooses the pinhole camera that sees what the lens sees without black borders: square
   pixels and a centred principal point, so a renderer (Blender, OpenGL, a NeRF) can take it
   as a field-of-view angle and an image size;
3. builds that graphics camera from its angle alone, as a renderer would;
4. checks both with cv2: libcam's rays through the real lens reproject onto their pixels
   with cv2.projectPoints (or cv2.fisheye, cv2.omnidir), and the graphics camera projects
   like cv2.projectPoints with the pinhole's K;
5. builds the map that turns a render into an image as the real lens would take it, for
   cv2.remap.

Exits with 1 when a check fails.
"""

import argparse
import sys

import cv2
import numpy as np

import libcam


def opencv_projection(camera, directions):
    """The pixels OpenCV gives camera-frame directions through the camera's lens, or None
    when OpenCV lacks the model."""
    zero = np.zeros(3)
    function = libcam.models[camera.model]["opencv"]
    if function == "cv2.projectPoints":
        pixels, _ = cv2.projectPoints(directions, zero, zero, camera.K, camera.dist)
    elif function == "cv2.fisheye.projectPoints":
        directions = directions[directions[:, 2] > 0]  # cv2.fisheye: points in front only
        pixels, _ = cv2.fisheye.projectPoints(directions.reshape(-1, 1, 3), zero, zero, camera.K, camera.dist)
    elif function == "cv2.omnidir.projectPoints":
        xi, k1, k2, p1, p2 = camera.dist
        pixels, _ = cv2.omnidir.projectPoints(directions.reshape(1, -1, 3), zero, zero, camera.K, float(xi),
                                              np.array([[k1, k2, p1, p2]]))
    else:
        return None
    return pixels.reshape(-1, 2)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("calibration")
    parser.add_argument("--camera", help="which camera of the file (name or position)")
    args = parser.parse_args()

    lens = libcam.read(args.calibration, camera=args.camera)
    print(f"lens      {lens}")

    render, why = libcam.new_camera(lens, keep="valid")
    fov = render.fov["horizontal"]
    print(f"render    {render.size[0]}x{render.size[1]}, {fov:.6f} degrees across: {why}")

    # What a renderer is given: an angle, an image size, and the look-at pose of the lens
    # (OpenCV's camera looks along the third row of R, with its image's up along minus
    # the second).
    graphics = libcam.from_fov(fov, render.size, axis="horizontal", eye=lens.center, gaze=lens.R[2], up=-lens.R[1])
    k_error = np.abs(graphics.K - render.K).max()
    print(f"graphics  K from the angle alone differs from the chosen pinhole's by {k_error:.2e}")

    ok = k_error < 1e-6
    width, height = lens.size
    xs, ys = np.meshgrid(np.linspace(0, width - 1, 64), np.linspace(0, height - 1, 48))
    grid = np.stack([xs, ys], axis=-1).reshape(-1, 2)
    rays, valid = lens.unproject(grid)
    reference = opencv_projection(lens, rays[valid])
    if reference is None:
        print(f"lens      OpenCV has no {lens.model} model: its check is skipped")
    else:
        front = rays[valid][:, 2] > 0 if libcam.models[lens.model]["opencv"] == "cv2.fisheye.projectPoints" else slice(None)
        error = np.abs(reference - grid[valid][front]).max()
        print(f"lens      {valid.sum()} rays of {len(grid)} pixels reproject through OpenCV within {error:.2e} px")
        ok &= error < 1e-6

    # World points along the lens's rays, through the graphics camera and through cv2.
    camera_points = rays[valid][rays[valid][:, 2] > 0] * 3.0
    world_points = (camera_points - lens.t) @ lens.R  # R^T (X_cam - t)
    pixels, in_front = graphics.project(world_points)
    inside = (pixels >= -0.5) & (pixels <= np.array(graphics.size) - 0.5)
    in_view = in_front & inside.all(axis=-1)
    opencv_pixels, _ = cv2.projectPoints(world_points, graphics.rvec, graphics.t, graphics.K, None)
    error = np.abs(pixels[in_view] - opencv_pixels.reshape(-1, 2)[in_view]).max()
    print(f"graphics  {in_view.sum()} points project as cv2.projectPoints with its K, rvec, t within {error:.2e} px")
    ok &= error < 1e-6

    coordinates, has_source = libcam.remap_map(lens, graphics)
    print(f"warp      render -> lens map {coordinates.shape}: {has_source.mean():.1%} of the lens's pixels "
          "see the render (cv2.remap(render, map, None, cv2.INTER_LINEAR))")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
