"""SignMode = WindingNumber from Python: an open box (its top face missing), on both
backends. The winding number, in numpy from every triangle's solid angle, decides the
sign where it is far from 1/2; the WindingNumber array follows it within 0.01; the
magnitudes equal the unsigned field's; and the medial filter takes the same SignMode.
Then a sheet of 9,800 triangles with a layer of samples just below it, where |w| is near
1/2 and the exact sum over every triangle decides: on llvmpipe that sum runs past the
context's loop limit, so the GPU backend finishes those samples on the CPU and says how
many (GetLastWindingCPUSamples), and both backends' arrays are the same bits."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray, vtk_to_numpy
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

m = 70
ticks = np.linspace(-1.1, 1.1, m + 1)
sheet_points = np.array([(x, y, 0.001) for y in ticks for x in ticks])
corner = np.array([i + j * (m + 1) for j in range(m) for i in range(m)])
sheet_triangles = np.concatenate([np.stack([corner, corner + 1, corner + m + 2], 1),
                                  np.stack([corner, corner + m + 2, corner + m + 1], 1)])
points = vtkPoints()
points.SetData(numpy_to_vtk(sheet_points, deep=1))
polys = vtkCellArray()
polys.SetData(3, numpy_to_vtkIdTypeArray(sheet_triangles.ravel().astype(np.int64), deep=1))
sheet = vtkPolyData()
sheet.SetPoints(points)
sheet.SetPolys(polys)
arrays = {}
for backend in ("SetBackendToCPU", "SetBackendToGPU"):
    f = vtkLinearFactorDistanceField()
    f.SetInputData(sheet)
    f.ExplicitGridOn()
    f.SetGridOrigin(-1, -1, -0.2)
    f.SetGridSpacing(0.1, 0.1, 0.1)
    f.SetGridDimensions(21, 21, 5)  # the layer z = 0 just below the sheet
    getattr(f, backend)()
    f.SetSignModeToWindingNumber()
    f.ComputeWindingNumberOn()
    f.Update()
    data = f.GetOutput().GetPointData()
    arrays[backend] = [vtk_to_numpy(data.GetArray(a)).copy() for a in ("Distance", "WindingNumber")]
    to_cpu = f.GetLastWindingCPUSamples()
    software = "llvmpipe" in f.GetLastRenderer()
    print(f"{backend} on {f.GetLastRenderer()}: {to_cpu} samples finished on the CPU")
    if backend == "SetBackendToCPU" or not software:
        failures += to_cpu != 0
    else:
        failures += not 0 < to_cpu <= 21 * 21
same = all(np.array_equal(a.view(np.uint32), b.view(np.uint32))
           for a, b in zip(arrays["SetBackendToCPU"], arrays["SetBackendToGPU"]))
print(f"sheet: Distance and WindingNumber the same bits on both backends: {same}")
failures += not same

print(f"{failures} failures")
sys.exit(1 if failures else 0)
