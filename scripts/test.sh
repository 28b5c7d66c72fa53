#!/usr/bin/env bash
# The whole test suite from a fresh clone: install what is missing, then
#   1. build and run every test (ctest) in build/;
#   2. the same suite built with AddressSanitizer + UndefinedBehaviorSanitizer in
#      build-asan/ (any report fails the test that hit it), but for the numerical
#      extremes and the long sweeps named below;
#   3. every libFuzzer target for a bounded time (LIBCAM_FUZZ_SECONDS each, default 6)
#      in build-fuzz/, built with clang.
# LIBCAM_QUICK=1 runs step 1 only. LIBCAM_FREE_DISK=1 (.ci/run sets it) removes each step's
# build folder once its tests pass: the three trees take 2.2, 4.0 and 2.9 GB, more together
# than a small machine has free, and only one is needed at a time (compiled files stay in
# ccache).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
jobs="$(nproc)"
bash "$root/scripts/install-deps.sh"
# Line tables only (-g1): enough for a sanitizer's or a debugger's backtrace with file and
# line, and the build of step 1 takes a third less time than with full debug information
# (-g): 231 s against 353 s on two cores.
line_tables=(-DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG")

echo "== 1/3: build and test"
# The AVX2 and AVX-512 kernels too, and their tests, where the quick start built this
# folder without them.
bash "$root/scripts/build.sh" "$root/build" "${line_tables[@]}" -DLIBCAM_DISPATCH_KERNELS=ON
(cd "$root/build" && ctest --output-on-failure --parallel "$jobs" --timeout 900)
[ "${LIBCAM_QUICK:-0}" = 1 ] && exit 0
free_disk() { if [ "${LIBCAM_FREE_DISK:-0}" = 1 ]; then rm -rf "$1"; fi; }
free_disk "$root/build"

echo "== 2/3: the tests again under AddressSanitizer + UndefinedBehaviorSanitizer"
# -O1, as the sanitizers' own documentation advises: the same code paths, and the build
# takes a third less time (the heaviest file: 98 s against 151 s at -O2, on two cores).
# GCC, not clang: clang compiles it faster (10.6 min against 14.5 on two cores, at -O2)
# but its instrumented tests ran 1.8 to 3 times slower (the 100000-pixel sweep: 192 s
# against 62 s), which costs more than the build saves.
bash "$root/scripts/build.sh" "$root/build-asan" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DLIBCAM_SANITIZE=ON \
  -DLIBCAM_BUILD_BENCHMARKS=OFF
# The test programs' own files are not instrumented (tests/CMakeLists.txt says why);
# libcam's libraries and the `libcam` program are.
# allocator_may_return_null: an allocation too large for the machine returns null, as
# glibc's malloc does, instead of aborting the test. libmrcal asks for one when a
# .cameramodel names a spline of absurd size (the file-error tests give it one, to check
# that libmrcal refuses it as libcam does); libmrcal then says "malloc() failed".
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:allocator_may_return_null=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# The long sweeps (tagged [sweep]), the installed-package test, Blender's renders and the
# comparison of whole maps with mrcal's are not registered in this build: they run in
# step 1 (tests/CMakeLists.txt says why).
(cd "$root/build-asan" && ctest --output-on-failure --parallel "$jobs" --timeout 1800)
free_disk "$root/build-asan"

echo "== 3/3: fuzzing every reader and the number parser"
CXX=clang++ LIBCAM_BUILD_TARGET=fuzzers bash "$root/scripts/build.sh" "$root/build-fuzz" "${line_tables[@]}" -DLIBCAM_FUZZ=ON -DLIBCAM_BUILD_TESTS=OFF \
  -DLIBCAM_BUILD_TOOLS=OFF -DLIBCAM_BUILD_BENCHMARKS=OFF -DLIBCAM_FUZZ_SECONDS="${LIBCAM_FUZZ_SECONDS:-6}"
# Two at a time: each fuzzer is one process on one core.
(cd "$root/build-fuzz" && ctest --output-on-failure -L fuzz --parallel "$jobs" --timeout 600)
