"""vtkLinearFactorDistanceField from Python: points and a polyline, checked against a
numpy brute force on every sample, through a numpy view of the Distance array, on both
backends and by both CPU routes (the site scan and the per-sample queries), with the
closest point rebuilt from ClosestBarycentric and Gradient. And a
triangle mesh whose cells are stored in 32-bit and in 64-bit arrays, all triangles (the
parallel copy) or with a quad among them (the cell-by-cell copy): the same field and
closest cells either way. And the peak memory a run reports, and the scan's buffer kept
from one execution to the next."""
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
    f.ComputeClosestBarycentricOn()
    f.ComputeGradientOn()
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
    # The closest point again from its cell (vertex cells 0-5, the polyline 6), the piece
    # of it (the polyline's segment) and the coordinates there; x - d g must be it.
    pd = image.GetPointData()
    cell = vtk_to_numpy(pd.GetArray("ClosestCellId"))
    sub = vtk_to_numpy(pd.GetArray("ClosestSubTriangle"))
    bary = vtk_to_numpy(pd.GetArray("ClosestBarycentric")).astype(np.float64)
    gradient = vtk_to_numpy(pd.GetArray("Gradient")).astype(np.float64)
    on_line = cell == 6
    start = np.where(on_line, 6 + sub, np.minimum(cell, 5))
    if (sub[~on_line] != 0).any() or (bary[~on_line] != [1, 0, 0]).any():
        print("FAIL: a vertex cell's piece or coordinates")
        sys.exit(1)
    closest = bary[:, :1] * coords[start] + bary[:, 1:2] * coords[np.minimum(start + 1, 11)]
    gap = np.abs(x - distance[:, None] * gradient - closest).max() / h.min()
    print(f"    x - Distance * Gradient within {gap:.2e} h of the closest point's coordinates")
    if not gap <= 1e-3:
        print("FAIL")
        sys.exit(1)


def triangle_mesh(storage32, with_quad):
    """A vertex cell, then triangles over a jittered grid (and a quad for the last two)."""
    pts = vtkPoints()
    for y in range(4):
        for x in range(4):
            pts.InsertNextPoint(x + 0.1 * rng.uniform(), y + 0.1 * rng.uniform(),
                                0.3 * np.sin(x + y))
    verts, polys = vtkCellArray(), vtkCellArray()
    if storage32:
        verts.Use32BitStorage()
        polys.Use32BitStorage()
    verts.InsertNextCell(1, [0])
    for y in range(3):
        for x in range(3):
            a = 4 * y + x
            if with_quad and (x, y) == (2, 2):
                polys.InsertNextCell(4, [a, a + 1, a + 5, a + 4])
            else:
                polys.InsertNextCell(3, [a, a + 1, a + 5])
                polys.InsertNextCell(3, [a, a + 5, a + 4])
    m = vtkPolyData()
    m.SetPoints(pts)
    m.SetVerts(verts)
    m.SetPolys(polys)
    return m


for with_quad in (False, True):
    rng = np.random.default_rng(11)
    fields = []
    for storage32 in (True, False):
        rng = np.random.default_rng(11)
        f = vtkLinearFactorDistanceField()
        f.SetInputData(triangle_mesh(storage32, with_quad))
        f.SetResolution(20)
        f.SetBackendToCPU()
        f.Update()
        data = f.GetOutput().GetPointData()
        fields.append((vtk_to_numpy(data.GetArray("Distance")).copy(),
                       vtk_to_numpy(data.GetArray("ClosestCellId")).copy()))
    (d32, c32), (d64, c64) = fields
    cells = 1 + (17 if with_quad else 18)
    print(f"cells in 32-bit and 64-bit arrays, quad {with_quad}: closest cells "
          f"{c64.min()}..{c64.max()} of {cells}")
    if not (np.array_equal(d32, d64) and np.array_equal(c32, c64)):
        print("FAIL: the storages give different fields")
        sys.exit(1)
    # The vertex cell is 0 (nearest where the corner it shares wins the tie), the
    # polygons 1.. in order: the last one is reported near its far corner.
    if not (c64.min() == 0 and c64.max() == cells - 1):
        print("FAIL: the closest cells do not number the vertex cell first")
        sys.exit(1)

