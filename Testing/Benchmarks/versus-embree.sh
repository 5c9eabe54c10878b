#!/usr/bin/env bash
# Benchmark (not a test): vtkdf linfac (CPU, unsigned Distance, whole run: reading
# excluded, conversion and sites included) against Embree's point query on the same grid,
# interleaved run by run, with the peak RSS of each of our runs (/usr/bin/time -v).
# The peer is the `embree-pq-hint` of a distance-field peer harness that takes
# `run MESH --peer embree-pq-hint --n N --threads T --reps 1` and prints a row with the
# peer's time_s (its tree build included); give its binary as PEERS, or "none" to time
# ours alone.
# usage: Testing/Benchmarks/versus-embree.sh BUILD_DIR MESH_DIR PEERS "MESH:N ..." [REPS]
# e.g.   Testing/Benchmarks/versus-embree.sh build ~/meshes ~/peers/build/peers \
#          "dragon_871k:32 dragon_871k:64 dragon_871k:128 bunny_75k:128" 5
# Prints, per row, the medians of REPS runs of each side, their ratio and the range of
# the run-by-run ratios, our peak RSS and the stages of our median run.
set -euo pipefail
build=${1:?usage: see the header}
meshes=${2:?usage: see the header}
peers=${3:?usage: see the header}
rows=${4:?usage: see the header}
reps=${5:-5}
threads=2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
printf "%-14s %4s %9s %9s %7s %-13s %8s  %s\n" mesh N ours_s embree_s ratio "ratio range" rss_MB "stages (our median run)"
for row in $rows; do
  mesh=${row%%:*} n=${row##*:}
  : >"$out/ours" >"$out/peer" >"$out/ratio" >"$out/rss" >"$out/stages"
  for _ in $(seq "$reps"); do
    line=$(VTK_SMP_MAX_THREADS=$threads /usr/bin/time -v -o "$out/time" "$build/bin/vtkdf" linfac \
      "$meshes/$mesh.vtp" -o "$out/f.vti" --resolution "$n" --arrays distance --backend cpu \
      --timing | grep '^vtkdf:')
    ours=$(sed -E 's/.*time_s=([0-9.]+).*/\1/' <<<"$line")
    echo "$ours" >>"$out/ours"
    echo "$ours $(sed -E 's/.*stages=([^ ]*).*/\1/' <<<"$line")" >>"$out/stages"
    awk '/Maximum resident set size/ {printf "%.0f\n", $NF / 1024}' "$out/time" >>"$out/rss"
    if [ "$peers" != none ]; then
      peer=$("$peers" run "$meshes/$mesh.vtp" --peer embree-pq-hint --n "$n" --threads $threads \
        --reps 1 2>/dev/null | awk '$1 == "embree-pq-hint" {print $5}')
      echo "$peer" >>"$out/peer"
      awk -v a="$peer" -v b="$ours" 'BEGIN {printf "%.2f\n", a / b}' >>"$out/ratio"
    fi
  done
  m_ours=$(median <"$out/ours")
  stages=$(sort -g "$out/stages" | awk -v m="$m_ours" '$1 == m {print $2; exit}')
  if [ "$peers" != none ]; then
    m_peer=$(median <"$out/peer")
    ratio=$(awk -v a="$m_peer" -v b="$m_ours" 'BEGIN {printf "%.2f", a / b}')
    range="$(sort -g "$out/ratio" | head -1)-$(sort -g "$out/ratio" | tail -1)"
  else
    m_peer=- ratio=- range=-
  fi
  printf "%-14s %4s %9s %9s %7s %-13s %8s  %s\n" "$mesh" "$n" "$m_ours" "$m_peer" "$ratio" "$range" \
    "$(median <"$out/rss")" "${stages:-}"
done
