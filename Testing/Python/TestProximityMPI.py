"""vtkDistanceFieldProximity in a distributed run without ParaView: mpiexec -n R
/usr/bin/python3 TestProximityMPI.py DATA, with VTK's vtkMPIController as the global
controller. Every rank holds both models whole (bunny_small and the teapot, overlapping,
then the teapot moved away); each takes its share of the face samples and rank 0 gathers
the answer. Rank 0's four outputs must equal, bit for bit, those of one process (the
same filter run with a one-process controller); the other ranks' outputs are empty."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkParallelCore import vtkDummyController, vtkMultiProcessController
from mpi4py import MPI  # noqa: F401 (initializes MPI before VTK's controller uses it)
from vtkmodules.vtkParallelMPI import vtkMPIController

from vtkdistancefields import vtkDistanceFieldProximity

controller = vtkMPIController()
controller.Initialize()
vtkMultiProcessController.SetGlobalController(controller)
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()


def read(name):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(os.path.join(sys.argv[1], name))
    reader.Update()
    return reader.GetOutput()


def moved(mesh, dx):
    points = vtkPoints()
    points.SetDataTypeToDouble()
    for i in range(mesh.GetNumberOfPoints()):
        x = mesh.GetPoint(i)
        points.InsertNextPoint(x[0] + dx, x[1], x[2])
    out = vtkPolyData()
    out.ShallowCopy(mesh)
    out.SetPoints(points)
    return out


def run(a, b):
    proximity = vtkDistanceFieldProximity()
    proximity.SetInputData(0, a)
    proximity.SetInputData(1, b)
    proximity.SetResolution(48)
    proximity.SetContactMargin(0.5)
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
bunny, teapot = read("bunny_small.vtp"), read("teapot.vtp")
for name, b in (("overlapping", teapot), ("apart", moved(teapot, 40))):
    distributed = run(bunny, b)
    if distributed.GetErrorCode():
        failures.append(f"{name}: rank {rank} failed")
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
    print(f"{name}: {ranks} ranks, colliding {distributed.GetLastColliding()}, separation "
          f"{distributed.GetLastSeparationDistance():.9g}, penetration "
          f"{distributed.GetLastPenetrationAB():.9g} / {distributed.GetLastPenetrationBA():.9g}, "
          f"{distributed.GetOutput(1).GetNumberOfPoints()} contacts", flush=True)

for failure in failures:
    print("FAIL:", failure, flush=True)
controller.Finalize()
sys.exit(1 if failures else 0)
