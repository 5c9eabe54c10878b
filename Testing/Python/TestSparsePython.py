"""vtkSparseDistanceField from Python (as docs/sparse-band.md uses it): a closed sphere's
band in bricks. Every piece, read with vtk_to_numpy, equals the dense field
(vtkLinearFactorDistanceField with the same band on its site scan) bit for bit; the
pieces hold every band sample; "inside?" answered from the pieces and the sides' grid
agrees with the sphere at every sample away from it; the pieces written as a .vtpd and
read back are the same; a contour of the pieces at 0 lies on the sphere; bad values
are errors."""
import os
import sys
import tempfile

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkContourFilter
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOXML import vtkXMLPartitionedDataSetReader
from vtkmodules.vtkIOParallelXML import vtkXMLPartitionedDataSetWriter

from vtkdistancefields import vtkLinearFactorDistanceField, vtkSparseDistanceField

failures = []


def check(condition, what):
    print(("ok: " if condition else "FAIL: ") + what)
    if not condition:
        failures.append(what)


sphere = vtkSphereSource()
sphere.SetRadius(1.0)
sphere.SetThetaResolution(32)
sphere.SetPhiResolution(32)
sphere.Update()

band, brick = 2.0, 8
sparse = vtkSparseDistanceField()
sparse.SetInputConnection(sphere.GetOutputPort())
sparse.SetResolution(40)
sparse.SetBandWidth(band)
sparse.SetBrickSize(brick)
sparse.SetSignModeToPseudoNormal()
sparse.SetComputeClosestPoint(True)
sparse.Update()
pieces, sides = sparse.GetOutputDataObject(0), sparse.GetOutputDataObject(1)
check(sparse.GetErrorCode() == 0 and pieces.GetNumberOfPartitions() > 0,
      f"{pieces.GetNumberOfPartitions()} pieces, {sparse.GetLastBandSamples()} band samples")

dense = vtkLinearFactorDistanceField()
dense.SetInputConnection(sphere.GetOutputPort())
dense.SetResolution(40)
dense.SetSignModeToPseudoNormal()
dense.SetRouteToSiteScan()
dense.SetComputeClosestFeature(True)
dense.SetComputeClosestPoint(True)
dense.SetMaximumDistance(band * min(sides.GetSpacing()) / brick)
dense.Update()
field = dense.GetOutput()
nx, ny, nz = field.GetDimensions()
distance = vtk_to_numpy(field.GetPointData().GetArray("Distance")).reshape(nz, ny, nx)
closest = vtk_to_numpy(field.GetPointData().GetArray("ClosestPoint")).reshape(nz, ny, nx, 3)
in_band = vtk_to_numpy(field.GetPointData().GetArray("ClosestFeature")).reshape(nz, ny, nx) != 255


def box(piece):
    """The slices of the whole grid that a piece covers."""
    e = piece.GetExtent()
    return (slice(e[4], e[5] + 1), slice(e[2], e[3] + 1), slice(e[0], e[1] + 1))


covered = np.zeros_like(in_band)
equal = True
for p in range(pieces.GetNumberOfPartitions()):
    piece = pieces.GetPartition(p)
    at = box(piece)
    shape = distance[at].shape
    mine = vtk_to_numpy(piece.GetPointData().GetArray("Distance")).reshape(shape)
    points = vtk_to_numpy(piece.GetPointData().GetArray("ClosestPoint")).reshape(shape + (3,))
    equal &= np.array_equal(mine.view(np.uint32), distance[at].view(np.uint32))
    equal &= np.array_equal(points.view(np.uint32), closest[at].view(np.uint32))
    covered[at] = True
check(equal, "every piece equals the dense field bit for bit")
check(not np.any(in_band & ~covered), "every band sample lies in a piece")

# "Inside?" anywhere: a piece's sign where there is one, else the brick's side.
side = vtk_to_numpy(sides.GetCellData().GetArray("Side"))
piece_of = vtk_to_numpy(sides.GetCellData().GetArray("Piece"))
bx, by, bz = [n - 1 for n in sides.GetDimensions()]
origin, spacing = np.array(field.GetOrigin()), np.array(field.GetSpacing())
k, j, i = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")
radius = np.linalg.norm(origin + spacing * np.stack([i, j, k], axis=-1), axis=-1)
away = np.abs(radius - 1.0) > 0.05
brick_id = (np.minimum(i // brick, bx - 1) + bx * (np.minimum(j // brick, by - 1)
                                                    + by * np.minimum(k // brick, bz - 1)))
inside = np.where(covered, distance < 0, side[brick_id] < 0)
check(np.array_equal(inside[away], radius[away] < 1.0),
      f"inside? from pieces and sides agrees with the sphere at {np.count_nonzero(away)} samples")
check(np.all((piece_of >= 0) == (side == 0)), "a brick has a piece or a side")

# The .vtpd written and read back.
with tempfile.TemporaryDirectory() as folder:
    path = os.path.join(folder, "band.vtpd")
    writer = vtkXMLPartitionedDataSetWriter()
    writer.SetFileName(path)
    writer.SetInputData(pieces)
    writer.Write()
    reader = vtkXMLPartitionedDataSetReader()
    reader.SetFileName(path)
    reader.Update()
    back = reader.GetOutput()
    same = back.GetNumberOfPartitions() == pieces.GetNumberOfPartitions()
    for p in range(min(back.GetNumberOfPartitions(), pieces.GetNumberOfPartitions())):
        a, b = back.GetPartition(p), pieces.GetPartition(p)
        same &= a.GetExtent() == b.GetExtent() and np.array_equal(
            vtk_to_numpy(a.GetPointData().GetArray("Distance")),
            vtk_to_numpy(b.GetPointData().GetArray("Distance")))
    check(same, f"the .vtpd read back ({back.GetNumberOfPartitions()} pieces)")

# A contour of the pieces at 0: on the sphere, within its facets' sag.
worst = 0.0
for p in range(pieces.GetNumberOfPartitions()):
    contour = vtkContourFilter()
    contour.SetInputData(pieces.GetPartition(p))
    contour.SetValue(0, 0.0)
    contour.Update()
    if contour.GetOutput().GetNumberOfPoints():
        xyz = vtk_to_numpy(contour.GetOutput().GetPoints().GetData())
        worst = max(worst, float(np.max(np.abs(np.linalg.norm(xyz, axis=1) - 1.0))))
check(0 < worst < 0.02, f"the zero contour within {worst:.4f} of the unit sphere")

bad = vtkSparseDistanceField()
bad.SetInputConnection(sphere.GetOutputPort())
bad.SetBandWidth(float("nan"))
bad.GlobalWarningDisplayOff()
bad.Update()
check(bad.GetErrorCode() != 0 and bad.GetOutputDataObject(0).GetNumberOfPartitions() == 0,
      "BandWidth NaN is an error, with an empty output")

sys.exit(1 if failures else 0)
