#!/usr/bin/env bash
# Installs what the project needs on Debian 12 (as root) and builds it into ./build.
set -euo pipefail
cd "$(dirname "$0")/.."
# clang and its runtime libraries: the libFuzzer target (Testing/run-fuzz.sh); dpkg-dev
# and file: cpack's Debian packages (Testing/run-install-tests.sh).
packages="cmake g++ make pkg-config libvtk9-dev python3-vtk9 python3-numpy libegl-dev
  libegl1-mesa-dev libgl1-mesa-dri libgles-dev libosmesa6-dev libepoxy-dev libglm-dev libqhull-dev
  libboost-dev libcgal-dev libgmp-dev libmpfr-dev libopenvdb-dev python3-openvdb
  xvfb xauth openmpi-bin
  clang libclang-rt-14-dev dpkg-dev file"
./Testing/install-packages.sh $packages
# DF_WERROR=ON (CI) makes a compiler warning in the project's sources an error.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3 \
  -DDF_WERROR="${DF_WERROR:-OFF}" >/dev/null
cmake --build build -j "$(nproc)"
