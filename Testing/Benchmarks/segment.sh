#!/usr/bin/env bash
# Benchmark (not a test): the segmented field (vtkdf segment, with --surface) next to the
# plain signed field (vtkdf linfac --signed) on the same grid: the overhead of
# segmentation, its stages, and the polygonization.
# usage: Testing/Benchmarks/segment.sh BUILD_DIR MESH_DIR [SIZES] [BACKENDS] [MESHES]
set -euo pipefail
build=${1:-build}
meshes=${2:?usage: Testing/Benchmarks/segment.sh BUILD_DIR MESH_DIR (see the usage line above)}
sizes=${3:-"128 256"}
backends=${4:-"cpu gpu"}
names=${5:-"max3ds_export snowden bunny_75k"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
field() { sed -E "s/.*[ ,]$1[=:]([^ ,]+).*/\1/" <<<"$2"; }
printf "%-14s %4s %-4s %9s %9s %9s %8s %8s %9s %9s %7s %8s\n" mesh N back signed_s segment_s \
  crossings patches field regions surface_s regions triangles
for mesh in $names; do
  for n in $sizes; do
    for backend in $backends; do
      common=("$meshes/$mesh.vtp" --resolution "$n" --backend "$backend" --timing)
      s=$("$build/bin/vtkdf" linfac "${common[@]}" -o "$out/s.vti" --signed --arrays distance |
        grep '^vtkdf: linfac') || { echo "$mesh $n $backend: failed"; continue; }
      g=$("$build/bin/vtkdf" segment "${common[@]}" -o "$out/g.vti" --surface "$out/g.vtp") ||
        { echo "$mesh $n $backend: failed"; continue; }
      seg=$(grep '^vtkdf: segment' <<<"$g")
      surf=$(grep '^vtkdf: surface' <<<"$g")
      segment_s=$(field time_s "$seg")
      # The surface's time: vtkSegmentedDistanceContour alone (vtkdf times it).
      # Stage times: the last "name:" in the line (regions= and patches= come before).
      printf "%-14s %4s %-4s %9.3f %9.3f %9.3f %8.3f %8.3f %9.3f %9.3f %7s %8s\n" "$mesh" "$n" "$backend" \
        "$(field time_s "$s")" "$segment_s" "$(sed -E 's/.*stages=crossings:([^,]+).*/\1/' <<<"$seg")" \
        "$(field patches "$seg")" "$(field field "$seg")" \
        "$(field regions "$seg")" "$(field time_s "$surf")" \
        "$(sed -E 's/.* regions=([0-9]+).*/\1/' <<<"$seg")" "$(field triangles "$surf")"
    done
  done
done
