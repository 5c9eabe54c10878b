"""vtkUnionClosestPoint from Python: two unit cubes side by side (one mesh, two connected
components) and queries on port 1: from (0.9, 0.5, 0.5) the union's boundary is 0.5 away
(not 0.1: the shared face is not boundary), from (2.5, 0.5, 0.5) 0.5 outside; the
bundled hubo_ankle_convex4 (4 overlapping convex pieces) from inside: the closest point
at |Distance| and inside the bounds, the same on the GPU (certified). vtkPenetrationDepth: a unit cube against one shifted
by 0.7 along x: depth 0.3, translate Q along +x, in the field data too."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkIntArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkCleanPolyData
from vtkmodules.vtkFiltersSources import vtkCubeSource
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from vtkdistancefields import vtkPenetrationDepth, vtkUnionClosestPoint


def cube(x):
    source = vtkCubeSource()
    source.SetBounds(x, x + 1, 0, 1, 0, 1)
    clean = vtkCleanPolyData()
    clean.SetInputConnection(source.GetOutputPort())
    clean.Update()
    return clean.GetOutput()


append = vtkAppendPolyData()
append.AddInputData(cube(0))
append.AddInputData(cube(1))
points = vtkPoints()
points.InsertNextPoint(0.9, 0.5, 0.5)
points.InsertNextPoint(2.5, 0.5, 0.5)
queries = vtkPolyData()
queries.SetPoints(points)

union = vtkUnionClosestPoint()
union.SetInputConnection(append.GetOutputPort())
union.SetQueryData(queries)
union.Update()
out = union.GetOutput()
distance = vtk_to_numpy(out.GetPointData().GetArray("Distance"))
print(f"two cubes: distances {distance[:2].tolist()}, {union.GetLastPieceCount()} pieces")
ok = union.GetLastPieceCount() == 2 and np.allclose(distance[:2], [-0.5, 0.5], atol=1e-6)

reader = vtkXMLPolyDataReader()
reader.SetFileName(os.path.join(sys.argv[1], "hubo_ankle_convex4.vtp"))
hubo = vtkUnionClosestPoint()
hubo.SetInputConnection(reader.GetOutputPort())
hubo.SetQueryPoint(0, 0.01, 0.01)
hubo.Update()
h = hubo.GetOutput()
d = h.GetPointData().GetArray("Distance").GetValue(0)
gap = np.linalg.norm(np.array(h.GetPoint(1)) - np.array(h.GetPoint(0)))
print(f"hubo_ankle_convex4: {hubo.GetLastPieceCount()} pieces, distance {d:.6f}, "
      f"|closest - query| {gap:.6f}")
ok = ok and hubo.GetLastPieceCount() == 4 and d < 0 and abs(gap + d) < 1e-6

# The same query with the GPU's bound (llvmpipe without a GPU): the same answer, bit for
# bit; the rendered views' settings (deprecated) do nothing, each call with a
# DeprecationWarning.
import warnings  # noqa: E402

gpu = vtkUnionClosestPoint()
gpu.SetInputConnection(reader.GetOutputPort())
gpu.SetQueryPoint(0, 0.01, 0.01)
gpu.SetBackendToGPU()
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    gpu.SetViewResolution(64)
    gpu.CertifyOff()
    passes = gpu.GetLastPasses()
deprecated = [w for w in caught if issubclass(w.category, DeprecationWarning)]
gpu.Update()
g = gpu.GetOutput().GetPointData()
print(f"on the GPU ({gpu.GetLastRenderer()}): distance {g.GetArray('Distance').GetValue(0):.6f}; "
      f"{len(deprecated)} deprecation warnings")
ok = ok and g.GetArray("Distance").GetValue(0) == d and gpu.GetLastBackend() == gpu.BACKEND_GPU \
    and len(deprecated) == 3 and passes == 0

shifted = vtkCubeSource()
shifted.SetBounds(0.7, 1.7, 0.2, 0.8, 0.2, 0.8)
shifted.Update()


def one_piece(mesh):
    """vtkCubeSource repeats its corners per face, so its faces are six connected
    components: a cell-data array of piece ids (PieceArray, for both solids) makes one."""
    ids = vtkIntArray()
    ids.SetName("Piece")
    for _ in range(mesh.GetNumberOfCells()):
        ids.InsertNextValue(7)
    mesh.GetCellData().AddArray(ids)
    return mesh


pd = vtkPenetrationDepth()
pd.SetSolidPData(one_piece(cube(0)))
pd.SetSolidQData(one_piece(shifted.GetOutput()))
pd.SetPieceArray("Piece")
pd.Update()
fields = pd.GetOutput().GetFieldData()
depth = fields.GetArray("PenetrationDepth").GetValue(0)
direction = fields.GetArray("Direction").GetTuple3(0)
print(f"penetration depth of two cubes: {depth:.7f} along {direction}, "
      f"intersecting {pd.GetLastIntersecting()}")
ok = ok and pd.GetLastIntersecting() and abs(depth - 0.3) < 1e-6 and \
    np.allclose(direction, [1, 0, 0]) and abs(pd.GetLastPenetrationDepth() - depth) == 0
if not ok:
    print("FAIL")
    sys.exit(1)
