"""vtkDistanceFieldProximity in a distributed run without ParaView: mpiexec -n R
/usr/bin/python3 TestProximityMPI.py DATA, with VTK's vtkMPIController as the global
controller. Every rank holds both models whole (bunny_small and the teapot, overlapping,
then the teapot moved away); each takes its share of the face samples and rank 0 gathers
the answer. Rank 0's four outputs must equal, bit for bit, those of one process (the
same filter run with a one-process controller); the other ranks' outputs are empty.
A second argument "gpu" runs every rank's searches on the GPU (each rank its own context)."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkParallelCore import vtkDummyController, vtkMultiProcessController
from mpi_support import moved, read, start_controller

from vtkdistancefields import vtkDistanceFieldProximity

controller, rank, ranks = start_controller()
backend = sys.argv[2] if len(sys.argv) > 2 else "cpu"


def run(a, b):
    proximity = vtkDistanceFieldProximity()
    proximity.SetInputData(0, a)
    proximity.SetInputData(1, b)
    proximity.SetResolution(48)
    proximity.SetContactMargin(0.5)
    getattr(proximity, "SetBackendTo" + backend.upper())()
    proximity.Update()
    return proximity


def arrays(data):
    """Every array of an output, and its points, as numpy arrays by name."""
    found = {}
    if data.GetPoints() is not None:
        found["points"] = vtk_to_numpy(data.GetPoints().GetData())
    for kind, attributes in (("point", data.GetPointData()), ("cell", data.GetCellData()),
                             ("field", data.GetFieldData())):
        for k in range(attributes.GetNumberOfArrays()):
            array = attributes.GetArray(k)
            found[f"{kind}:{array.GetName()}"] = vtk_to_numpy(array)
    return found


failures = []
bunny, teapot = read(sys.argv[1], "bunny_small.vtp"), read(sys.argv[1], "teapot.vtp")
for name, b in (("overlapping", teapot), ("apart", moved(teapot, (40, 0, 0)))):
    distributed = run(bunny, b)
    if distributed.GetErrorCode() or distributed.GetLastBackend() != backend:
        failures.append(f"{name}: rank {rank} failed on the {backend}")
        continue
    if rank != 0:
        if any(distributed.GetOutput(p).GetNumberOfPoints() for p in range(4)):
            failures.append(f"{name}: rank {rank} has output")
        continue
    vtkMultiProcessController.SetGlobalController(vtkDummyController())
    alone = run(bunny, b)
    vtkMultiProcessController.SetGlobalController(controller)
    for port in range(4):
        x, y = arrays(distributed.GetOutput(port)), arrays(alone.GetOutput(port))
        if x.keys() != y.keys():
            failures.append(f"{name}: port {port} arrays {sorted(x)} vs {sorted(y)}")
            continue
        for key in x:
            if x[key].shape != y[key].shape or not np.array_equal(x[key], y[key], equal_nan=True):
                failures.append(f"{name}: port {port} {key} differs from one process")
    print(f"{name}: {ranks} ranks on the {backend}, colliding {distributed.GetLastColliding()}, separation "
          f"{distributed.GetLastSeparationDistance():.9g}, penetration "
          f"{distributed.GetLastPenetrationAB():.9g} / {distributed.GetLastPenetrationBA():.9g}, "
          f"{distributed.GetOutput(1).GetNumberOfPoints()} contacts", flush=True)

for failure in failures:
    print("FAIL:", failure, flush=True)
controller.Finalize()
sys.exit(1 if failures else 0)
