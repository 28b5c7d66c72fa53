#!/usr/bin/env bash
# Installs a built libcam into a temporary prefix, builds examples/consumer against the
# installed CMake package (and a pkg-config build of the same source), runs both, and
# checks the printed ray against the seed's worked answer.
# Usage: scripts/test-install.sh BUILD_DIR
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:?usage: test-install.sh BUILD_DIR}" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
for path in bin/libcam include/libcam/version.hpp include/libcam/convert/fov_convert.hpp \
            lib/cmake/libcam/libcamConfig.cmake lib/pkgconfig/libcam.pc lib/pkgconfig/libcam-core.pc \
            lib/pkgconfig/libcam-fit.pc; do
  [ -e "$work/prefix/$path" ] || { echo "test-install: missing $path in the install"; exit 1; }
done
"$work/prefix/bin/libcam" --version | grep -q "^libcam " || { echo "test-install: libcam --version"; exit 1; }

# Expected: the seed's d at (0, 0) is (-2/3, -sqrt2/3 - 1/sqrt2, sqrt2/3 - 1/sqrt2), normalised.
check() {
  awk -v out="$1" 'BEGIN {
    s = sqrt(2); x = -2/3; y = -s/3 - 1/s; z = s/3 - 1/s; n = sqrt(x*x + y*y + z*z)
    split(out, lines, "\n"); ok = 0
    for (i in lines) if (lines[i] ~ /^direction /) {
      split(lines[i], f, " ")
      if ((f[2] - x/n)^2 + (f[3] - y/n)^2 + (f[4] - z/n)^2 < 1e-24) ok = 1
    }
    exit ok ? 0 : 1 }' || { echo "test-install: wrong ray from the consumer:"; echo "$1"; exit 1; }
}

cmake -S "$root/examples/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" \
      -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/consumer" > "$work/build.log"
check "$("$work/consumer/consumer")"
# libcam::fit: a FOV camera's simplest model is the FOV form itself.
check_fit() {
  echo "$1" | grep -q "^chosen FOV max " || { echo "test-install: wrong fit from the consumer:"; echo "$1"; exit 1; }
}
check_fit "$("$work/consumer/consumer_fit")"

# The same source through pkg-config.
export PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig"
c++ "$root/examples/consumer/main.cpp" -o "$work/consumer-pc" $(pkg-config --cflags --libs libcam-core)
check "$("$work/consumer-pc")"
c++ "$root/examples/consumer/fit_main.cpp" -o "$work/consumer-fit-pc" $(pkg-config --cflags --libs libcam-fit)
check_fit "$("$work/consumer-fit-pc")"
echo "test-install: the installed package builds and runs examples/consumer and its fit example (CMake and pkg-config)"
