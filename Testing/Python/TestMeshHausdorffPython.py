"""vtkMeshHausdorffDistance from Python, numpy in and out (as docs/hausdorff.md uses it):
a unit square against a roof over it, both built from numpy arrays, whose distances are
known in closed form: from the square to the roof h / sqrt(1 + 4 h^2), inside the
square's faces (its vertices are on the roof), from the roof to the square h (its
ridge). Each certified interval holds its value and is no wider than asked; every
point's Distance, read with vtk_to_numpy, is the closed form's; the wrapped getters
repeat the field data; a RelativeError of 0 is an error."""
import math

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

from vtkdistancefields import vtkMeshHausdorffDistance


def mesh(points, triangles):
    """A vtkPolyData of numpy points (N, 3) and triangles (M, 3)."""
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.asarray(points, dtype=np.float64), deep=True))
    cells = vtkCellArray()
    offsets = np.arange(0, 3 * len(triangles) + 1, 3, dtype=np.int64)
    cells.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True),
                  numpy_to_vtkIdTypeArray(np.asarray(triangles, dtype=np.int64).ravel(), deep=True))
    poly = vtkPolyData()
    poly.SetPoints(pts)
    poly.SetPolys(cells)
    return poly


h = 0.25
square = mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 3]])
roof = mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0, h], [0.5, 1, h]],
            [[0, 4, 5], [0, 5, 3], [4, 1, 2], [4, 2, 5]])
a_to_b, b_to_a = h / math.sqrt(1 + 4 * h * h), h
diagonal = math.sqrt(2 + h * h)

failures = []
for relative in (1e-6, 1e-3):
    hausdorff = vtkMeshHausdorffDistance()
    hausdorff.SetInputData(square)
    hausdorff.SetMeshBData(roof)
    hausdorff.SetRelativeError(relative)
    hausdorff.Update()
    fd = hausdorff.GetOutput(0).GetFieldData()
    bounds = vtk_to_numpy(fd.GetArray("OneSidedHausdorffBounds")).reshape(2, 2)
    for (lower, upper), value, name in zip(bounds, (a_to_b, b_to_a), ("A to B", "B to A")):
        if not lower - 1e-13 <= value <= upper + 1e-13:
            failures.append(f"{name} ({relative}): [{lower}, {upper}] misses {value}")
        if upper - lower > relative * diagonal:
            failures.append(f"{name} ({relative}): {upper - lower} wide")
    lower, upper = hausdorff.GetHausdorffBounds()
    if (lower, upper) != tuple(vtk_to_numpy(fd.GetArray("HausdorffBounds")).ravel()):
        failures.append("GetHausdorffBounds differs from the field data")
    if not lower <= hausdorff.GetHausdorffDistance() <= upper:
        failures.append("the Hausdorff distance outside its interval")
    # Every point's distance to the other mesh, numpy out.
    d_square = vtk_to_numpy(hausdorff.GetOutput(0).GetPointData().GetArray("Distance"))
    d_roof = vtk_to_numpy(hausdorff.GetOutput(1).GetPointData().GetArray("Distance"))
    if not np.allclose(d_square, 0, atol=1e-15):
        failures.append(f"the square's corners at {d_square}, not on the roof")
    if not np.allclose(d_roof, [0, 0, 0, 0, h, h], rtol=1e-14, atol=1e-15):
        failures.append(f"the roof's points at {d_roof}")

bad = vtkMeshHausdorffDistance()
bad.SetInputData(square)
bad.SetMeshBData(roof)
bad.SetRelativeError(0)
bad.GlobalWarningDisplayOff()
bad.Update()
if bad.GetErrorCode() == 0:
    failures.append("RelativeError 0 accepted")

for failure in failures:
    print("FAIL:", failure)
print(len(failures), "failures")
raise SystemExit(1 if failures else 0)
