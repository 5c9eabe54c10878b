"""vtkPenetrationDepth in a distributed run without ParaView: mpiexec -n R /usr/bin/python3
TestPenetrationMPI.py DATA, with VTK's vtkMPIController as the global controller. Every
rank holds both solids (the four convex pieces of hubo_ankle_convex4, and the same moved
to overlap, then apart); each builds its block of the Minkowski sums and rank 0 gathers
them and answers. Rank 0's output must equal, bit for bit, that of one process (the same
filter with a one-process controller); the ranks' blocks must add up to the kept pairs,
each rank building its share; the other ranks' outputs are empty."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from mpi4py import MPI
from vtkmodules.vtkParallelCore import vtkDummyController, vtkMultiProcessController
from mpi_support import moved, read, start_controller

from vtkdistancefields import vtkPenetrationDepth

controller, rank, ranks = start_controller()
ankle = read(sys.argv[1], "hubo_ankle_convex4.vtp")


def run(p, q):
    depth = vtkPenetrationDepth()
    depth.SetSolidPData(p)
    depth.SetSolidQData(q)
    depth.SetBackendToCPU()
    depth.UseConvexHullsOn()  # the moved pieces: convex up to rounding
    depth.Update()
    return depth


def arrays(data):
    found = {"points": vtk_to_numpy(data.GetPoints().GetData())}
    fields = data.GetFieldData()
    for k in range(fields.GetNumberOfArrays()):
        found[fields.GetArray(k).GetName()] = vtk_to_numpy(fields.GetArray(k))
    return found


failures = []
bounds = ankle.GetBounds()
size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
for name, offset in (("overlapping", (0.1 * size, 0.05 * size, 0)), ("apart", (3 * size, 0, 0))):
    q = moved(ankle, offset)
    distributed = run(ankle, q)
    if distributed.GetErrorCode():
        failures.append(f"{name}: rank {rank} failed")
    built = MPI.COMM_WORLD.allgather(distributed.GetLastPairsBuilt())
    if rank != 0:
        if distributed.GetOutput().GetNumberOfPoints():
            failures.append(f"{name}: rank {rank} has output")
        continue
    vtkMultiProcessController.SetGlobalController(vtkDummyController())
    alone = run(ankle, q)
    vtkMultiProcessController.SetGlobalController(controller)
    kept = alone.GetLastPairsKept()
    if sum(built) != kept or distributed.GetLastPairsKept() != kept:
        failures.append(f"{name}: the ranks built {built} of {kept} kept sums")
    if kept >= ranks and min(built) == 0:
        failures.append(f"{name}: a rank built nothing ({built})")
    x, y = arrays(distributed.GetOutput()), arrays(alone.GetOutput())
    if x.keys() != y.keys():
        failures.append(f"{name}: arrays {sorted(x)} vs {sorted(y)}")
    else:
        for key in x:
            if x[key].shape != y[key].shape or not np.array_equal(x[key], y[key]):
                failures.append(f"{name}: {key} differs from one process")
    print(f"{name}: {ranks} ranks built {built} of {kept} kept sums ({alone.GetLastPairsTotal()} "
          f"pairs); depth {distributed.GetLastPenetrationDepth():.9g}, separation "
          f"{distributed.GetLastSeparationDistance():.9g}", flush=True)

for failure in failures:
    print("FAIL:", failure, flush=True)
controller.Finalize()
sys.exit(1 if failures else 0)
