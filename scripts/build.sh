#!/usr/bin/env bash
# Installs what Brume needs on Debian 12 (only the missing packages), then
# configures and builds it in ./build (Ninja, Release).
#   scripts/build.sh            # set up and build
#   BUILD_DIR=other scripts/build.sh
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  # ParaView 5.11 and the VTK 9.2 it ships (the primary stack), with what its
  # CMake package needs.
  paraview paraview-dev python3-paraview libglew-dev
  qtbase5-dev qttools5-dev libqt5svg5-dev qtxmlpatterns5-dev-tools
  # What ParaView's CMake package asks for when the plugin and charts are built.
  libopenmpi-dev libdouble-conversion-dev libutfcpp-dev liblz4-dev liblzma-dev
  libexpat1-dev libxml2-dev libfreetype-dev libpng-dev libjpeg-dev libtiff-dev
  zlib1g-dev libeigen3-dev
  # Ray casting, volumes, OpenGL with no X server (EGL or OSMesa).
  libembree-dev libopenvdb-dev libboost-iostreams-dev libegl-dev libegl-mesa0
  libosmesa6-dev
  # The brume command line's parser and the counter-based random numbers
  # (both header-only).
  libcli11-dev librandom123-dev
  # Tools and test frameworks; mpirun for distributed runs and their tests.
  cmake ninja-build g++ git libgtest-dev libbenchmark-dev openmpi-bin
  # callgrind counts the phases' instructions (Brume.InstructionCounts).
  valgrind
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "brume: installing ${#missing[@]} Debian packages: ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then
    sudo_cmd=(sudo)
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

build_dir=${BUILD_DIR:-build}
warnings_as_errors=OFF
if [ "${CI:-}" = "true" ]; then
  warnings_as_errors=ON
fi
# pyenv's python3 may come first on PATH: ParaView's Python is the system one.
cmake -S . -B "$build_dir" -G Ninja \
  -DCMAKE_BUILD_TYPE=Release \
  -DPython3_EXECUTABLE=/usr/bin/python3 \
  -DBRUME_WARNINGS_AS_ERRORS="$warnings_as_errors"
# Two jobs fit the 2-core, 24 GiB machines.
cmake --build "$build_dir" --parallel "${BUILD_JOBS:-2}"
