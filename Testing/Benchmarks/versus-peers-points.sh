#!/usr/bin/env bash
# Benchmark (not a test): vtkdf probe (vtkMeshDistanceFilter on the CPU: the surface's
# hierarchy, the exact distance, closest point, cell, barycentric coordinates, gradient
# and, with --signed, the winding number's side, at every point; reading and writing
# excluded) against a point-query peer on the same points, interleaved run by run, with
# our peak RSS (/usr/bin/time -v). The peers come from a harness that takes
# `points MESH POINTS --out OUT.tsv --peers NAME --no-exact --threads T --reps 1` and
# prints `peer NAME time_s T ...` (its tree build included); give its binary as PEERS.
# usage: Testing/Benchmarks/versus-peers-points.sh BUILD_DIR MESH_DIR PEERS \
#          "MESH:POINTS.npy:PEER[:SIGN] ..." [REPS]
#   PEER: embree, vtk-implicit or cgal-aabb; SIGN: unsigned or winding (the default).
# e.g.   Testing/Benchmarks/versus-peers-points.sh build ~/meshes ~/peers/build/peers \
#          "bunny_75k:bunny_uniform.npy:embree bunny_75k:bunny_near.npy:embree" 5
# Points: `python3 Testing/Benchmarks/points.py MESH N OUT_UNIFORM.npy OUT_NEAR.npy` draws
# N uniform points in the padded box and N within 1 % of the diagonal of the surface.
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
printf "%-12s %-22s %-12s %-8s %8s %8s %7s %-11s %7s  %s\n" mesh points peer sign ours_s peer_s ratio \
  "ratio range" rss_MB "stages (our median run)"
for row in $rows; do
  IFS=: read -r mesh points peer sign <<<"$row"
  sign=${sign:-winding}
  flags=()
  [ "$sign" = winding ] && flags=(--signed)
  : >"$out/ours" >"$out/peer" >"$out/ratio" >"$out/rss" >"$out/stages"
  for _ in $(seq "$reps"); do
    line=$(VTK_SMP_MAX_THREADS=$threads /usr/bin/time -v -o "$out/time" "$build/bin/vtkdf" probe \
      "$meshes/$mesh.vtp" "$points" -o "$out/d.npy" "${flags[@]}" --timing | grep 'time_s=')
    ours=$(sed -E 's/.*time_s=([0-9.]+).*/\1/' <<<"$line")
    echo "$ours" >>"$out/ours"
    echo "$ours $(sed -E 's/.*stages=([^ ]*).*/\1/' <<<"$line")" >>"$out/stages"
    awk '/Maximum resident set size/ {printf "%.0f\n", $NF / 1024}' "$out/time" >>"$out/rss"
    time_peer=$("$peers" points "$meshes/$mesh.vtp" "$points" --out "$out/peer.tsv" --peers "$peer" \
      --no-exact --threads $threads --reps 1 2>/dev/null | awk '$1 == "peer" {print $4}')
    echo "$time_peer" >>"$out/peer"
    awk -v a="$time_peer" -v b="$ours" 'BEGIN {printf "%.2f\n", a / b}' >>"$out/ratio"
  done
  m_ours=$(median <"$out/ours")
  m_peer=$(median <"$out/peer")
  stages=$(sort -g "$out/stages" | awk -v m="$m_ours" '$1 == m {print $2; exit}')
  printf "%-12s %-22s %-12s %-8s %8s %8s %7s %-11s %7s  %s\n" "$mesh" "$(basename "$points")" "$peer" \
    "$sign" "$m_ours" "$m_peer" "$(awk -v a="$m_peer" -v b="$m_ours" 'BEGIN {printf "%.2f", a / b}')" \
    "$(sort -g "$out/ratio" | head -1)-$(sort -g "$out/ratio" | tail -1)" "$(median <"$out/rss")" \
    "${stages:-}"
done
