#!/usr/bin/env bash
# Benchmark (not a test): field + medial axis (vtkdf medial --timing) on armadillo_52k and
# bunny_75k at 128^3 and 256^3, both backends (on the GPU from a mesh, field and medial
# pass are one fused GPU pass: their sum is in field_s).
# usage: Testing/Benchmarks/medial.sh BUILD_DIR MESH_DIR [SIZES] [BACKENDS]
set -euo pipefail
build=${1:-build}
meshes=${2:?usage: Testing/Benchmarks/medial.sh BUILD_DIR MESH_DIR (see the usage line above)}
sizes=${3:-"128 256"}
backends=${4:-"cpu gpu"}
out=$(mktemp -d)
printf "%-14s %5s %-12s %-7s %9s %9s %9s %8s  %s\n" mesh N dims backend total_s field_s medial_s voxels renderer
for mesh in armadillo_52k bunny_75k; do
  for n in $sizes; do
    for backend in $backends; do
      line=$("$build/bin/vtkdf" medial "$meshes/$mesh.vtp" -o "$out/m.vti" --resolution "$n" \
        --backend "$backend" --timing | grep '^vtkdf:') || { echo "$mesh $n $backend: failed"; continue; }
      dims=$(sed -E 's/.*dims=([0-9x]+).*/\1/' <<<"$line")
      t=$(sed -E 's/.*time_s=([0-9.]+).*/\1/' <<<"$line")
      if grep -q 'field+medial:' <<<"$line"; then  # GPU from a mesh: one fused pass
        f=$(sed -E 's/.*field\+medial:([0-9.]+).*/\1/' <<<"$line"); m=0
      else
        f=$(sed -E 's/.*field:([0-9.]+).*/\1/' <<<"$line")
        m=$(sed -E 's/.*medial:([0-9.]+).*/\1/' <<<"$line")
      fi
      v=$(sed -E 's/.*medial_voxels=([0-9]+).*/\1/' <<<"$line")
      r=$(sed -E 's/.*renderer="([^"]*)".*/\1/' <<<"$line")
      printf "%-14s %5s %-12s %-7s %9.3f %9.3f %9.3f %8s  %s\n" "$mesh" "$n" "$dims" "$backend" \
        "$t" "$f" "$m" "$v" "$r"
    done
  done
done
rm -rf "$out"
