#!/usr/bin/env bash
# The main job on a bundled mesh: the exact signed distance field of the Stanford bunny
# on a 96^3 grid, both backends, written to out/ (.vti to open in ParaView, .png slice).
set -euo pipefail
cd "$(dirname "$0")/.."
./Testing/setup.sh
mkdir -p out
for backend in cpu gpu; do
  ./build/bin/vtkdf linfac Testing/Data/bunny_small.vtp -o out/bunny_$backend.vti \
    --resolution 96 --signed --arrays distance,cellid,feature,point \
    --backend $backend --png out/bunny_$backend.png --timing
done
echo "wrote out/bunny_cpu.vti out/bunny_cpu.png (and the GPU's out/bunny_gpu.*)"
