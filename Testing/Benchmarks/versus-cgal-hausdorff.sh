#!/usr/bin/env bash
# Benchmark (not a test): vtkdf hausdorff (vtkMeshHausdorffDistance: both one-sided
# distances, each certified within E times the diagonal, and every vertex's distance;
# reading and writing excluded) against CGAL's bounded-error symmetric Hausdorff distance
# at the same bound, interleaved run by run. CGAL comes from a harness that takes
# `hausdorff A B --rel-error E --threads T` and prints `hausdorff symmetric H ... time_s T`
# (CGAL 5.5 runs it on one thread whatever T); give its binary as PEERS.
# usage: Testing/Benchmarks/versus-cgal-hausdorff.sh BUILD_DIR PEERS "A.vtp:B.vtp ..." \
#          [REPS] [E]
# e.g.   python3 Testing/Benchmarks/hausdorff_inputs.py ~/meshes /tmp/pairs
#        Testing/Benchmarks/versus-cgal-hausdorff.sh build ~/peers/build/peers \
#          "~/meshes/bunny_75k.vtp:/tmp/pairs/bunny_75k_decimated.vtp" 5
# Prints, per pair, both values (they must agree within E times the diagonal), the
# medians of REPS runs of each side, their ratio and the range of the run-by-run ratios,
# and the stages of our median run.
set -euo pipefail
build=${1:?usage: see the header}
peers=${2:?usage: see the header}
pairs=${3:?usage: see the header}
reps=${4:-5}
error=${5:-1e-6}
threads=2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
printf "%-24s %-30s %-13s %-13s %8s %8s %7s %-11s  %s\n" A B ours cgal ours_s cgal_s ratio \
  "ratio range" "stages (our median run)"
for pair in $pairs; do
  IFS=: read -r a b <<<"$pair"
  : >"$out/ours" >"$out/peer" >"$out/ratio" >"$out/stages"
  for _ in $(seq "$reps"); do
    lines=$(VTK_SMP_MAX_THREADS=$threads "$build/bin/vtkdf" hausdorff "$a" "$b" -o "$out/a.vtp" \
      --relative-error "$error" --timing)
    value=$(grep -Eo 'hausdorff distance=[0-9.e-]+' <<<"$lines" | cut -d= -f2)
    ours=$(grep -Eo 'time_s=[0-9.]+' <<<"$lines" | cut -d= -f2)
    echo "$ours" >>"$out/ours"
    echo "$ours $(grep -Eo 'stages=[^ ]*' <<<"$lines" | cut -d= -f2)" >>"$out/stages"
    peer=$("$peers" hausdorff "$a" "$b" --rel-error "$error" --threads $threads 2>/dev/null |
      awk '$1 == "hausdorff" {print $3, $11}')
    cgal=${peer% *}
    echo "${peer#* }" >>"$out/peer"
    awk -v a="${peer#* }" -v b="$ours" 'BEGIN {printf "%.2f\n", a / b}' >>"$out/ratio"
  done
  m_ours=$(median <"$out/ours")
  m_peer=$(median <"$out/peer")
  stages=$(sort -g "$out/stages" | awk -v m="$m_ours" '$1 == m {print $2; exit}')
  printf "%-24s %-30s %-13.9g %-13.9g %8s %8s %7s %-11s  %s\n" "$(basename "$a")" "$(basename "$b")" \
    "$value" "$cgal" "$m_ours" "$m_peer" \
    "$(awk -v a="$m_peer" -v b="$m_ours" 'BEGIN {printf "%.2f", a / b}')" \
    "$(sort -g "$out/ratio" | head -1)-$(sort -g "$out/ratio" | tail -1)" "${stages:-}"
done
