#!/usr/bin/env bash
# Proximity by chamfer distance (Martinek et al. (VMV 2011) §6.3): writes out/proximity.png, a bunny
# next to a cow, its vertices coloured by the cow's chamfer field.
set -euo pipefail
cd "$(dirname "$0")/.."
./Testing/setup.sh
mkdir -p out
PYTHONPATH=build/lib/python3/dist-packages xvfb-run -a /usr/bin/python3 \
  Examples/Python/proximity.py Testing/Data out/proximity.png
