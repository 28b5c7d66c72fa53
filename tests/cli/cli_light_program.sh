#!/usr/bin/env bash
# The `libcam` program starts light (tools/libcam/commands_module.hpp): it links neither
# OpenCV, libmrcal nor Ceres and loads none of them for --version or a JSON camera, while
# the commands that need them and mrcal's .cameramodel format still work through the
# commands module beside it; without the module, such a command fails in one line.
# Usage: tests/cli/cli_light_program.sh PATH_TO_LIBCAM
set -euo pipefail
program="${1:?usage: cli_light_program.sh PATH_TO_LIBCAM}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
heavy="opencv|mrcal|ceres|gdal|freeimage|cholmod"

fail() { echo "cli_light_program: $*"; exit 1; }

# Linked: the program's DT_NEEDED entries.
needed="$(readelf -d "$program" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')"
if echo "$needed" | grep -Eiq "$heavy"; then fail "the program links $(echo "$needed" | grep -Ei "$heavy" | tr '\n' ' ')"; fi

# Loaded: what the dynamic loader opens for --version, for --help and for a JSON camera.
loaded() { LD_DEBUG=libs "$@" 2>&1 >/dev/null | sed -n 's/.*calling init: //p'; }
"$program" convert --fov 90 --size 640x480 -o "$work/camera.json"
for run in "--version" "--help" "info $work/camera.json" "convert --from $work/camera.json --to opencv-yaml"; do
  # shellcheck disable=SC2086 # the flags are split on purpose
  libraries="$(loaded "$program" $run)"
  if echo "$libraries" | grep -Eiq "$heavy"; then fail "libcam $run loaded $(echo "$libraries" | grep -Ei "$heavy" | head -3 | tr '\n' ' ')"; fi
done

# --help lists every command, the module's too.
for command in convert info rays project derive remap rectify dataset render-plan verify fit bench demo; do
  "$program" --help | grep -Eq "^  $command " || fail "libcam --help does not list $command"
done

# A heavy command and its own help run in the module.
"$program" verify --help | grep -q -- "--grid" || fail "libcam verify --help does not show verify's flags"
"$program" demo | grep -q "all checks pass" || fail "libcam demo did not pass"

# mrcal's .cameramodel from the light commands: written, read back, described.
"$program" convert --from "$work/camera.json" --to cameramodel -o "$work/camera.cameramodel"
"$program" convert --from "$work/camera.cameramodel" --to json -o "$work/back.json"
"$program" info "$work/camera.cameramodel" | grep -q "cameramodel, 1 camera" || fail "libcam info on a .cameramodel"
# A broken one: the module's reader throws, the program reports it in one line.
echo "{ 'lensmodel': 'LENSMODEL_NOPE'" > "$work/broken.cameramodel"
if "$program" info "$work/broken.cameramodel" 2> "$work/broken.err"; then fail "read a broken .cameramodel"; fi
[ "$(wc -l < "$work/broken.err")" = 1 ] && grep -q "^libcam: error: .*broken.cameramodel" "$work/broken.err" ||
  fail "unclear error for a broken .cameramodel: $(cat "$work/broken.err")"

# Without its module: one line naming the command and the file looked for, exit 1.
cp "$program" "$work/libcam"
set +e
"$work/libcam" verify "$work/camera.json" 2> "$work/missing.err"
status=$?
set -e
[ "$status" = 1 ] || fail "libcam verify without its module exited $status"
[ "$(wc -l < "$work/missing.err")" = 1 ] && grep -q "^libcam: error: libcam verify needs .*libcam-commands.so" "$work/missing.err" ||
  fail "unclear error without the module: $(cat "$work/missing.err")"
if "$work/libcam" info "$work/camera.cameramodel" 2> "$work/missing-format.err"; then fail "read a .cameramodel without the module"; fi
grep -q "^libcam: error: .*cameramodel format needs .*libcam-commands.so" "$work/missing-format.err" ||
  fail "unclear error for a .cameramodel without the module: $(cat "$work/missing-format.err")"
"$work/libcam" info "$work/camera.json" > /dev/null || fail "a light command needs the module"
echo "cli_light_program: the program links and loads no OpenCV, mrcal or Ceres for its light commands; the module runs the others and .cameramodel files"
