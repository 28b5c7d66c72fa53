#!/usr/bin/env bash
# Makes reproject-mrcal.png, the picture of README.md and docs/reprojection.md: mrcal's own
# calibration of a Nikon D750 with a Samyang 12 mm fisheye (186 views of a 10x10 board),
# solved by mrcal twice, with OPENCV8 and with its splined model, each reprojected by
# `libcam reproject --heatmap` on the same corners, side by side.
# Usage: docs/images/make-reproject-picture.sh LIBCAM MRCAL_FOLDER
#   LIBCAM: the program (build/tools/libcam); MRCAL_FOLDER: the folder holding
#   opencv8-0.cameramodel and splined-0.cameramodel (mrcal's doc/data/figueroa-overpass-looking-S).
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 LIBCAM MRCAL_FOLDER (holding opencv8-0.cameramodel and splined-0.cameramodel)" >&2
  exit 2
fi
libcam=$1
folder=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
here=$(cd "$(dirname "$0")" && pwd)
"$libcam" reproject "$folder/opencv8-0.cameramodel" --heatmap "$work/opencv8.png" > /dev/null
"$libcam" reproject "$folder/splined-0.cameramodel" --heatmap "$work/splined.png" > /dev/null
/usr/bin/python3 - "$work/opencv8.png" "$work/splined.png" "$here/reproject-mrcal.png" <<'PY'
import sys, numpy as np, cv2
left, right = (cv2.imread(path) for path in sys.argv[1:3])
height = max(left.shape[0], right.shape[0])
pad = lambda image: cv2.copyMakeBorder(image, 0, height - image.shape[0], 0, 0, cv2.BORDER_CONSTANT)
gap = np.zeros((height, 16, 3), np.uint8)
cv2.imwrite(sys.argv[3], np.hstack([pad(left), gap, pad(right)]), [cv2.IMWRITE_PNG_COMPRESSION, 9])
PY
echo "wrote $here/reproject-mrcal.png"
