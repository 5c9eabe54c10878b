"""A downstream script: the signed distance field of the unit cube with
vtkLinearFactorDistanceField, checked against the exact distance at every sample.
Run with the system Python (/usr/bin/python3) and the package on its path (the Debian
package puts it there; an install tree needs PYTHONPATH=<prefix>/lib/python3/dist-packages).
"""
import math
import sys

from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

from vtkdistancefields import vtkLinearFactorDistanceField


def cube_distance(p):
    """The signed distance from p to the cube [0, 1]^3 (negative inside)."""
    sides = [max(-x, x - 1) for x in p]
    outside = math.sqrt(sum(d * d for d in sides if d > 0))
    return outside if outside > 0 else max(sides)


points = vtkPoints()
for k in range(8):
    points.InsertNextPoint(k & 1, (k >> 1) & 1, (k >> 2) & 1)
triangles = vtkCellArray()
for a, b, c, d in ((0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2),
                   (1, 3, 7, 5)):
    triangles.InsertNextCell(3, (a, b, c))
    triangles.InsertNextCell(3, (a, c, d))
cube = vtkPolyData()
cube.SetPoints(points)
cube.SetPolys(triangles)

field = vtkLinearFactorDistanceField()
field.SetInputData(cube)
field.ExplicitGridOn()
field.SetGridOrigin(-0.5, -0.5, -0.5)
field.SetGridSpacing(0.125, 0.125, 0.125)
field.SetGridDimensions(17, 17, 17)
field.SetSignModeToPseudoNormal()
field.Update()

image = field.GetOutput()
distance = image.GetPointData().GetArray("Distance")
worst = max(abs(distance.GetTuple1(v) - cube_distance(image.GetPoint(v)))
            for v in range(image.GetNumberOfPoints()))
print(f"signed distance to the unit cube on 17^3 samples ({field.GetLastBackend()} backend): "
      f"largest error {worst:.2g}")
sys.exit(0 if worst <= 1e-5 else 1)
