"""Benchmark (not a test): vtkSparseDistanceField at large grids, with spot checks.

PYTHONPATH=build/lib/python3/dist-packages python3 Testing/Benchmarks/sparse_band.py \
    MESH N [BAND] [BRICK] [CHECKS] [SIGN]

Runs the sparse band of MESH (.vtp or .ply) on the default grid of resolution N, signed by
SIGN (pseudonormal, the default, or winding), BAND spacings (default 3) in bricks of BRICK
samples (default 32), and
prints the filter's time, stages, pieces, band samples and their memory; run it under
/usr/bin/time -v for the process's peak memory. With CHECKS > 0, that many random band
samples of the pieces are compared with a brute-force distance to every triangle (numpy,
double precision; the error in spacings), and that many random samples beyond the band
(in bricks without a piece, and the far samples of pieces) have their side compared
with the winding number's (vtkMeshDistanceFilter, SignMode WindingNumber)."""
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from vtkdistancefields import vtkMeshDistanceFilter, vtkSparseDistanceField


def point_triangle_distance(p, a, b, c):
    """Distance from point p to every triangle (a, b, c): arrays (T, 3), in double
    (Ericson, Real-Time Collision Detection, 5.1.5: the closest point by regions)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = np.einsum("ij,ij->i", ab, ap), np.einsum("ij,ij->i", ac, ap)
    bp = p - b
    d3, d4 = np.einsum("ij,ij->i", ab, bp), np.einsum("ij,ij->i", ac, bp)
    cp = p - c
    d5, d6 = np.einsum("ij,ij->i", ab, cp), np.einsum("ij,ij->i", ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = va + vb + vc
        v, w = vb / denom, vc / denom
        closest = a + ab * v[:, None] + ac * w[:, None]  # the interior
        # Edges and corners, the later assignments taking precedence as in Ericson's order.
        t = np.where(d3 - d4 + d5 - d6 != 0, (d4 - d3) / ((d4 - d3) + (d5 - d6)), 0)
        bc = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
        closest[bc] = (b + (c - b) * t[:, None])[bc]
        t = np.where(d2 - d6 != 0, d2 / (d2 - d6), 0)
        acr = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        closest[acr] = (a + ac * t[:, None])[acr]
        t = np.where(d1 - d3 != 0, d1 / (d1 - d3), 0)
        abr = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        closest[abr] = (a + ab * t[:, None])[abr]
    closest[(d6 >= 0) & (d5 <= d6)] = c[(d6 >= 0) & (d5 <= d6)]
    closest[(d3 >= 0) & (d4 <= d3)] = b[(d3 >= 0) & (d4 <= d3)]
    closest[(d1 <= 0) & (d2 <= 0)] = a[(d1 <= 0) & (d2 <= 0)]
    return np.sqrt(np.nanmin(np.einsum("ij,ij->i", closest - p, closest - p)))


def read(path):
    reader = vtkXMLPolyDataReader() if path.endswith(".vtp") else vtkPLYReader()
    reader.SetFileName(path)
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(reader.GetOutputPort())
    triangles.Update()
    return triangles.GetOutput()


def main(path, n, band=3.0, brick=32, checks=0, sign="pseudonormal"):
    mesh = read(path)
    sparse = vtkSparseDistanceField()
    sparse.SetInputData(mesh)
    sparse.SetResolution(n)
    sparse.SetBandWidth(band)
    sparse.SetBrickSize(brick)
    sparse.SetSignMode({"pseudonormal": 1, "winding": 2}[sign])
    start = time.perf_counter()
    sparse.Update()
    seconds = time.perf_counter() - start
    pieces, sides = sparse.GetOutputDataObject(0), sparse.GetOutputDataObject(1)
    print(f"{path.split('/')[-1]} {n}^3 band {band:g} brick {brick} {sign}: {seconds:.2f} s "
          f"(filter {sparse.GetLastTime():.2f} s), {sparse.GetLastPieces()} pieces "
          f"({sparse.GetLastCandidateBricks()} candidate bricks, "
          f"{sparse.GetLastWindingBricksDecided()} beyond the band signed by sample), "
          f"{sparse.GetLastBandSamples()} band samples, pieces {sparse.GetLastPieceMemory():.0f} MiB, "
          f"run peak {sparse.GetLastPeakMemory():.0f} MiB; stages {sparse.GetLastStageTimes()}",
          flush=True)
    if checks <= 0:
        return 0
    rng = np.random.default_rng(1)
    spacing = np.array(pieces.GetPartition(0).GetSpacing())
    origin = np.array(pieces.GetPartition(0).GetOrigin())
    h = spacing.min()
    xyz = vtk_to_numpy(mesh.GetPoints().GetData()).astype(np.float64)
    ids = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    a, b, c = xyz[ids[:, 0]], xyz[ids[:, 1]], xyz[ids[:, 2]]
    # Band samples: a random piece, a random sample of it within the band.
    worst, far_points, far_sides = 0.0, [], []
    for _ in range(checks):
        piece = pieces.GetPartition(int(rng.integers(pieces.GetNumberOfPartitions())))
        e = piece.GetExtent()
        dims = (e[1] - e[0] + 1, e[3] - e[2] + 1, e[5] - e[4] + 1)
        distance = vtk_to_numpy(piece.GetPointData().GetArray("Distance"))
        hidden = vtk_to_numpy(piece.GetPointData().GetArray("vtkGhostType")) != 0
        for want_band in (True, False):
            choices = np.flatnonzero(hidden != want_band)
            if len(choices) == 0:
                continue
            at = int(rng.choice(choices))
            ijk = np.array([e[0] + at % dims[0], e[2] + at // dims[0] % dims[1],
                            e[4] + at // (dims[0] * dims[1])])
            x = origin + spacing * ijk
            if want_band:
                exact = point_triangle_distance(x, a, b, c)
                worst = max(worst, abs(abs(float(distance[at])) - exact) / h)
            else:
                far_points.append(x)
                far_sides.append(-1 if distance[at] < 0 else 1)
    # Far samples in bricks without a piece: their brick's side.
    side = vtk_to_numpy(sides.GetCellData().GetArray("Side"))
    counts = [d - 1 for d in sides.GetDimensions()]
    empty = np.flatnonzero(side != 0)
    for brick_id in rng.choice(empty, size=min(checks, len(empty)), replace=False):
        bijk = np.array([brick_id % counts[0], brick_id // counts[0] % counts[1],
                         brick_id // (counts[0] * counts[1])])
        ijk = bijk * brick + rng.integers(0, brick, size=3)
        far_points.append(origin + spacing * ijk)
        far_sides.append(int(side[brick_id]))
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.array(far_points), deep=True))
    cloud = vtkPolyData()
    cloud.SetPoints(points)
    winding = vtkMeshDistanceFilter()
    winding.SetInputData(0, cloud)
    winding.SetInputData(1, mesh)
    winding.SetSignModeToWindingNumber()
    winding.Update()
    signs = np.where(vtk_to_numpy(winding.GetOutput().GetPointData().GetArray("Distance")) < 0, -1, 1)
    wrong = int(np.count_nonzero(signs != np.array(far_sides)))
    print(f"checks: {checks} band samples against brute force, worst error {worst:.2e} h; "
          f"{len(far_sides)} samples beyond the band, {wrong} sides unlike the winding number's",
          flush=True)
    return 0


if __name__ == "__main__":
    a = sys.argv[1:]
    sys.exit(main(a[0], int(a[1]), float(a[2]) if len(a) > 2 else 3.0,
                  int(a[3]) if len(a) > 3 else 32, int(a[4]) if len(a) > 4 else 0,
                  a[5] if len(a) > 5 else "pseudonormal"))
