#!/usr/bin/env bash
# Benchmark (not a test): the signed field with SignMode = WindingNumber against
# PseudoNormal, vtkdf linfac --sign winding|pseudonormal, both backends.
# usage: Testing/Benchmarks/winding.sh BUILD_DIR MESH_DIR [SIZES] [BACKENDS] [REPS] [MESHES]
# Columns: each mode's time (best of REPS), the winding sign stage alone, the ratio of
# the two times, the samples decided by blocks, by crossings along lines (closed meshes)
# and by the exact sum, and the fraction of
# samples whose sign differs between the two modes.
set -euo pipefail
build=${1:-build}
meshes=${2:?usage: Testing/Benchmarks/winding.sh BUILD_DIR MESH_DIR (see the usage line above)}
sizes=${3:-"128 256"}
backends=${4:-"cpu gpu"}
reps=${5:-3}
names=${6:-"bunny_75k aneurysm dragon_871k"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# Runs vtkdf REPS times; prints the fastest run's timing line (the .vti of the last run).
best() {
  local line="" run
  for _ in $(seq "$reps"); do
    run=$("$build/bin/vtkdf" linfac "$@" --timing | grep '^vtkdf:') || return 1
    if [ -z "$line" ] || awk -v a="$(sed -E 's/.*time_s=([0-9.]+).*/\1/' <<<"$run")" \
      -v b="$(sed -E 's/.*time_s=([0-9.]+).*/\1/' <<<"$line")" 'BEGIN{exit !(a < b)}'; then
      line=$run
    fi
  done
  echo "$line"
}
field() { sed -E "s/.*[ ,]$1[=:]([^ ,]+).*/\1/" <<<"$2"; }

printf "%-12s %4s %-12s %-4s %9s %9s %8s %6s %10s %10s %7s %9s  %s\n" mesh N dims back \
  pseudo_s winding_s sign_s ratio block_smp line_smp exact sign_diff renderer
for mesh in $names; do
  for n in $sizes; do
    for backend in $backends; do
      common=("$meshes/$mesh.vtp" --resolution "$n" --arrays distance --backend "$backend")
      p=$(best "${common[@]}" -o "$out/p.vti" --sign pseudonormal) || { echo "$mesh $n $backend: failed"; continue; }
      w=$(best "${common[@]}" -o "$out/w.vti" --sign winding) || { echo "$mesh $n $backend: failed"; continue; }
      diff=$(/usr/bin/python3 - "$out/p.vti" "$out/w.vti" <<'PY'
import sys
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy
import numpy as np
def distance(path):
    r = vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    return vtk_to_numpy(r.GetOutput().GetPointData().GetArray("Distance"))
p, w = distance(sys.argv[1]), distance(sys.argv[2])
print("%.3e" % np.mean((p < 0) != (w < 0)))
PY
)
      tp=$(field time_s "$p"); tw=$(field time_s "$w")
      printf "%-12s %4s %-12s %-4s %9.3f %9.3f %8.3f %6.2f %10s %10s %7s %9s  %s\n" "$mesh" "$n" \
        "$(field dims "$w")" "$backend" "$tp" "$tw" "$(field sign "$w")" \
        "$(awk -v a="$tw" -v b="$tp" 'BEGIN{print a/b}')" "$(field winding_block_samples "$w")" \
        "$(field winding_line_samples "$w")" \
        "$(field winding_exact_samples "$w")" "$diff" "$(sed -E 's/.*renderer="([^"]*)".*/\1/' <<<"$w")"
    done
  done
done
