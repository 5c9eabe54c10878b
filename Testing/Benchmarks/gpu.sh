#!/usr/bin/env bash
# Benchmark (not a test): every distance-field filter on the GPU and on the CPU of the same
# host, for a machine with a hardware GPU. Prints vtkdf's --timing lines (backend, renderer,
# stages), BenchChamfer's and BenchUnion's tables and BenchRender's (the volume mapper next
# to VTK's ray caster, in the module's headless EGL context: no X server needed); run it
# with the thread count you want to compare against (vtkSMPTools uses every core by
# default).
# usage: Testing/Benchmarks/gpu.sh BUILD_DIR MESH_DIR [SIZES]
set -uo pipefail
build=${1:?usage: Testing/Benchmarks/gpu.sh BUILD_DIR MESH_DIR [SIZES]}
meshes=${2:?usage: Testing/Benchmarks/gpu.sh BUILD_DIR MESH_DIR [SIZES]}
sizes=${3:-"128 256"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() { "$build/bin/vtkdf" "$@" --timing 2>&1 | grep -E '^vtkdf:|ERR' | cut -c1-400; }

echo "== linear factorization, unsigned, then pseudonormal and winding-number signs"
for mesh in bunny_75k armadillo_52k aneurysm dragon_871k; do
  for n in $sizes; do
    for backend in gpu cpu; do
      run linfac "$meshes/$mesh.vtp" -o "$out/f.vti" --resolution "$n" --arrays distance --backend "$backend"
      for sign in pseudonormal winding; do
        run linfac "$meshes/$mesh.vtp" -o "$out/f.vti" --resolution "$n" --arrays distance \
          --sign "$sign" --backend "$backend"
      done
    done
  done
done
echo "== voxelization and chamfer"
"$build/bin/BenchChamfer" "$meshes/bunny_75k.vtp" "$meshes/dragon_871k.vtp" \
  --sizes "$(tr ' ' ',' <<<"$sizes")" --backends cpu,gpu --reps 1
echo "== medial axis and segmented field"
for n in $sizes; do
  for backend in gpu cpu; do
    run medial "$meshes/armadillo_52k.vtp" -o "$out/m.vti" --resolution "$n" --backend "$backend"
    run segment "$meshes/bunny_75k.vtp" -o "$out/s.vti" --resolution "$n" --backend "$backend"
  done
done
echo "== convex queries: union closest point, penetration depth"
"$build/bin/BenchUnion" --backends cpu,gpu
echo "== volume mapper next to VTK's ray caster (headless)"
"$build/bin/BenchRender" "$meshes" --headless --sizes "$(tr ' ' ',' <<<"$sizes")" \
  --planes 32,64,256 --frames 30 --repeats 5
