#!/usr/bin/env bash
# Makes dataset-views.png, the picture of README.md and docs/datasets.md: a room with
# checkered walls seen through the RealSense T265's fisheye (basalt's calibration), as a
# one-image COLMAP model turned into pinholes twice: by `libcam dataset --camera views`
# (every pixel's ray kept, in several pinhole views) and by COLMAP's image_undistorter (one
# pinhole, a small centre crop). Left: the fisheye with each view's footprint outlined
# (COLMAP's crop in white); middle: the views, unfolded as a cube's faces; right: COLMAP's
# crop, at the same scale.
# Usage: docs/images/make-dataset-views-picture.sh LIBCAM T265_CALIBRATION [COLMAP]
#   LIBCAM: the program (build/tools/libcam); T265_CALIBRATION: basalt's calibration of
#   the RealSense T265 (t265_kb4_calib.json, from basalt's repository); COLMAP: the colmap
#   program (default: colmap on the PATH).
set -euo pipefail
if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: $0 LIBCAM T265_CALIBRATION (basalt's t265_kb4_calib.json) [COLMAP]" >&2
  exit 2
fi
libcam=$1
lens=$2
colmap=${3:-colmap}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
here=$(cd "$(dirname "$0")" && pwd)

# The one-image model: the lens as COLMAP's OPENCV_FISHEYE, its image named image.png.
"$libcam" convert --from "$lens" --to colmap -o "$work/scene/sparse/0" > /dev/null
mkdir -p "$work/scene/images"
# The fisheye photo: each pixel's ray (Kannala-Brandt inverted by Newton's method) meets
# the walls of a room, each wall checkered in its own colour.
/usr/bin/python3 - "$work/scene/sparse/0/cameras.txt" "$work/scene/images/image.png" "$here" <<'PY'
import sys, cv2
sys.path.insert(0, sys.argv[3])
from fisheye_room import kannala_brandt_rays, room_image
line = [l for l in open(sys.argv[1]) if l.strip() and not l.startswith("#")][0].split()
w, h = int(line[2]), int(line[3])
fx, fy, cx, cy, *k = map(float, line[4:])
cx, cy = cx - 0.5, cy - 0.5  # COLMAP's pixels to OpenCV's
# The camera off the room's centre.
cv2.imwrite(sys.argv[2], room_image(kannala_brandt_rays(w, h, fx, fy, cx, cy, k), [0.3, -0.2, 0.0]))
PY

"$libcam" dataset "$work/scene/sparse/0" -o "$work/views" --camera views --json > "$work/views.json"
"$colmap" image_undistorter --image_path "$work/scene/images" --input_path "$work/scene/sparse/0" \
  --output_path "$work/colmap" --output_type COLMAP > /dev/null
"$libcam" convert --from "$work/colmap/sparse" --to json -o "$work/colmap.json" > /dev/null

/usr/bin/python3 - "$work" "$here/dataset-views.png" <<'PY'
import sys, json, numpy as np, cv2
work, out = sys.argv[1], sys.argv[2]
summary = json.load(open(f"{work}/views.json"))
line = [l for l in open(f"{work}/scene/sparse/0/cameras.txt") if l.strip() and not l.startswith("#")][0].split()
fx, fy, cx, cy, *k = map(float, line[4:])
cx, cy = cx - 0.5, cy - 0.5
fisheye = cv2.imread(f"{work}/scene/images/image.png")

def to_fisheye(rays):  # Kannala-Brandt, rays in the fisheye's frame, any direction
    r = np.hypot(rays[:, 0], rays[:, 1])
    theta = np.arctan2(r, rays[:, 2])
    t2 = theta * theta
    theta_d = theta * (1 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3]))))
    s = np.where(r > 0, theta_d / np.maximum(r, 1e-12), 0)
    return np.stack([fx * rays[:, 0] * s + cx, fy * rays[:, 1] * s + cy], 1)

def axes(yaw, pitch):  # a view's axes in the fisheye's frame (libcam's turn, transposed)
    y, p = np.radians(yaw), np.radians(-pitch)
    ry = np.array([[np.cos(y), 0, np.sin(y)], [0, 1, 0], [-np.sin(y), 0, np.cos(y)]])
    rx = np.array([[1, 0, 0], [0, np.cos(p), -np.sin(p)], [0, np.sin(p), np.cos(p)]])
    return ry @ rx

def outline(width, height, f, ccx, ccy, turn):
    n = 200
    xs = np.concatenate([np.linspace(0, width - 1, n), np.full(n, width - 1.0), np.linspace(width - 1, 0, n), np.zeros(n)])
    ys = np.concatenate([np.zeros(n), np.linspace(0, height - 1, n), np.full(n, height - 1.0), np.linspace(height - 1, 0, n)])
    rays = np.stack([(xs - ccx) / f, (ys - ccy) / f, np.ones_like(xs)], 1) @ turn.T
    return to_fisheye(rays)

