#!/usr/bin/env bash
# Installs a built libcam into a temporary prefix and checks what a user gets:
# - every installed header compiles on its own (-fsyntax-only, two at a time), with only
#   the installed include folder, Eigen's and, for interop/ and dataset/ alone, OpenCV's;
# - no installed header includes, even through another, a header of a private dependency
#   (mrcal, Ceres, nlohmann JSON, yaml-cpp, pugixml, libzip, OpenEXR), nor OpenCV's outside
#   interop/ and dataset/ (whose public surface speaks cv::Mat by design); no detail/ folder;
# - examples/consumer builds against the installed CMake package, a program for each
#   library (core, io, reproject, interop, dataset, check, fit, report), and each runs and
#   prints the answer worked by hand; the same sources through pkg-config;
# - the camera-file consumer (libcam::io alone) compiled by hand with nothing but the
#   installed headers and Eigen sees no OpenCV, mrcal, Ceres, nlohmann, yaml-cpp or pugixml
#   header, nor links OpenCV's, mrcal's or Ceres's libraries.
# Usage: scripts/test-install.sh BUILD_DIR
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:?usage: test-install.sh BUILD_DIR}" && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
for path in bin/libcam include/libcam/version.hpp include/libcam/dataset/colmap_dataset.hpp \
            include/libcam/reproject/reproject.hpp lib/pkgconfig/libcam-dataset.pc lib/pkgconfig/libcam-reproject.pc include/libcam/convert/look_at_convert.hpp \
            include/libcam/io/camera_file.hpp include/libcam/interop/formats.hpp include/libcam/report/image.hpp \
            lib/cmake/libcam/libcamConfig.cmake lib/pkgconfig/libcam.pc lib/pkgconfig/libcam-core.pc \
            lib/pkgconfig/libcam-io.pc lib/pkgconfig/libcam-check.pc include/libcam/check/verify.hpp \
            lib/pkgconfig/libcam-fit.pc lib/pkgconfig/libcam-report.pc lib/pkgconfig/libcam-calibrate.pc \
            lib/pkgconfig/libcam-stereo.pc include/libcam/stereo/rectify.hpp \
            lib/libcam/libcam-commands.so; do
  [ -e "$work/prefix/$path" ] || { echo "test-install: missing $path in the install"; exit 1; }
