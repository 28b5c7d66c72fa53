#!/usr/bin/env bash
# Makes blender-fisheye.png, the Blender picture of README.md and docs/blender.md: a scene
# rendered by Blender (Cycles) through a real fisheye calibration, the RealSense T265's
# (basalt's calibration), by way of libcam render-plan: Blender renders the plan's camera,
# libcam remap warps the render into the lens's image, and libcam project's pixels for
# the spheres' centres are drawn on top as crosses.
# Usage: docs/images/make-blender-picture.sh LIBCAM T265_CALIBRATION
#   LIBCAM: the program (build/tools/libcam); T265_CALIBRATION: basalt's calibration of
#   the RealSense T265 (t265_kb4_calib.json, from basalt's repository). Needs blender.
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 LIBCAM T265_CALIBRATION (basalt's t265_kb4_calib.json)" >&2
  exit 2
fi
libcam=$1
lens=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
here=$(cd "$(dirname "$0")" && pwd)

"$libcam" render-plan --from "$lens" -o "$work/plan"
blender -b --factory-startup -noaudio -P "$work/plan/render.py" -P "$here/blender_scene.py" \
  -o "$work/render_" -F PNG -f 1 -- "$work/points.txt" > "$work/blender.log" 2>&1 ||
  { tail -20 "$work/blender.log" >&2; exit 1; }
mkdir -p "$work/lens"
"$libcam" remap --from "$work/plan/render.json" --to "$work/plan/lens.json" --interpolation cubic \
  "$work/render_0001.png" -o "$work/lens"
# shellcheck disable=SC2046
"$libcam" project --from "$work/plan/lens.json" --points $(cat "$work/points.txt") --json > "$work/pixels.json"
/usr/bin/python3 - "$work" "$here/blender-fisheye.png" <<'PY'
import json, sys
import cv2, numpy as np
work, out = sys.argv[1], sys.argv[2]
height = 480  # the picture's height; both images are scaled to it
render = cv2.imread(f"{work}/render_0001.png")
lens = cv2.imread(f"{work}/lens/render_0001.png")
scale = height / lens.shape[0]
lens = cv2.resize(lens, (round(lens.shape[1] * scale), height), interpolation=cv2.INTER_AREA)
render = cv2.resize(render, (height * render.shape[1] // render.shape[0], height), interpolation=cv2.INTER_AREA)
for entry in json.load(open(f"{work}/pixels.json"))["pixels"]:
    if entry["valid"]:
        # The pixel in the scaled picture: centres at (x + 0.5) scale - 0.5. A cross 6 px each
        # way, drawn to 1/16 pixel (cv2's shift 4).
        x, y = ((c + 0.5) * scale - 0.5 for c in entry["pixel"])
        for dx, dy in ((6, 0), (0, 6)):
            p = (round((x - dx) * 16), round((y - dy) * 16))
            q = (round((x + dx) * 16), round((y + dy) * 16))
            cv2.line(lens, p, q, (255, 255, 255), 1, cv2.LINE_AA, 4)
gap = np.full((height, 8, 3), 255, np.uint8)
cv2.imwrite(out, np.hstack([render, gap, lens]))
PY
echo "wrote $here/blender-fisheye.png"
