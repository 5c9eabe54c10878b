"""SignMode = WindingNumber from Python: an open box (its top face missing), on both
backends. The winding number, in numpy from every triangle's solid angle, decides the
sign where it is far from 1/2; the WindingNumber array follows it within 0.01; the
magnitudes equal the unsigned field's; and the medial filter takes the same SignMode."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

from vtkdistancefields import vtkLinearFactorDistanceField, vtkMedialAxisFilter

corners = np.array([[i & 1, (i >> 1) & 1, (i >> 2) & 1] for i in range(8)], dtype=float)
faces = [(0, 2, 3, 1), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]  # no top
triangles = np.array([t for a, b, c, d in faces for t in ((a, b, c), (a, c, d))])
points = vtkPoints()
for c in corners:
    points.InsertNextPoint(*c)
polys = vtkCellArray()
for t in triangles:
    polys.InsertNextCell(3, [int(i) for i in t])
box = vtkPolyData()
box.SetPoints(points)
box.SetPolys(polys)


def winding(x):
    """Van Oosterom and Strackee, summed over the triangles, at every row of x."""
    total = np.zeros(len(x))
    for t in triangles:
        a, b, c = (corners[i] - x for i in t)
        la, lb, lc = (np.linalg.norm(v, axis=1) for v in (a, b, c))
        det = np.einsum("ij,ij->i", a, np.cross(b, c))
        den = (la * lb * lc + np.einsum("ij,ij->i", a, b) * lc
               + np.einsum("ij,ij->i", a, c) * lb + np.einsum("ij,ij->i", b, c) * la)
        total += 2 * np.arctan2(det, den)
    return total / (4 * np.pi)


failures = 0
for backend in ("SetBackendToCPU", "SetBackendToGPU"):
    fields = {}
    for mode in ("SetSignModeToWindingNumber", "SetSignModeToUnsigned"):
        f = vtkLinearFactorDistanceField()
        f.SetInputData(box)
        f.SetResolution(20)
        getattr(f, backend)()
        getattr(f, mode)()
        f.ComputeWindingNumberOn()
        f.Update()
        fields[mode] = f.GetOutput()
    image = fields["SetSignModeToWindingNumber"]
    d = vtk_to_numpy(image.GetPointData().GetArray("Distance"))
    w = vtk_to_numpy(image.GetPointData().GetArray("WindingNumber"))
    unsigned = vtk_to_numpy(fields["SetSignModeToUnsigned"].GetPointData().GetArray("Distance"))
    x = np.array([image.GetPoint(v) for v in range(image.GetNumberOfPoints())])
    exact = winding(x)
    decided = np.abs(np.abs(exact) - 0.5) > 0.01
    wrong = int(np.sum((d[decided] < 0) != (np.abs(exact[decided]) > 0.5)))
    off = float(np.max(np.abs(w - exact)))
    same = bool(np.array_equal(np.abs(d), unsigned))
    print(f"{backend}: {int(np.sum(d < 0))} of {len(d)} samples inside, {wrong} wrong signs, "
          f"WindingNumber off by at most {off:.2g}, magnitudes equal: {same}")
    failures += wrong > 0 or off > 0.01 or not same or np.sum(d < 0) == 0

    medial = vtkMedialAxisFilter()
    medial.SetInputData(box)
    medial.SetResolution(24)
    medial.SetSeparationAngle(60)
    getattr(medial, backend)()
    medial.SetSignModeToWindingNumber()
    medial.Update()
    count = medial.GetMedialPoints().GetNumberOfPoints()
    print(f"{backend}: medial axis of the open box with the winding sign: {count} voxels")
    failures += count == 0

print(f"{failures} failures")
sys.exit(1 if failures else 0)
