"""A distributed run without ParaView: mpiexec -n R /usr/bin/python3 TestMPIPython.py DATA,
with VTK's own vtkMPIController as the global controller. Each rank holds a part of the
mesh (a range of its cells, with global point and cell ids: their original indices) and
asks the linear factorization for its piece of the grid; the filter gathers the parts.
Every rank's slab must equal, bit for bit, the same samples of the field of the whole mesh
without ids (which every rank also computes), and the slabs must cover the grid."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_ID_TYPE
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from mpi4py import MPI  # noqa: F401 (initializes MPI before VTK's controller uses it)
from vtkmodules.vtkParallelMPI import vtkMPIController

from vtkdistancefields import vtkLinearFactorDistanceField

controller = vtkMPIController()
controller.Initialize()
vtkMultiProcessController.SetGlobalController(controller)
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()

reader = vtkXMLPolyDataReader()
reader.SetFileName(os.path.join(sys.argv[1], "bunny_small.vtp"))
reader.Update()
whole = reader.GetOutput()

# This rank's part: a range of cells, with every point (unused ones are ignored), and
# global ids = original indices.
cells = whole.GetNumberOfCells()
first, last = rank * cells // ranks, (rank + 1) * cells // ranks
part = vtkPolyData()
part.SetPoints(whole.GetPoints())
polys = whole.GetPolys()
offsets = vtk_to_numpy(polys.GetOffsetsArray())
connectivity = vtk_to_numpy(polys.GetConnectivityArray())
mine = vtkCellArray()
mine.SetData(numpy_to_vtk(offsets[first:last + 1] - offsets[first], deep=True,
                          array_type=VTK_ID_TYPE),
             numpy_to_vtk(connectivity[offsets[first]:offsets[last]], deep=True,
                          array_type=VTK_ID_TYPE))
part.SetPolys(mine)
point_ids = numpy_to_vtk(np.arange(whole.GetNumberOfPoints(), dtype=np.int64), deep=True,
                         array_type=VTK_ID_TYPE)
point_ids.SetName("GlobalPointIds")
cell_ids = numpy_to_vtk(np.arange(first, last, dtype=np.int64), deep=True,
                        array_type=VTK_ID_TYPE)
cell_ids.SetName("GlobalCellIds")
part.GetPointData().SetGlobalIds(point_ids)
part.GetCellData().SetGlobalIds(cell_ids)


def field(mesh):
    f = vtkLinearFactorDistanceField()
    f.SetInputData(mesh)
    f.SetResolution(24)
    f.SetSignModeToWindingNumber()
    f.ComputeClosestPointOn()
    f.SetBackendToCPU()
    return f


reference = field(whole)  # every rank holds the same mesh: nothing is gathered
reference.Update()
distributed = field(part)
distributed.UpdatePiece(rank, ranks, 0)
slab = distributed.GetOutput()
extent = slab.GetExtent()
full = reference.GetOutput()
wx, wy = full.GetDimensions()[0], full.GetDimensions()[1]
ok = True
for name in ("Distance", "ClosestCellId", "ClosestPoint"):
    values = vtk_to_numpy(full.GetPointData().GetArray(name))
    grid = values.reshape((-1, wy, wx) + values.shape[1:])
    expected = grid[extent[4]:extent[5] + 1, extent[2]:extent[3] + 1, extent[0]:extent[1] + 1]
    got = vtk_to_numpy(slab.GetPointData().GetArray(name))
    same = got.tobytes() == np.ascontiguousarray(expected).reshape(got.shape).tobytes()
    ok = ok and same
print(f"rank {rank} of {ranks}: cells {first}..{last - 1}, extent {extent}: "
      f"{'equal to the whole mesh field bit for bit' if ok else 'DIFFERS'}", flush=True)
# Each rank computed a slab, not the whole grid.
is_slab = ranks == 1 or tuple(extent) != tuple(full.GetExtent())
controller.Finalize()
sys.exit(0 if ok and is_slab else 1)
