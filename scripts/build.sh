#!/usr/bin/env bash
# Configures and builds libcam.
# Usage: scripts/build.sh [BUILD_DIR [extra cmake arguments...]]   (default BUILD_DIR: ./build)
# LIBCAM_BUILD_TARGET=NAME builds that target (and what it needs) instead of everything.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-${LIBCAM_BUILD_DIR:-$root/build}}"
shift || true
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE="${LIBCAM_BUILD_TYPE:-RelWithDebInfo}" "$@"
fi
cmake --build "$build" --parallel "$(nproc)" ${LIBCAM_BUILD_TARGET:+--target "$LIBCAM_BUILD_TARGET"}
