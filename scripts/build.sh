#!/usr/bin/env bash
# Configures and builds libcam into ./build (Release with assertions of its own tests).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${LIBCAM_BUILD_DIR:-$root/build}"
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE="${LIBCAM_BUILD_TYPE:-RelWithDebInfo}"
fi
cmake --build "$build" --parallel "$(nproc)"
