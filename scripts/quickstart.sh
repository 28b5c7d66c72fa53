#!/usr/bin/env bash
# The main job on the built-in example: install what is missing, build the program, then
# convert the two worked example cameras and check every ray against OpenCV and mrcal.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/scripts/install-deps.sh"
# Only what the demo runs: the program and its commands module (tools/CMakeLists.txt), not
# the tests, benchmarks or Python module (scripts/test.sh builds those in the same folder).
# Line tables only (-g1), as scripts/test.sh builds: a third less time than full -g. The
# batch kernels for SSE2 alone (LIBCAM_DISPATCH_KERNELS=OFF: the same results; the AVX2 and
# AVX-512 copies are two of the three longest files to compile); scripts/test.sh adds them.
LIBCAM_BUILD_TARGET="libcam_cli libcam_commands" bash "$root/scripts/build.sh" "${LIBCAM_BUILD_DIR:-$root/build}" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DLIBCAM_DISPATCH_KERNELS=OFF
"${LIBCAM_BUILD_DIR:-$root/build}/tools/libcam" demo
