"""vtkUnionClosestPoint from Python: two unit cubes side by side (one mesh, two connected
components) and queries on port 1: from (0.9, 0.5, 0.5) the union's boundary is 0.5 away
(not 0.1: the shared face is not boundary), from (2.5, 0.5, 0.5) 0.5 outside; the
bundled hubo_ankle_convex4 (4 overlapping convex pieces) from inside: the closest point
at |Distance| and inside the bounds."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkCleanPolyData
from vtkmodules.vtkFiltersSources import vtkCubeSource
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from vtkdistancefields import vtkUnionClosestPoint


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
if not ok:
    print("FAIL")
    sys.exit(1)
