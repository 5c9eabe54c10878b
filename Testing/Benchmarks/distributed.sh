#!/usr/bin/env bash
# Strong scaling of the linear factorization (DF_FILTER=segmented: the segmented field) over
# MPI ranks (Testing/Benchmarks/distributed.py):
# 1 rank x 1 thread, 1 rank x 2 threads, 2 ranks x 1 thread, and 2 ranks with the mesh partitioned (gathered
# by the filter), on each mesh at each resolution. Ranks are not bound to cores (OpenMPI
# binds each to one by default, which leaves a rank of two threads one core).
# Usage: Testing/Benchmarks/distributed.sh BUILD_DIR MESH_DIR [RESOLUTION] [MESH...]
set -euo pipefail
build=$(cd "${1:?usage: distributed.sh BUILD_DIR MESH_DIR [RESOLUTION] [MESH...]}" && pwd)
meshes=${2:?usage: distributed.sh BUILD_DIR MESH_DIR [RESOLUTION] [MESH...]}
resolution=${3:-256}
shift 3 || shift $#
names=("$@")
[ ${#names[@]} -gt 0 ] || names=(bunny_75k dragon_871k)
here=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$build/lib/python3/dist-packages" OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
for name in "${names[@]}"; do
  mpiexec --bind-to none -n 1 /usr/bin/python3 "$here/distributed.py" "$meshes" "$name" "$resolution" 1
  mpiexec --bind-to none -n 1 /usr/bin/python3 "$here/distributed.py" "$meshes" "$name" "$resolution" 2
  mpiexec --bind-to none -n 2 /usr/bin/python3 "$here/distributed.py" "$meshes" "$name" "$resolution" 1
  mpiexec --bind-to none -n 2 /usr/bin/python3 "$here/distributed.py" "$meshes" "$name" "$resolution" 1 partitioned
done