# The run's peak memory (Linux): at least the arrays it wrote, well within the
# machine. A grid of 160^3 samples with Distance (4 bytes) and ClosestPoint (12 bytes)
# writes 62.5 MiB.
if sys.platform.startswith("linux"):
    f = vtkLinearFactorDistanceField()
    f.SetInputData(mesh)
    f.SetResolution(160)
    f.SetBackendToCPU()
    f.SetPadding(0.5)
    f.ComputeClosestPointOn()
    f.Update()
    n = f.GetOutput().GetNumberOfPoints()
    written = 16 * n / 2**20
    peak = f.GetLastPeakMemory()
    print(f"{n} samples: {written:.1f} MiB of arrays, peak memory {peak:.1f} MiB")
    if not written <= peak <= 4 * written + 64:
        print("FAIL: the peak memory does not hold the arrays, or is far above them")
        sys.exit(1)

# The site scan's nearest-site buffer (8 bytes a sample) stays with the filter between
# executions: reused by a grid at most as large (the same field as a new filter's), freed
# when the grid needs less than half of it, when the input changes, or when asked.
f = vtkLinearFactorDistanceField()
f.SetInputData(triangle_mesh(False, True))
f.SetBackendToCPU()
f.SetRouteToSiteScan()


def run_at(resolution):
    f.SetResolution(resolution)
    f.Update()
    fresh = vtkLinearFactorDistanceField()
    fresh.SetInputData(f.GetInput())
    fresh.SetBackendToCPU()
    fresh.SetRouteToSiteScan()
    fresh.SetResolution(resolution)
    fresh.Update()
    same = np.array_equal(vtk_to_numpy(f.GetOutput().GetPointData().GetArray("Distance")),
                          vtk_to_numpy(fresh.GetOutput().GetPointData().GetArray("Distance")))
    return f.GetOutput().GetNumberOfPoints(), f.GetWorkBufferBytes(), same


kept = []
for resolution in (40, 36, 20):
    kept.append(run_at(resolution))
print("kept between executions (samples, bytes, same field):", kept)
(n40, b40, s40), (n36, b36, s36), (n20, b20, s20) = kept
if not (s40 and s36 and s20):
    print("FAIL: a re-execution's field differs from a new filter's")
    sys.exit(1)
if not (b40 == 8 * n40 and b36 == b40 and b20 == 8 * n20):
    print("FAIL: the buffer is not kept for a smaller grid, or kept for one under half of it")
    sys.exit(1)
f.ReleaseWorkBuffers()
released = f.GetWorkBufferBytes()
f.SetResolution(24)
f.Update()
kept24 = f.GetWorkBufferBytes()
f.SetInputData(triangle_mesh(False, False))
f.SetRouteToSampleQueries()  # the new input's run needs no buffer: none stays
f.Update()
print(f"released: {released} bytes; kept at 24: {kept24}; after a new input: "
      f"{f.GetWorkBufferBytes()}")
if released != 0 or kept24 != 8 * f.GetOutput().GetNumberOfPoints() or f.GetWorkBufferBytes():
    print("FAIL: the buffer is not released when asked or when the input changes")
    sys.exit(1)

# Culling, the earlier name of DomainShape: its setters and getter still work, each call
# with a DeprecationWarning that names the new one.
import warnings  # noqa: E402

f = vtkLinearFactorDistanceField()
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    f.SetCulling(f.CULLING_MANIFOLD)
    manifold = f.GetDomainShape()
    f.SetCullingToNonManifold()
    old = f.GetCulling()
names = [str(w.message) for w in caught if issubclass(w.category, DeprecationWarning)]
print(f"Culling: DomainShape {manifold} then {old}; {len(names)} deprecation warnings")
if manifold != f.DOMAIN_SHAPE_MANIFOLD or old != f.DOMAIN_SHAPE_NON_MANIFOLD:
    print("FAIL: the deprecated Culling calls do not set DomainShape")
    sys.exit(1)
if len(names) != 3 or not all("DomainShape" in n for n in names):
    print(f"FAIL: expected 3 deprecation warnings naming DomainShape: {names}")
    sys.exit(1)
print("1 passed, 0 failed")
