"""vtkMeshDistanceFilter from Python, numpy in and numpy out (the example of
docs/mesh-distance.md): random points around the unit cube [0, 1]^3 (a closed mesh of
12 triangles) against the box's signed distance in closed form, within 1e-12; the
closest points on the box and the gradients of unit length; an image's samples as the
points (the output an image too); the summary in field data. vtkMeshDistanceFunction
through vtkSampleFunction (the same distances) and vtkClipPolyData (a sheet cut along
the cube's faces). vtkClipByMeshDistance: a grid clipped to the box, the unit cube."""
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkCubeSource

from vtkdistancefields import vtkMeshDistanceFilter

cube = vtkCubeSource()
cube.SetBounds(0, 1, 0, 1, 0, 1)
clean = vtkCleanPolyData()
clean.SetInputConnection(cube.GetOutputPort())
triangles = vtkTriangleFilter()
triangles.SetInputConnection(clean.GetOutputPort())
triangles.Update()
surface = triangles.GetOutput()

# The example: numpy points in, numpy distances out.
xyz = np.random.default_rng(3).uniform(-0.5, 1.5, size=(20000, 3))
points = vtkPoints()
points.SetData(numpy_to_vtk(xyz, deep=True))
cloud = vtkPolyData()
cloud.SetPoints(points)
probe = vtkMeshDistanceFilter()
probe.SetInputData(cloud)
probe.SetSurfaceData(surface)
probe.SetSignModeToWindingNumber()
probe.Update()
distance = vtk_to_numpy(probe.GetOutput().GetPointData().GetArray("Distance"))


def box_distance(p):
    """The signed distance to [0, 1]^3."""
    q = np.abs(p - 0.5) - 0.5
    outside = np.linalg.norm(np.maximum(q, 0), axis=1)
    inside = np.minimum(q.max(axis=1), 0)
    return outside + inside


expected = box_distance(xyz)
error = np.abs(distance - expected).max()
assert error < 1e-12, f"largest difference from the box's distance {error}"
assert (distance < 0).sum() == (expected < 0).sum() > 0
out = probe.GetOutput().GetPointData()
closest = vtk_to_numpy(out.GetArray("ClosestPoint"))
assert np.abs(box_distance(closest)).max() < 1e-12, "a closest point off the box"
gradient = vtk_to_numpy(out.GetArray("Gradient"))
assert np.abs(np.linalg.norm(gradient, axis=1) - 1).max() < 1e-9
field = probe.GetOutput().GetFieldData()
farthest = int(field.GetArray("FarthestPointId").GetValue(0))
assert farthest == int(np.argmax(np.abs(expected)))
assert abs(field.GetArray("MaximumAbsoluteDistance").GetValue(0) - np.abs(expected).max()) < 1e-12

# An image's samples: the output is an image with the same arrays.
image = vtkImageData()
image.SetDimensions(9, 8, 7)
image.SetOrigin(-0.25, -0.25, -0.25)
image.SetSpacing(0.2, 0.2, 0.2)
probe.SetInputData(image)
probe.Update()
result = probe.GetOutput()
assert result.IsA("vtkImageData"), result.GetClassName()
samples = np.array([image.GetPoint(i) for i in range(image.GetNumberOfPoints())])
on_grid = vtk_to_numpy(result.GetPointData().GetArray("Distance"))
assert np.abs(on_grid - box_distance(samples)).max() < 1e-12
assert not probe.GetLastBuiltHierarchy(), "the surface's hierarchy was not kept"
print(f"{len(xyz)} points: largest difference {error:.3g}; {len(samples)} samples of an image")

# vtkMeshDistanceFunction: vtkSampleFunction (one point at a time, from vtkSMPTools'
# threads) samples the box's distance; vtkClipPolyData cuts a sheet along the cube.
from vtkmodules.vtkFiltersCore import vtkClipPolyData
from vtkmodules.vtkFiltersSources import vtkPlaneSource
from vtkmodules.vtkImagingHybrid import vtkSampleFunction

from vtkdistancefields import vtkMeshDistanceFunction

function = vtkMeshDistanceFunction()
function.SetInput(surface)
sample = vtkSampleFunction()
sample.SetImplicitFunction(function)
sample.SetModelBounds(-0.5, 1.5, -0.5, 1.5, -0.5, 1.5)
sample.SetSampleDimensions(17, 13, 11)
sample.SetOutputScalarTypeToDouble()
sample.ComputeNormalsOff()
sample.Update()
grid = sample.GetOutput()
nodes = np.array([grid.GetPoint(i) for i in range(grid.GetNumberOfPoints())])
sampled = vtk_to_numpy(grid.GetPointData().GetScalars())
assert np.abs(sampled - box_distance(nodes)).max() < 1e-12, "vtkSampleFunction's values"

sheet = vtkPlaneSource()
sheet.SetOrigin(-0.52, -0.52, 0.5)  # no vertex on a face: every cut interpolates
sheet.SetPoint1(1.48, -0.52, 0.5)
sheet.SetPoint2(-0.52, 1.48, 0.5)
sheet.SetResolution(40, 40)
clip = vtkClipPolyData()
clip.SetInputConnection(sheet.GetOutputPort())
clip.SetClipFunction(function)
clip.InsideOutOn()  # keep the negative side: the sheet within the cube
clip.Update()
bounds = clip.GetOutput().GetBounds()
assert max(abs(b - e) for b, e in zip(bounds, (0, 1, 0, 1, 0.5, 0.5))) < 1e-9, bounds
print(f"vtkSampleFunction: {len(nodes)} samples; vtkClipPolyData: the square {bounds}")

# vtkClipByMeshDistance: a grid whose cells straddle the box's faces, clipped to the box
# (the winding sign): the unit cube, but where the distance outside is to an edge or a
# corner of the box (not linear along a cell's edge): its cells' volume within 2%, every
# kept point inside the cube or on it.
from vtkmodules.vtkFiltersVerdict import vtkCellSizeFilter  # noqa: E402

from vtkdistancefields import vtkClipByMeshDistance  # noqa: E402

block = vtkImageData()
block.SetDimensions(21, 21, 21)
block.SetOrigin(-0.55, -0.55, -0.55)
block.SetSpacing(0.1, 0.1, 0.1)
cut = vtkClipByMeshDistance()
cut.SetInputData(block)
cut.SetSurfaceData(surface)
cut.Update()
sizes = vtkCellSizeFilter()
sizes.SetInputConnection(cut.GetOutputPort())
sizes.Update()
volume = vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Volume")).sum()
bounds = cut.GetOutput().GetBounds()
kept = vtk_to_numpy(cut.GetOutput().GetPointData().GetArray("Distance"))
assert max(abs(b - e) for b, e in zip(bounds, (0, 1, 0, 1, 0, 1))) < 1e-9, bounds
assert abs(volume - 1) < 0.02 and kept.max() <= 1e-12, (volume, kept.max())
print(f"vtkClipByMeshDistance: {cut.GetOutput().GetNumberOfCells()} cells, bounds {bounds}, "
      f"volume {volume:.6f}")
