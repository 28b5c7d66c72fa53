#!/usr/bin/env bash
# Makes remap-fisheye.png, the before/after picture of README.md and docs/remap.md:
# a checkerboard drawn on a 160-degree pinhole, seen through the RealSense T265's fisheye
# (basalt's calibration, --inverse), then undistorted to the pinhole "valid" chooses and
# to the LONLAT camera that keeps every pixel.
# Usage: docs/images/make-remap-pictures.sh LIBCAM T265_CALIBRATION
#   LIBCAM: the program (build/tools/libcam); T265_CALIBRATION: basalt's calibration of
#   the RealSense T265 (t265_kb4_calib.json, from basalt's repository).
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

# The scene: a pinhole 160 degrees across, and a checkerboard with coloured bands drawn on it.
"$libcam" remap --from "$lens" --to-fov 160 --size 1600x1200 --camera-out "$work/scene.json" > /dev/null
/usr/bin/python3 - "$work/scene.png" <<'PY'
import sys, numpy as np, cv2
h, w = 1200, 1600
y, x = np.mgrid[0:h, 0:w]
board = ((x // 50 + y // 50) % 2).astype(np.uint8)
img = np.dstack([200 - 150 * board] * 3).astype(np.int32)
img[:, :, 2] += 55 * ((y // 300) % 2 == 0)
img[:, :, 0] += 55 * ((x // 400) % 2 == 0)
img = np.clip(img, 0, 255).astype(np.uint8)
cv2.imwrite(sys.argv[1], img)
PY
# The fisheye photo: the scene as the lens sees it.
mkdir -p "$work/fisheye" "$work/pinhole" "$work/lonlat"
"$libcam" remap --from "$lens" --to "$work/scene.json" --inverse --interpolation cubic "$work/scene.png" -o "$work/fisheye"
mv "$work/fisheye/scene.png" "$work/fisheye.png"
# Undistorted: the widest pinhole with no black borders, and the LONLAT camera that keeps everything.
"$libcam" remap --from "$lens" --to-pinhole valid --interpolation cubic "$work/fisheye.png" -o "$work/pinhole"
"$libcam" remap --from "$lens" --to-lonlat all --interpolation cubic "$work/fisheye.png" -o "$work/lonlat"
/usr/bin/python3 - "$work" "$here/remap-fisheye.png" <<'PY'
import sys, numpy as np, cv2
work, out = sys.argv[1], sys.argv[2]
tiles = [cv2.resize(cv2.imread(f"{work}/{p}"), (424, 400), interpolation=cv2.INTER_AREA)
         for p in ("fisheye.png", "pinhole/fisheye.png", "lonlat/fisheye.png")]
gap = np.full((400, 8, 3), 255, np.uint8)
cv2.imwrite(out, np.hstack([tiles[0], gap, tiles[1], gap, tiles[2]]))
PY
echo "wrote $here/remap-fisheye.png"
