#!/usr/bin/env python3
"""The Python module's speed beside the C++ batch engine, cv2 and mrcal, on the same points.

    PYTHONPATH=build/python python3 bench/python_bench.py [--from CAMERA] [--grid 1225x817]
                                                          [--libcam build/tools/libcam] [--runs 5]

The points are those of `libcam bench`: a grid of pixels over the image (corners
included) and their rays (z = 1 for OpenCV's models). The C++ rows come from
`libcam bench --grid ... --threads 1 --simd best --json` on the same grid, in the same run:
each Python row's time against the C++ batch on separate arrays (the layout the engine
reads) and against the C++ call on the Python call's own layout (numpy's C-ordered (N, 3)
and (N, 2): `project_interleaved`, `unproject_interleaved`), which is what the module
itself adds. The Python rows are the median of 7 timed calls, one thread, outputs allocated by each call (as a
user calls them) and, for libcam, also written into arrays given with out=. Not a test:
nothing here is asserted.
"""

import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import time

import numpy as np

import libcam

ROOT = pathlib.Path(__file__).resolve().parents[1]


def median_seconds(function, repeat=7):
    function()  # warm: tables built, pages touched
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def per_call_seconds(function, calls=20000):
    function()
    best = float("inf")
    for _ in range(5):
        start = time.perf_counter()
        for _ in range(calls):
            function()
        best = min(best, (time.perf_counter() - start) / calls)
    return best


