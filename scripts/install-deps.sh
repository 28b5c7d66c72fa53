#!/usr/bin/env bash
# Installs the Debian 12 packages libcam needs, only those that are missing.
# Idempotent: a second run installs nothing and exits 0.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  ccache                 # keeps compiled files between builds (scripts/build.sh)
  libeigen3-dev          # core math
  libopencv-dev          # reference
  libopencv-contrib-dev  # reference: cv::omnidir (the unified camera model)
  libmrcal-dev mrcal python3-mrcal mrgingham   # reference + .cameramodel files; mrgingham: chessboard corners beside libcam's
  catch2                 # tests (2.13)
  libcli11-dev           # command-line parsing
  nlohmann-json3-dev     # JSON camera files
  libyaml-cpp-dev        # YAML camera files (OpenCV, and the YAML of other tools)
  libpugixml-dev         # OpenCV's XML camera files
  libzip-dev             # the .npz archive of mrcal's observations in a .cameramodel
  libopenexr-dev         # remap maps written as two-channel EXR images
  libbenchmark-dev       # micro-benchmarks
  libceres-dev           # model fitting
  libboost-dev           # multiprecision reference
  clang libclang-rt-14-dev   # libFuzzer and its sanitizer runtimes
  colmap                 # reference: COLMAP's own program reads the models libcam writes
  python3-numpy python3-opencv   # reference: the remap tests against mrcal's and COLMAP's maps; the Python module
  pybind11-dev python3-pytest    # the Python module (import libcam) and its tests
  python3-distributed    # Dask: the Python test and example that spread libcam dataset's image tasks over worker processes
  blender                # reference: Cycles renders through the cameras libcam writes for Blender
  hugin-tools            # reference: Hugin's pano_trafo maps pixels through a .pto's a b c d e (lens databases)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
