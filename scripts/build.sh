#!/usr/bin/env bash
# Configures and builds libcam.
# Usage: scripts/build.sh [BUILD_DIR [extra cmake arguments...]]   (default BUILD_DIR: ./build)
# LIBCAM_BUILD_TARGET=NAME builds that target (and what it needs) instead of everything;
# several names separated by spaces build each.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-${LIBCAM_BUILD_DIR:-$root/build}}"
shift || true
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
# ccache, where it is installed, keeps every compiled file by its contents: a second
# build of the same sources (another checkout, the sanitizer tree's unchanged flags, the
# next run on this machine) takes the objects from it. Paths are hashed relative to the
# source tree and the working folder is left out, so a fresh clone elsewhere hits too.
launcher=()
if command -v ccache >/dev/null 2>&1 && [ "${LIBCAM_CCACHE:-1}" = 1 ]; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=1 CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-include_file_mtime,include_file_ctime,time_macros}"
  export CCACHE_MAXSIZE="${CCACHE_MAXSIZE:-20G}"
fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" "${generator[@]}" "${launcher[@]}" -DCMAKE_BUILD_TYPE="${LIBCAM_BUILD_TYPE:-RelWithDebInfo}" "$@"
elif [ "$#" -gt 0 ]; then
  # Settings given again are applied to the existing folder (the quick start's build/
  # without the AVX kernels, then scripts/test.sh's with them).
  cmake -S "$root" -B "$build" "$@" > /dev/null
fi
targets=()
for target in ${LIBCAM_BUILD_TARGET:-}; do targets+=(--target "$target"); done
cmake --build "$build" --parallel "$(nproc)" "${targets[@]}"