def cpp_rows(libcam_exe, camera_path, grid):
    out = subprocess.run([libcam_exe, "bench", "--from", str(camera_path), "--grid", grid, "--threads", "1", "--simd",
                          "best", "--json"], check=True, capture_output=True, text=True).stdout
    rows = {}
    for row in json.loads(out)["rows"]:
        if row["library"] == "libcam" and row["scalar"] == "double" and row["threads"] == 1:
            rows[(row["op"], row["method"])] = row["ns_per_point"]
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--from", dest="camera", default=str(ROOT / "tests" / "fuzz" / "corpus" / "json" / "opencv8.json"))
    parser.add_argument("--grid", default="1225x817")
    parser.add_argument("--libcam", default=str(ROOT / "build" / "tools" / "libcam"))
    parser.add_argument("--runs", type=int, default=1, help="repeat the libcam rows and their C++ batch this often")
    args = parser.parse_args()
    if args.runs < 1:
        parser.error("--runs: expected at least 1")

    import cv2
    import mrcal

    cv2.setNumThreads(1)
    camera = libcam.read(args.camera)
    columns, rows = (int(v) for v in args.grid.split("x"))
    width, height = camera.size
    xs, ys = np.meshgrid(np.linspace(0, width - 1, columns), np.linspace(0, height - 1, rows))
    pixels = np.ascontiguousarray(np.stack([xs, ys], axis=-1).reshape(-1, 2))
    points, valid = camera.unproject(pixels)
    points, pixels = np.ascontiguousarray(points[valid]), np.ascontiguousarray(pixels[valid])
    n = len(points)
    K, dist = camera.K, camera.dist
    opencv = libcam.models[camera.model]["opencv"]
    mrcal_model = libcam.models[camera.model]["mrcal"]
    intrinsics = np.concatenate([[K[0, 0], K[1, 1], K[0, 2], K[1, 2]], dist])
    zero = np.zeros(3)

    print(f"camera {camera.model} {width}x{height}, {n} points (grid {args.grid}), one thread; "
          f"load average {os.getloadavg()[0]:.2f}")

    pixels_out = np.empty((n, 2))
    rays_out = np.empty((n, 3))
    mask_out = np.empty(n, dtype=bool)
    # The same points as the rows of a (3, N) array (its .T: each coordinate's values
    # together, the layout the C++ batch reads): read in place, the pixels written as the
    # rows of a (2, N) array.
    columns_in = np.ascontiguousarray(points.T).T
    columns_out = np.empty((2, n)).T

    def libcam_rows(cpp):
        """(op, call, seconds, C++ ns on arrays, C++ ns on the call's layout) of libcam's calls."""
        batch, interleaved = cpp.get(("project", "batch")), cpp.get(("project", "interleaved"))
        rows = [("project", "cam.project(points, frame='camera')",
                 median_seconds(lambda: camera.project(points, frame="camera")), batch, interleaved),
                ("project", "... out=(pixels, mask)",
                 median_seconds(lambda: camera.project(points, frame="camera", out=(pixels_out, mask_out))), batch,
                 interleaved),
                ("project", "cam.project(points_3xN.T, frame='camera')",
                 median_seconds(lambda: camera.project(columns_in, frame="camera")), batch, batch),
                ("project", "... out=(pixels_2xN.T, mask)",
                 median_seconds(lambda: camera.project(columns_in, frame="camera", out=(columns_out, mask_out))), batch,
                 batch)]
        for method in ("exact", "fast"):
            arrays, same_layout = cpp.get(("unproject", method)), cpp.get(("unproject", f"interleaved-{method}"))
            rows.append(("unproject", f"cam.unproject(pixels, method='{method}')",
                         median_seconds(lambda: camera.unproject(pixels, method=method)), arrays, same_layout))
            rows.append(("unproject", "... out=(directions, mask)",
                         median_seconds(lambda: camera.unproject(pixels, method=method, out=(rays_out, mask_out))),
                         arrays, same_layout))
        return rows

    # Each run times the C++ batch (a `libcam bench` process) and then libcam's Python
    # calls; on a machine whose other work comes and goes the ratio is taken run by run.
    runs = []
    for _ in range(args.runs):
        cpp = cpp_rows(args.libcam, args.camera, args.grid)
        runs.append(libcam_rows(cpp))
    def ratio_column(ns, i, reference):
        """The median ratio of row i's times to run by run C++ times, and their range."""
        ratios = sorted(t / run[i][reference] for t, run in zip(ns, runs) if run[i][reference])
        if not ratios:
            return ""
        spread = f" ({ratios[0]:.2f}..{ratios[-1]:.2f})" if len(ratios) > 1 else ""
        return f"{statistics.median(ratios):.2f}{spread}"

    table = []
    for i, (op, call, *_) in enumerate(runs[0]):
        ns = [run[i][2] * 1e9 / n for run in runs]
        table.append((op, "libcam", call, statistics.median(ns), ratio_column(ns, i, 3), ratio_column(ns, i, 4)))

    def add(op, library, call, seconds):
        table.append((op, library, call, seconds * 1e9 / n, "", ""))

    if opencv == "cv2.projectPoints":
        add("project", "cv2", "cv2.projectPoints", median_seconds(lambda: cv2.projectPoints(points, zero, zero, K, dist)))
    if mrcal_model:
        add("project", "mrcal", "mrcal.project", median_seconds(lambda: mrcal.project(points, mrcal_model, intrinsics)))
    if opencv == "cv2.projectPoints":
        add("unproject", "cv2", "cv2.undistortPoints (5 iterations, not converged)",
            median_seconds(lambda: cv2.undistortPoints(pixels.reshape(-1, 1, 2), K, dist)))
        add("unproject", "cv2", "cv2.undistortPointsIter (100 iterations)",
            median_seconds(lambda: cv2.undistortPointsIter(pixels.reshape(-1, 1, 2), K, dist, None, None,
                                                           (cv2.TERM_CRITERIA_COUNT, 100, 0))))
    if mrcal_model:
        add("unproject", "mrcal", "mrcal.unproject", median_seconds(lambda: mrcal.unproject(pixels, mrcal_model, intrinsics)))

    print(f"\n{'op':<10} {'library':<8} {'call':<46} {'ns/point':>9} {'/ C++ on arrays':>18} {'/ C++ same layout':>18}")
    for op, library, call, ns, arrays, same_layout in table:
        print(f"{op:<10} {library:<8} {call:<46} {ns:9.2f} {arrays:>18} {same_layout:>18}")
    print("\nC++ batch (libcam bench, same grid, last run): " +
          ", ".join(f"{op} {method} {ns:.2f} ns" for (op, method), ns in sorted(cpp.items()) if op in ("project", "unproject")))
    print(f"(libcam rows: the median of {args.runs} runs; each ratio against the C++ call of its own run, "
          f"their median and (range); load average now {os.getloadavg()[0]:.2f})")

    one_point, one_pixel = points[:1].copy(), pixels[:1].copy()
    print("\nper call, one point (microseconds):")
    calls = [("libcam cam.project", lambda: camera.project(one_point, frame="camera")),
             ("libcam cam.unproject", lambda: camera.unproject(one_pixel))]
    if opencv == "cv2.projectPoints":
        calls += [("cv2.projectPoints", lambda: cv2.projectPoints(one_point, zero, zero, K, dist)),
                  ("cv2.undistortPoints", lambda: cv2.undistortPoints(one_pixel.reshape(-1, 1, 2), K, dist))]
    if mrcal_model:
        calls += [("mrcal.project", lambda: mrcal.project(one_point, mrcal_model, intrinsics)),
                  ("mrcal.unproject", lambda: mrcal.unproject(one_pixel, mrcal_model, intrinsics))]
    for name, call in calls:
        print(f"  {name:<24} {per_call_seconds(call) * 1e6:7.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
