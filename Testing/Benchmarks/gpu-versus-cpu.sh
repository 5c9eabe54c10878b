#!/usr/bin/env bash
# Benchmark (not a test): vtkdf linfac (unsigned Distance, the whole run) on the GPU
# backend and on the CPU backend of the same host, interleaved run by run; on a machine
# without a GPU the GPU backend runs on Mesa's llvmpipe, on the same cores, which
# measures the GPU path's work rather than its speed. Each run is a new process: the GPU
# side pays for making its context and compiling its programs.
# usage: Testing/Benchmarks/gpu-versus-cpu.sh BUILD_DIR MESH_DIR "MESH:N ..." [REPS]
# e.g.   Testing/Benchmarks/gpu-versus-cpu.sh build ~/meshes \
#          "bunny_75k:96 bunny_75k:128 armadillo_52k:96 armadillo_52k:128 dragon_871k:64" 5
# Prints, per row, the medians of REPS runs of each backend (time_s and the scan stage),
# their ratio, the culling factors (distance evaluations a sample) of both, and whether
# the two backends' outputs are the same bytes.
set -euo pipefail
build=${1:?usage: see the header}
meshes=${2:?usage: see the header}
rows=${3:?usage: see the header}
reps=${4:-5}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
field() { grep -oE "$1[=:][^ ,]*" | head -1 | cut -c$((${#1} + 2))- | grep . || echo nan; }
printf "%-14s %4s %8s %8s %8s %8s %6s %9s %9s %s\n" mesh N gpu_s scan_s cpu_s scan_s ratio evals_gpu evals_cpu outputs
for row in $rows; do
  mesh=${row%%:*} n=${row##*:}
  for backend in gpu cpu; do : >"$out/$backend.time" >"$out/$backend.scan"; done
  for _ in $(seq "$reps"); do
    for backend in gpu cpu; do
      line=$("$build/bin/vtkdf" linfac "$meshes/$mesh.vtp" -o "$out/$backend.vti" \
        --resolution "$n" --arrays distance --backend "$backend" --timing 2>&1 | grep '^vtkdf:')
      field time_s <<<"$line" >>"$out/$backend.time"
      field scan <<<"$line" >>"$out/$backend.scan"
      field culling_factor <<<"$line" >"$out/$backend.evals"
    done
  done
  same=$(cmp -s "$out/gpu.vti" "$out/cpu.vti" && echo same || echo DIFFERENT)
  g=$(median <"$out/gpu.time") c=$(median <"$out/cpu.time")
  printf "%-14s %4s %8.3f %8.3f %8.3f %8.3f %6.2f %9s %9s %s\n" "$mesh" "$n" "$g" \
    "$(median <"$out/gpu.scan")" "$c" "$(median <"$out/cpu.scan")" \
    "$(awk -v a="$g" -v b="$c" 'BEGIN {print a / b}')" "$(cat "$out/gpu.evals")" \
    "$(cat "$out/cpu.evals")" "$same"
done
