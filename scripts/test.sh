#!/usr/bin/env bash
# The whole test suite from a fresh clone: install what is missing, then
#   1. build and run every test (ctest) in build/;
#   2. the same suite built with AddressSanitizer + UndefinedBehaviorSanitizer in
#      build-asan/ (any report fails the test that hit it), but for four long numerical
#      sweeps (see below);
#   3. every libFuzzer target for a bounded time (LIBCAM_FUZZ_SECONDS each, default 12)
#      in build-fuzz/, built with clang.
# LIBCAM_QUICK=1 runs step 1 only.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
jobs="$(nproc)"
bash "$root/scripts/install-deps.sh"
# Line tables only (-g1): enough for a sanitizer's or a debugger's backtrace with file and
# line, and the build of step 1 takes a third less time than with full debug information
# (-g): 231 s against 353 s on two cores.
line_tables=(-DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG")

echo "== 1/3: build and test"
bash "$root/scripts/build.sh" "$root/build" "${line_tables[@]}"
(cd "$root/build" && ctest --output-on-failure --parallel "$jobs" --timeout 900)
[ "${LIBCAM_QUICK:-0}" = 1 ] && exit 0

echo "== 2/3: the tests again under AddressSanitizer + UndefinedBehaviorSanitizer"
# -O1, as the sanitizers' own documentation advises: the same code paths, and the build
# takes a third less time (the heaviest file: 98 s against 151 s at -O2, on two cores).
# Built by clang, as the fuzzers are: it compiles libcam's templates under the sanitizers
# in half GCC's time (test_lens_harness.cpp: 63 s against 135 s, side by side), and the
# suite is then compiled by two compilers.
CXX=clang++ bash "$root/scripts/build.sh" "$root/build-asan" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DLIBCAM_SANITIZE=ON \
  -DLIBCAM_BUILD_BENCHMARKS=OFF
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# The installed-package test links a consumer against the instrumented static libraries
# without the sanitizer runtime; it runs in step 1.
# The six sweeps of numerical extremes below run in step 1 only: under the sanitizers
# they take 9 minutes of the two cores (580 s of CPU) and run the same code as the tests
# that do run here, at values chosen for their numbers, not for new paths through memory
# (the sweep over a 100000-pixel-wide image, whose indices are large, stays). So does the
# fit of mrcal's splined calibrations (72 s here): Ceres on a large model, through the
# fitting code the other fit tests run here.
# So does the comparison with mrcal's maps (277 s under the sanitizers, 17 s in step 1):
# eight full maps through the remap code the remap tests run here on smaller images.
# And Blender's renders (about 110 s in step 1): the time is Blender's, and the libcam code
# they run (the Blender camera files, projection, render plans) is tested here by the
# file, model and remap tests. And the new camera chosen for real lenses and for the
# lenses where OpenCV's choosers fail (197 s under the sanitizers, 20 s in step 1): whole
# maps of large real lenses, through the chooser and map code the other remap tests run
# here on smaller images.
asan_skipped="install_consumer|test_blender_render|The new camera for real lenses|The new camera where OpenCV's choosers fail|mrcal's splined calibrations become an OpenCV model|extremes: batch methods at the focal lengths of 1e-6|extremes: batch methods just inside and just outside the fold-over radius|peers: libcam's remap maps against mrcal|extremes: nothing is NaN or infinite without the invalid flag|extremes: the fold-over radius of each OpenCV model|rays both ways agree on every pixel of a 1920x1080 image|CAHVORE: libcam's rays reproject through mrcal_project"
(cd "$root/build-asan" && ctest --output-on-failure --parallel "$jobs" --timeout 1800 -E "$asan_skipped")

echo "== 3/3: fuzzing every reader and the number parser"
CXX=clang++ LIBCAM_BUILD_TARGET=fuzzers bash "$root/scripts/build.sh" "$root/build-fuzz" "${line_tables[@]}" -DLIBCAM_FUZZ=ON -DLIBCAM_BUILD_TESTS=OFF \
  -DLIBCAM_BUILD_TOOLS=OFF -DLIBCAM_BUILD_BENCHMARKS=OFF -DLIBCAM_FUZZ_SECONDS="${LIBCAM_FUZZ_SECONDS:-12}"
# Two at a time: each fuzzer is one process on one core.
(cd "$root/build-fuzz" && ctest --output-on-failure -L fuzz --parallel "$jobs" --timeout 600)
