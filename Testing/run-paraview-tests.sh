#!/usr/bin/env bash
# The ParaView plugin (run by .ci/run, as root, after Testing/run-tests.sh has built
# ./build against the system's VTK): installs Debian's ParaView 5.11, unpacks
# python3-paraview beside the build (it conflicts with python3-vtk9, so it is not
# installed: pvbatch alone gets its modules), builds the same sources against
# ParaView's VTK into ./build-paraview and runs its tests (Testing/ParaView) under
# xvfb-run.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
./Testing/install-packages.sh paraview paraview-dev xvfb xauth
build="$root/build-paraview"
unpacked="$build/python3-paraview"
if [ ! -d "$unpacked/usr/lib/python3/dist-packages/paraview" ]; then
  mkdir -p "$build/download"
  (cd "$build/download" && apt-get download -qq python3-paraview)
  dpkg -x "$build"/download/python3-paraview_*.deb "$unpacked"
fi
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DParaView_DIR=/usr/lib/x86_64-linux-gnu/cmake/paraview-5.11 \
  -DDF_PARAVIEW_PYTHON_ROOT="$unpacked" -DDF_SYSTEM_BUILD_DIR="$root/build" >/dev/null
cmake --build "$build" -j "$(nproc)"
cd "$build"
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure -j "$(nproc)"