colours = [(40, 40, 255), (255, 80, 40), (40, 200, 40), (0, 200, 255), (255, 40, 200), (200, 200, 0)]
drawn = fisheye.copy()
for i, c in enumerate(summary["cameras"]):
    pts = outline(c["width"], c["height"], c["fx"], c["cx"], c["cy"], axes(c["yaw_deg"], c["pitch_deg"]))
    cv2.polylines(drawn, [np.round(pts * 4).astype(np.int32)], True, colours[i % 6], 3, cv2.LINE_AA, shift=2)
crop = json.load(open(f"{work}/colmap.json"))
crop = crop["cameras"][0] if "cameras" in crop else crop
K = crop["K"]
size = crop.get("image_size") or crop.get("size")
cw, ch = (size["width"], size["height"]) if isinstance(size, dict) else size
pts = outline(cw, ch, K[0][0], K[0][2], K[1][2], np.eye(3))
cv2.polylines(drawn, [np.round(pts * 4).astype(np.int32)], True, (255, 255, 255), 3, cv2.LINE_AA, shift=2)

# The views unfolded as a cube's faces around the front one; each framed in its colour.
views = {}
for i, c in enumerate(summary["cameras"]):
    name = "image.png" if c["views"] == 1 else f"image_view{c['view']}.png"
    image = cv2.imread(f"{work}/views/images/{name}")
    views[(round(c["yaw_deg"]), round(c["pitch_deg"]))] = (cv2.copyMakeBorder(image, 3, 3, 3, 3, cv2.BORDER_CONSTANT, value=colours[i % 6]), c)
front = views.get((0, 0))
if front is not None and len(views) == 5 and {(-90, 0), (90, 0), (0, -90), (0, 90)} <= views.keys():
    # Each side view's edge meets the front's (a cube's faces, unfolded).
    fw, fh = front[0].shape[1], front[0].shape[0]
    fl, ft = -front[1]["cx"] - 3, -front[1]["cy"] - 3
    pos = {(0, 0): (fl, ft)}
    left, right, up, down = views[(-90, 0)], views[(90, 0)], views[(0, -90)], views[(0, 90)]
    pos[(-90, 0)] = (fl - left[0].shape[1], -left[1]["cy"] - 3)
    pos[(90, 0)] = (fl + fw, -right[1]["cy"] - 3)
    pos[(0, -90)] = (-up[1]["cx"] - 3, ft - up[0].shape[0])
    pos[(0, 90)] = (-down[1]["cx"] - 3, ft + fh)
    x_min = min(p[0] for p in pos.values()); y_min = min(p[1] for p in pos.values())
    W = int(max(pos[k][0] + views[k][0].shape[1] for k in pos) - x_min) + 1
    H = int(max(pos[k][1] + views[k][0].shape[0] for k in pos) - y_min) + 1
    canvas = np.full((H, W, 3), 255, np.uint8)
    for key, (x0, y0) in pos.items():
        image = views[key][0]
        X, Y = int(round(x0 - x_min)), int(round(y0 - y_min))
        canvas[Y:Y + image.shape[0], X:X + image.shape[1]] = image
else:  # another layout: the views side by side
    tiles = [v[0] for v in views.values()]
    H = max(t.shape[0] for t in tiles)
    canvas = np.hstack([cv2.copyMakeBorder(t, 0, H - t.shape[0], 0, 8, cv2.BORDER_CONSTANT, value=(255, 255, 255)) for t in tiles])
colmap_image = cv2.imread(f"{work}/colmap/images/image.png")
colmap_image = cv2.copyMakeBorder(colmap_image, 3, 3, 3, 3, cv2.BORDER_CONSTANT, value=(255, 255, 255))

def fit(image, height):
    return cv2.resize(image, (round(image.shape[1] * height / image.shape[0]), height), interpolation=cv2.INTER_AREA)
height = 360
scale = height / canvas.shape[0]
left = fit(drawn, height)
middle = fit(canvas, height)
# COLMAP's crop at the views' angular scale: as many degrees per inch as the views.
angular = scale * summary["cameras"][0]["fx"] / K[0][0]
right = cv2.resize(colmap_image, None, fx=angular, fy=angular, interpolation=cv2.INTER_AREA)
right = cv2.copyMakeBorder(right, 0, height - right.shape[0], 0, 0, cv2.BORDER_CONSTANT, value=(255, 255, 255))
right = cv2.copyMakeBorder(right, 0, 0, 0, max(0, 200 - right.shape[1]), cv2.BORDER_CONSTANT, value=(255, 255, 255))
gap = np.full((height, 12, 3), 255, np.uint8)
row = np.hstack([left, gap, middle, gap, right])

def caption(width, text):
    strip = np.full((22, width, 3), 255, np.uint8)
    cv2.putText(strip, text, (2, 16), cv2.FONT_HERSHEY_SIMPLEX, 0.45, (0, 0, 0), 1, cv2.LINE_AA)
    return strip
kept = sum(1 for c in summary["cameras"])
captions = np.hstack([caption(left.shape[1] + 12, "T265 fisheye (each view outlined)"),
                      caption(middle.shape[1] + 12, f"libcam dataset --camera views: {kept} pinholes"),
                      caption(right.shape[1], "colmap image_undistorter")])
cv2.imwrite(out, np.vstack([captions, row]), [cv2.IMWRITE_PNG_COMPRESSION, 9])
PY
echo "wrote $here/dataset-views.png"
