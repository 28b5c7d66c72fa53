#!/usr/bin/env bash
# The main job on the built-in example: install what is missing, build, then convert the
# two worked example cameras and check every ray against OpenCV and mrcal.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
bash "$root/scripts/build.sh"
"${LIBCAM_BUILD_DIR:-$root/build}/tools/libcam" demo
