"""vtkLinearFactorDistanceField from Python: points and a polyline, checked against a
numpy brute force on every sample, through a numpy view of the Distance array, on both
backends and by both CPU routes (the site scan and the per-sample queries)."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

from vtkdistancefields import vtkLinearFactorDistanceField

rng = np.random.default_rng(5)
coords = rng.uniform(-1.0, 1.0, size=(12, 3))
points = vtkPoints()
for c in coords:
    points.InsertNextPoint(*c)
verts, lines = vtkCellArray(), vtkCellArray()
for i in range(6):
    verts.InsertNextCell(1, [i])
lines.InsertNextCell(6, list(range(6, 12)))
mesh = vtkPolyData()
mesh.SetPoints(points)
mesh.SetVerts(verts)
mesh.SetLines(lines)

runs = (("SetBackendToCPU", "SetRouteToSiteScan", "site scan"),
        ("SetBackendToCPU", "SetRouteToSampleQueries", "sample queries"),
        ("SetBackendToGPU", "SetRouteToAuto", "site scan"))
for backend, route, expected in runs:
    f = vtkLinearFactorDistanceField()
    f.SetInputData(mesh)
    f.SetResolution(24)
    getattr(f, backend)()
    getattr(f, route)()
    f.Update()
    if f.GetLastRoute() != expected:
        print(f"FAIL: {route} ran {f.GetLastRoute()!r}")
        sys.exit(1)
    image = f.GetOutput()
    distance = vtk_to_numpy(image.GetPointData().GetArray("Distance"))
    nx, ny, nz = image.GetDimensions()
    o, h = np.array(image.GetOrigin()), np.array(image.GetSpacing())
    k, j, i = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")
    x = o + h * np.stack([i.ravel(), j.ravel(), k.ravel()], axis=1)

    best = np.min(np.linalg.norm(x[:, None, :] - coords[None, :6, :], axis=2), axis=1)
    for a, b in zip(coords[6:11], coords[7:12]):
        t = np.clip(((x - a) @ (b - a)) / np.dot(b - a, b - a), 0.0, 1.0)
        best = np.minimum(best, np.linalg.norm(x - (a + t[:, None] * (b - a)), axis=1))
    err = np.max(np.abs(distance - best)) / h.min()
    print(f"{backend[12:]}, {f.GetLastRoute()}: {distance.size} samples, renderer "
          f"{f.GetLastRenderer()!r}, max |error| {err:.2e} h")
    if not err <= 1e-3:
        print("FAIL")
        sys.exit(1)
print("1 passed, 0 failed")
