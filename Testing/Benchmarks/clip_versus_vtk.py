"""Benchmark (not a test): vtkClipByMeshDistance (winding-number sign) next to what VTK
offers for the same cut, vtkTableBasedClipDataSet with vtkImplicitPolyDataDistance as
its clip function (the mesh's cell locator; its sign from an angle-weighted normal), on
an N^3 grid of hexahedra around the mesh (padded by a tenth): time (median of REPS
interleaved runs of both; each side's search structure built in each run), the cells
each keeps, and the points of the grid where VTK's sign differs from ours (our winding
number's: certified).
usage: PYTHONPATH=BUILD/lib/python3/dist-packages /usr/bin/python3 clip_versus_vtk.py
       MESH.vtp N [REPS]
Both sides use the machine's threads where they can: ours vtkSMPTools (the distances),
VTK's clip vtkSMPTools in 9.1's table-based clip but its implicit function one point at
a time."""
import statistics
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkFiltersCore import vtkImplicitPolyDataDistance
from vtkmodules.vtkFiltersGeneral import vtkTableBasedClipDataSet
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from vtkdistancefields import vtkClipByMeshDistance, vtkMeshDistanceFilter

path, n = sys.argv[1], int(sys.argv[2])
reps = int(sys.argv[3]) if len(sys.argv) > 3 else 5
reader = vtkXMLPolyDataReader()
reader.SetFileName(path)
reader.Update()
mesh = reader.GetOutput()
b = mesh.GetBounds()
size = max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
grid = vtkImageData()
grid.SetDimensions(n, n, n)
h = 1.2 * size / (n - 1)
grid.SetSpacing(h, h, h)
grid.SetOrigin(*[(b[2 * a] + b[2 * a + 1] - 1.2 * size) / 2 for a in range(3)])


def ours():
    clip = vtkClipByMeshDistance()
    clip.SetInputData(grid)
    clip.SetSurfaceData(mesh)
    clip.Update()
    return clip.GetOutput().GetNumberOfCells()


def theirs():
    function = vtkImplicitPolyDataDistance()
    function.SetInput(mesh)
    clip = vtkTableBasedClipDataSet()
    clip.SetInputData(grid)
    clip.SetClipFunction(function)
    clip.InsideOutOn()
    clip.Update()
    return clip.GetOutput().GetNumberOfCells()


times = {"ours": [], "vtk": []}
cells = {}
for _ in range(reps):
    for name, run in (("ours", ours), ("vtk", theirs)):
        start = time.perf_counter()
        cells[name] = run()
        times[name].append(time.perf_counter() - start)
# The signs at the grid's points: ours (certified) against VTK's function's.
signed = vtkMeshDistanceFilter()
signed.SetInputData(grid)
signed.SetSurfaceData(mesh)
signed.SetSignModeToWindingNumber()
signed.ComputeClosestPointOff()
signed.ComputeClosestCellIdOff()
signed.ComputeBarycentricOff()
signed.ComputeGradientOff()
signed.Update()
d = vtk_to_numpy(signed.GetOutput().GetPointData().GetArray("Distance"))
function = vtkImplicitPolyDataDistance()
function.SetInput(mesh)
theirs_d = np.array([function.FunctionValue(grid.GetPoint(i)) for i in range(len(d))])
wrong = np.count_nonzero((d < 0) != (theirs_d < 0))
ours_t, vtk_t = statistics.median(times["ours"]), statistics.median(times["vtk"])
print(f"{path.split('/')[-1]} {n}^3: ours {ours_t:.3f} s ({min(times['ours']):.3f}-"
      f"{max(times['ours']):.3f}), {cells['ours']} cells; vtk {vtk_t:.3f} s "
      f"({min(times['vtk']):.3f}-{max(times['vtk']):.3f}), {cells['vtk']} cells; "
      f"ratio {vtk_t / ours_t:.1f}x; VTK's sign differs at {wrong} of {len(d)} points")
