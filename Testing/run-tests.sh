#!/usr/bin/env bash
# Sets up (Testing/setup.sh) and runs the whole test suite. Tests that open a render
# window need an X server: the suite runs under xvfb-run, with -noreset (an X server
# resets when its last client disconnects and refuses connections meanwhile: a test that
# opens its next window just then would fail).
set -euo pipefail
cd "$(dirname "$0")/.."
./Testing/setup.sh
cd build
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure -j "$(nproc)"
