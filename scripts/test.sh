#!/usr/bin/env bash
# The whole test suite from a fresh clone: install what is missing, then
#   1. build and run every test (ctest) in build/;
#   2. the same suite built with AddressSanitizer + UndefinedBehaviorSanitizer in
#      build-asan/ (any report fails the test that hit it), but for the numerical
#      extremes and the long sweeps named below;
#   3. every libFuzzer target for a bounded time (LIBCAM_FUZZ_SECONDS each, default 6)
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
# The AVX2 and AVX-512 kernels too, and their tests, where the quick start built this
# folder without them.
bash "$root/scripts/build.sh" "$root/build" "${line_tables[@]}" -DLIBCAM_DISPATCH_KERNELS=ON
(cd "$root/build" && ctest --output-on-failure --parallel "$jobs" --timeout 900)
[ "${LIBCAM_QUICK:-0}" = 1 ] && exit 0

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
# The installed-package test links a consumer against the instrumented static libraries
# without the sanitizer runtime; it runs in step 1.
# The tests of numerical extremes (test_extremes) are not built here: they measure
# libcam's numbers against a 113-bit reference, through the same code the engine tests
# run here, at values chosen for their numbers rather than for new paths through memory.
# Building and running them under the sanitizers took 540 s of CPU (4.5 minutes of the
# two cores). Their sweep over a 100000-pixel-wide image, whose indices are large, goes
# with them: step 1 still runs it, without the sanitizers' checks of those indices.
# So do two sweeps of the engine's numbers: float against double on every lens model of
# the harness (100 s here) and the comparison with mrcal_unproject and cv::undistortPoints
# wherever they converge (67 s here), through the batch code the other harness and
# unprojection tests run here.
# So does the fit of mrcal's splined calibrations (72 s here): Ceres on a large model,
# through the fitting code the other fit tests run here.
# So does the comparison with mrcal's maps (277 s under the sanitizers, 17 s in step 1):
# eight full maps through the remap code the remap tests run here on smaller images.
# And Blender's renders (about 110 s in step 1; their program is not even built here): the
# time is Blender's, and the libcam code they run (the Blender camera files, projection,
# render plans) is tested here by the file, model and remap tests. And the new camera chosen for real lenses and for the
# lenses where OpenCV's choosers fail (197 s under the sanitizers, 20 s in step 1): whole
# maps of large real lenses, through the chooser and map code the other remap tests run
# here on smaller images. And two sweeps over whole real reconstructions (88 s under the
# sanitizers, 4 s in step 1): the table of real reconstructions, each against its tool's
# number, and the dataset run over real COLMAP models, through the readers and dataset code
# the other tests (and the fuzz targets) run here on small files.
# And the calibrations of boards rendered through a lens (about 95 s each under the
# sanitizers, 10 s in step 1): OpenCV's detectors and Ceres fits over many views, through
# the calibrate code the command-line and sample-image calibrate tests run here.
asan_skipped="Calibrate: a chessboard through|Calibrate: a ChArUco board through|install_consumer|The new camera for real lenses|The new camera where OpenCV's choosers fail|mrcal's splined calibrations become an OpenCV model|peers: libcam's remap maps against mrcal|rays both ways agree on every pixel of a 1920x1080 image|CAHVORE: libcam's rays reproject through mrcal_project|harness: float agrees with double within a multiple of float's epsilon|Unprojection agrees with mrcal_unproject and cv::undistortPoints wherever they converge inside the domain|Every real reconstruction and calibration libcam reads|dataset: real COLMAP models keep each point.s reprojection error"
(cd "$root/build-asan" && ctest --output-on-failure --parallel "$jobs" --timeout 1800 -E "$asan_skipped")

echo "== 3/3: fuzzing every reader and the number parser"
CXX=clang++ LIBCAM_BUILD_TARGET=fuzzers bash "$root/scripts/build.sh" "$root/build-fuzz" "${line_tables[@]}" -DLIBCAM_FUZZ=ON -DLIBCAM_BUILD_TESTS=OFF \
  -DLIBCAM_BUILD_TOOLS=OFF -DLIBCAM_BUILD_BENCHMARKS=OFF -DLIBCAM_FUZZ_SECONDS="${LIBCAM_FUZZ_SECONDS:-6}"
# Two at a time: each fuzzer is one process on one core.
(cd "$root/build-fuzz" && ctest --output-on-failure -L fuzz --parallel "$jobs" --timeout 600)