done
# The detail/ folders (report's OpenCV helpers, io's per-format readers and the parsers'
# trees) stay inside their libraries.
detail_installed="$(find "$work/prefix/include/libcam" -type d -name detail)"
[ -z "$detail_installed" ] || { echo "test-install: installed a detail folder: $detail_installed"; exit 1; }
# Every installed header on its own, as the first line of a program; the headers each
# one pulls in (-MD) are held against the private dependencies.
compile_alone() {
  local header="$1" flags=(-I"$work/prefix/include" $(pkg-config --cflags eigen3))
  case "$header" in libcam/interop/* | libcam/dataset/*) flags+=($(pkg-config --cflags opencv4)) ;; esac
  local deps="$work/headers/${header//\//_}.d"
  if ! printf '#include "%s"\n' "$header" | c++ -std=c++20 -fsyntax-only "${flags[@]}" -MD -MF "$deps" -x c++ - \
       2> "$deps.err"; then
    echo "test-install: the installed $header does not compile on its own:"; head -5 "$deps.err"; return 1
  fi
  local private="mrcal|ceres/|nlohmann/|yaml-cpp/|pugixml|/zip\.h|OpenEXR/|Imath/"
  case "$header" in libcam/interop/* | libcam/dataset/*) ;; *) private="$private|opencv2/" ;; esac
  # The headers it pulled in, one a line, libcam's own left out.
  local outside; outside="$(tr ' \\' '\n\n' < "$deps" | grep -v -e '^$' -e ':$' -e "^$work/prefix/include/" | sort -u)"
  if echo "$outside" | grep -Eq "$private"; then
    echo "test-install: the installed $header includes a private dependency's header:"
    echo "$outside" | grep -E "$private" | head -5; return 1
  fi
}
export -f compile_alone
export work
mkdir "$work/headers"
(cd "$work/prefix/include" && find libcam -name '*.hpp' | sort) > "$work/header-list"
[ "$(wc -l < "$work/header-list")" -gt 50 ] || { echo "test-install: too few installed headers"; exit 1; }
# Run from an empty folder: a quoted include looks beside its source first, here stdin.
(cd "$work/headers" && xargs -P2 -n1 bash -c 'compile_alone "$0"' < "$work/header-list") ||
  { echo "test-install: installed headers that do not stand alone or include private headers (above)"; exit 1; }
"$work/prefix/bin/libcam" --version | grep -q "^libcam " || { echo "test-install: libcam --version"; exit 1; }
# The installed program starts without OpenCV (tools/libcam/commands_module.hpp) and
# finds its commands module in lib/libcam/ for the commands that need it.
if LD_DEBUG=libs "$work/prefix/bin/libcam" --version 2>&1 >/dev/null | grep -q "calling init: .*opencv"; then
  echo "test-install: the installed libcam --version loads OpenCV"; exit 1
fi
"$work/prefix/bin/libcam" verify --help | grep -q -- "--grid" || { echo "test-install: the installed libcam verify --help"; exit 1; }
"$work/prefix/bin/libcam" demo | grep -q "all checks pass" || { echo "test-install: the installed libcam demo"; exit 1; }

# The Python module, where the build made one: installed under the prefix (its
# site-packages folder relative to it) and importable from there by the interpreter it
# was built for, with the version the program prints.
if [ -f "$build/python/libcam/__init__.py" ]; then
  python="$(sed -n 's/^LIBCAM_PYTHON_EXECUTABLE:INTERNAL=//p' "$build/CMakeCache.txt")"
  package="$(find "$work/prefix" -path '*/libcam/__init__.py' -print -quit)"
  [ -n "$package" ] || { echo "test-install: the Python package is missing from the install"; exit 1; }
  version="$(cd "$work" && PYTHONPATH="$(dirname "$(dirname "$package")")" "$python" -c "import libcam; print(libcam.__version__)")"
  [ "libcam $version" = "$("$work/prefix/bin/libcam" --version | head -1 | cut -d' ' -f1-2)" ] ||
    { echo "test-install: import libcam from the install printed '$version'"; exit 1; }
fi

# Expected: for the camera at eye (0,5,5) looking at the origin (90 degrees, 3x3), the
# look-at formula's d at pixel (0, 0), counted from the bottom-left, is
# (-2/3, -sqrt2/3 - 1/sqrt2, sqrt2/3 - 1/sqrt2), normalised.
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
# libcam::fit: a graphics camera's simplest model is the look-at form itself.
check_fit() {
  echo "$1" | grep -q "^chosen LOOK_AT max " || { echo "test-install: wrong fit from the consumer:"; echo "$1"; exit 1; }
}
check_fit "$("$work/consumer/consumer_fit")"

# libcam::io alone reads a JSON camera and an OpenCV YAML one (written here by the
# installed program) and refuses an mrcal one, naming libcam::interop and the call that
# registers it.
"$work/prefix/bin/libcam" convert --fov 90 --size 3x3 --eye 0,5,5 --target 0,0,0 -o "$work/camera.json"
"$work/prefix/bin/libcam" convert --from "$work/camera.json" --to opencv-yaml -o "$work/camera.yaml"
"$work/prefix/bin/libcam" convert --from "$work/camera.json" --to cameramodel -o "$work/camera.cameramodel"
check "$("$work/consumer/consumer_io" "$work/camera.json")"
check "$("$work/consumer/consumer_io" "$work/camera.yaml")"
check_io_refuses_cameramodel() {
  if "$1" "$work/camera.cameramodel" 2> "$work/io.err"; then echo "test-install: $1 read a .cameramodel without libcam::interop"; exit 1; fi
  grep -q "register_interop_formats" "$work/io.err" || { echo "test-install: unclear error from $1:"; cat "$work/io.err"; exit 1; }
}
check_io_refuses_cameramodel "$work/consumer/consumer_io"

# A program for each library above io, each with an answer known without libcam.
run_consumer() {  # NAME EXPECTED-LINE [ARGUMENTS]
  local name="$1" expected="$2"; shift 2
  [ -x "$work/consumer/$name" ] || { echo "test-install: examples/consumer did not build $name"; exit 1; }
  local out; out="$("$work/consumer/$name" "$@")" || { echo "test-install: $name failed:"; echo "$out"; exit 1; }
  echo "$out" | grep -qx -- "$expected" || { echo "test-install: $name printed, not '$expected':"; echo "$out"; exit 1; }
}
# The origin projects to the centre pixel (1, 1), observed at (1.5, 1): half a pixel.
echo "$("$work/consumer/consumer_reproject")" | awk '$1 == "residual_px" { ok = ($2 - 0.5)^2 < 1e-24 } END { exit !ok }' ||
  { echo "test-install: consumer_reproject's residual is not 0.5 pixels"; "$work/consumer/consumer_reproject"; exit 1; }
# mrcal's .cameramodel, read through the installed libcam::interop, holds the same camera.
check "$("$work/consumer/consumer_interop" "$work/camera.cameramodel")"
run_consumer consumer_dataset "images /data/scene/images"
# Two pinholes 0.5 apart: the disparity of a point 4 in front gives back depth 4.
echo "$("$work/consumer/consumer_stereo")" | awk '$1 == "baseline" { ok = ($2 - 0.5)^2 < 1e-24 && ($4 - 4)^2 < 1e-20 } END { exit !ok }' ||
  { echo "test-install: consumer_stereo's depth is not 4:"; "$work/consumer/consumer_stereo"; exit 1; }
run_consumer consumer_check "checks [1-9][0-9]* failed 0"
run_consumer consumer_report "png 89 50 4e 47 0d 0a 1a 0a"

# The same consumer by hand: only the installed include folder and Eigen's on the
# include path, only libcam's io and core libraries on the link line. The headers it
# sees are listed (-MD) and none may be OpenCV's, mrcal's, Ceres's or nlohmann's.
c++ -std=c++20 -MD -MF "$work/consumer-io.d" -I"$work/prefix/include" $(pkg-config --cflags eigen3) \
    "$root/examples/consumer/io_main.cpp" -o "$work/consumer-io-bare" -L"$work/prefix/lib" -lcam_io -lcam_core \
    -lyaml-cpp -lpugixml -lzip
if grep -Eiq "opencv|mrcal|ceres|nlohmann|yaml-cpp|pugixml|zip\.h" "$work/consumer-io.d"; then
  echo "test-install: the io consumer includes a header of OpenCV, mrcal, Ceres, nlohmann, yaml-cpp or pugixml:"
  grep -Eio "[^ ]*(opencv|mrcal|ceres|nlohmann|yaml-cpp|pugixml)[^ ]*" "$work/consumer-io.d" | sort -u
  exit 1
fi
check "$("$work/consumer-io-bare" "$work/camera.json")"
check "$("$work/consumer-io-bare" "$work/camera.yaml")"
check_io_refuses_cameramodel "$work/consumer-io-bare"

# The same sources through pkg-config; libcam-io's flags name no OpenCV, mrcal or Ceres.
export PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig"
io_flags="$(pkg-config --cflags --libs libcam-io)"
if echo "$io_flags" | grep -Eiq "opencv|mrcal|ceres"; then
  echo "test-install: pkg-config libcam-io names OpenCV, mrcal or Ceres: $io_flags"
  exit 1
fi
c++ "$root/examples/consumer/io_main.cpp" -o "$work/consumer-io-pc" $io_flags
check "$("$work/consumer-io-pc" "$work/camera.json")"
check "$("$work/consumer-io-pc" "$work/camera.yaml")"
c++ "$root/examples/consumer/main.cpp" -o "$work/consumer-pc" $(pkg-config --cflags --libs libcam-core)
check "$("$work/consumer-pc")"
c++ "$root/examples/consumer/fit_main.cpp" -o "$work/consumer-fit-pc" $(pkg-config --cflags --libs libcam-fit)
check_fit "$("$work/consumer-fit-pc")"
echo "test-install: $(wc -l < "$work/header-list") installed headers compile alone and include no private dependency's; examples/consumer builds and runs against every library (CMake), and core, io and fit through pkg-config"
