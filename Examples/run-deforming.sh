#!/usr/bin/env bash
# Two deforming bunnies moving into and out of contact, 100 frames through one
# vtkDistanceFieldProximity (Sud et al. (I3D 2006) §6.2): writes out/deforming_plot.png
# (separation and penetrations per frame) and out/deforming_frame_*.png, prints the
# per-frame time. Optional arguments: RESOLUTION (default 128) and FRAMES (default 100).
set -euo pipefail
cd "$(dirname "$0")/.."
./Testing/setup.sh
mkdir -p out
PYTHONPATH=build/lib/python3/dist-packages xvfb-run -a /usr/bin/python3 \
  Examples/Python/deforming_bunnies.py Testing/Data out "${1:-128}" "${2:-100}"
