"""vtkSegmentedDistanceField from Python: an open disk gives two regions (its front and
back meet only across its boundary), the field data describes them, and
SegmentedDistance = min(Distance, Delta) + RegionOffset * RegionIndex; blended with
itself (vtkDistanceFieldBlend), the field is unchanged; two squares crossing without a
shared edge make four regions when cut along the crossing (CutSelfIntersections), two
uncut."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkDiskSource

from vtkdistancefields import vtkSegmentedDistanceField

disk = vtkDiskSource()
disk.SetInnerRadius(0.0)
disk.SetOuterRadius(1.0)
disk.SetCircumferentialResolution(32)
triangles = vtkTriangleFilter()
triangles.SetInputConnection(disk.GetOutputPort())

segment = vtkSegmentedDistanceField()
segment.SetInputConnection(triangles.GetOutputPort())
segment.SetResolution(24)
segment.SetBackendToCPU()
segment.Update()

image = segment.GetOutput()
fd = image.GetFieldData()
pd = image.GetPointData()
f = vtk_to_numpy(pd.GetArray("SegmentedDistance"))
r = vtk_to_numpy(pd.GetArray("RegionIndex"))
d = vtk_to_numpy(pd.GetArray("Distance"))
delta = fd.GetArray("Delta").GetValue(0)
offset = fd.GetArray("RegionOffset").GetValue(0)
sides = vtk_to_numpy(fd.GetArray("RegionSides"))
expected = np.minimum(d.astype(np.float64), delta) + offset * r
print(f"{segment.GetLastRegionCount()} regions, {segment.GetLastPatchCount()} patch, "
      f"sides {sides.tolist()}, largest |f - expected| {np.abs(f - expected).max():.3g}")
ok = (segment.GetLastRegionCount() == 2 and fd.GetArray("RegionCount").GetValue(0) == 2
      and sides.tolist() == [[0, 0, 0], [1, 0, 1]]
      and np.abs(f - expected).max() <= 1e-6 * (offset * 2)
      and set(np.unique(r).tolist()) == {0, 1})
if not ok:
    print("FAIL")
    sys.exit(1)

# vtkDistanceFieldBlend: a field blended with itself is itself.
from vtkdistancefields import vtkDistanceFieldBlend  # noqa: E402

blend = vtkDistanceFieldBlend()
blend.SetInputConnection(0, segment.GetOutputPort())
blend.SetInputConnection(1, segment.GetOutputPort())
blend.SetT(0.4)
blend.Update()
blended = blend.GetOutput().GetPointData()
same = (np.array_equal(vtk_to_numpy(blended.GetArray("RegionIndex")), r)
        and np.abs(vtk_to_numpy(blended.GetArray("Distance")) - d).max() <= 1e-6 * delta)
print(f"blend with itself at T = 0.4: {'the same field' if same else 'differs'}")
if not same:
    print("FAIL")
    sys.exit(1)

# vtkSegmentedDistanceContour: the disk's surface, every triangle between regions 0 and 1,
# every point on the disk's plane (within 2% of a spacing: the rim's vertices are the
# least-squares points of the tangent planes around a polygonal rim) and within its rim.
from vtkdistancefields import vtkSegmentedDistanceContour  # noqa: E402

contour = vtkSegmentedDistanceContour()
contour.SetInputConnection(segment.GetOutputPort())
contour.Update()
surface = contour.GetOutput()
xyz = vtk_to_numpy(surface.GetPoints().GetData())
pairs = vtk_to_numpy(surface.GetCellData().GetArray("Regions"))
h = image.GetSpacing()[0]
print(f"contour: {surface.GetNumberOfCells()} triangles, largest |z| {np.abs(xyz[:, 2]).max():.3g}, "
      f"largest radius {np.hypot(xyz[:, 0], xyz[:, 1]).max():.4f}")
if (surface.GetNumberOfCells() == 0 or not np.all(pairs == [0, 1])
        or np.abs(xyz[:, 2]).max() > 0.02 * h or np.hypot(xyz[:, 0], xyz[:, 1]).max() > 1.0 + 1e-6):
    print("FAIL")
    sys.exit(1)

# The paper's vertices (UseClosestPoints off): every point on the disk's plane, no
# feature fans.
paper = vtkSegmentedDistanceContour()
paper.SetInputConnection(segment.GetOutputPort())
paper.UseClosestPointsOff()
paper.SetFeatureAngle(45)
paper.Update()
flat = vtk_to_numpy(paper.GetOutput().GetPoints().GetData())
print(f"paper's vertices: {paper.GetOutput().GetNumberOfCells()} triangles, largest |z| "
      f"{np.abs(flat[:, 2]).max():.3g}, {paper.GetLastFeatureCells()} feature cells")
if (paper.GetOutput().GetNumberOfCells() == 0
        or np.abs(flat[:, 2]).max() > 1e-6 or paper.GetLastFeatureCells() != 0):
    print("FAIL")
    sys.exit(1)


# Two squares crossing along the z axis without a shared edge: cut along the crossing
# (CutSelfIntersections, the default), four half-planes and four regions; uncut, two.
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData

points = vtkPoints()
quads = vtkCellArray()
for c, s in ((1.0, 0.1), (-0.2, 1.0)):
    ids = [points.InsertNextPoint(-c, -s, -1), points.InsertNextPoint(c, s, -1),
           points.InsertNextPoint(c, s, 1), points.InsertNextPoint(-c, -s, 1)]
    quads.InsertNextCell(4, ids)
crossed = vtkPolyData()
crossed.SetPoints(points)
crossed.SetPolys(quads)
counts = {}
for cut in (True, False):
    f = vtkSegmentedDistanceField()
    f.SetInputData(crossed)
    f.SetResolution(20)
    f.SetBackendToCPU()
    f.SetCutSelfIntersections(cut)
    f.Update()
    counts[cut] = (f.GetLastRegionCount(), f.GetLastCrossedTriangles())
print(f"crossed squares: cut {counts[True]}, uncut {counts[False]} (regions, triangles cut)")
# A build configured with -DDF_USE_CGAL=OFF finds the crossing but cannot cut it.
expected_cut = (4, 4) if vtkSegmentedDistanceField.IsSelfIntersectionCutAvailable() else (2, 0)
if counts[True] != expected_cut or counts[False] != (2, 0):
    print("FAIL: expected", expected_cut, "when cut")
    sys.exit(1)
