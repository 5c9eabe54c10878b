"""Strong scaling of the linear factorization (or, with DF_FILTER=segmented, the segmented
field) over MPI ranks, without ParaView:
mpiexec -n R /usr/bin/python3 distributed.py MESH_DIR MESH RESOLUTION THREADS [partitioned]
(PYTHONPATH: the build's Python package). Every rank computes its slab of the grid
(UpdatePiece); "partitioned" gives each rank a part of the mesh's cells with global ids
instead of the whole mesh, so that the filter gathers it. Prints, on rank 0, the time of
the slowest rank (median of 3 runs), each rank's peak memory, and the threads per rank."""
import os
import resource
import sys
import time

import numpy as np
from mpi4py import MPI  # noqa: F401 (initializes MPI before VTK's controller uses it)
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_ID_TYPE, vtkSMPTools
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkParallelMPI import vtkMPIController

from vtkdistancefields import vtkLinearFactorDistanceField, vtkSegmentedDistanceField

mesh_dir, name, resolution, threads = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
partitioned = sys.argv[5:6] == ["partitioned"]
vtkSMPTools.Initialize(threads)
controller = vtkMPIController()
controller.Initialize()
vtkMultiProcessController.SetGlobalController(controller)
rank, ranks = controller.GetLocalProcessId(), controller.GetNumberOfProcesses()

reader = vtkXMLPolyDataReader()
reader.SetFileName(os.path.join(mesh_dir, name + ".vtp"))
reader.Update()
mesh = reader.GetOutput()
if partitioned:
    cells = mesh.GetNumberOfCells()
    first, last = rank * cells // ranks, (rank + 1) * cells // ranks
    offsets = vtk_to_numpy(mesh.GetPolys().GetOffsetsArray())
    connectivity = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray())
    polys = vtkCellArray()
    polys.SetData(numpy_to_vtk(offsets[first:last + 1] - offsets[first], deep=True,
                               array_type=VTK_ID_TYPE),
                  numpy_to_vtk(connectivity[offsets[first]:offsets[last]], deep=True,
                               array_type=VTK_ID_TYPE))
    part = vtkPolyData()
    part.SetPoints(mesh.GetPoints())
    part.SetPolys(polys)
    ids = numpy_to_vtk(np.arange(mesh.GetNumberOfPoints()), deep=True, array_type=VTK_ID_TYPE)
    cell_ids = numpy_to_vtk(np.arange(first, last), deep=True, array_type=VTK_ID_TYPE)
    part.GetPointData().SetGlobalIds(ids)
    part.GetCellData().SetGlobalIds(cell_ids)
    mesh = part

times = []
for run in range(3):
    if os.environ.get("DF_FILTER") == "segmented":
        f = vtkSegmentedDistanceField()
    else:
        f = vtkLinearFactorDistanceField()
        f.SetSignModeToPseudoNormal()
    f.SetInputData(mesh)
    f.SetResolution(resolution)
    f.SetBackendToCPU()
    controller.Barrier()
    start = time.perf_counter()
    f.UpdatePiece(rank, ranks, 0)
    controller.Barrier()
    times.append(time.perf_counter() - start)
memory = np.array([resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0])
memories = np.zeros(ranks)
controller.AllGather(memory, memories, 1)
if rank == 0:
    extent = f.GetOutput().GetExtent()
    print(f"{f.GetClassName()}, {name} {resolution}^3, {ranks} rank(s) x {threads} thread(s)"
          f"{', mesh partitioned' if partitioned else ''}: {sorted(times)[1]:.2f} s "
          f"(slowest rank, median of 3), rank 0's slab {extent}, peak memory per rank "
          + ", ".join(f"{m:.0f} MiB" for m in memories)
          + f"; rank 0's stages {f.GetLastStageTimes()}", flush=True)
controller.Finalize()
