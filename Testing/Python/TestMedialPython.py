"""vtkMedialAxisFilter from Python: the medial voxels of a sphere lie at its centre, and
the point output (port 1) has one point per medial voxel."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkSphereSource

from vtkdistancefields import vtkMedialAxisFilter

sphere = vtkSphereSource()
sphere.SetCenter(0.3, -0.2, 0.1)
sphere.SetRadius(1.0)
sphere.SetThetaResolution(64)
sphere.SetPhiResolution(64)
triangles = vtkTriangleFilter()
triangles.SetInputConnection(sphere.GetOutputPort())

medial = vtkMedialAxisFilter()
medial.SetInputConnection(triangles.GetOutputPort())
medial.SetResolution(48)
medial.SetSeparationAngle(60)
medial.SetBackendToCPU()
medial.Update()

image = medial.GetOutputDataObject(0)
points = medial.GetOutputDataObject(1)
mask = vtk_to_numpy(image.GetPointData().GetArray("Medial"))
xyz = vtk_to_numpy(points.GetPoints().GetData())
h = image.GetSpacing()[0]
far = np.linalg.norm(xyz - np.array([0.3, -0.2, 0.1]), axis=1).max() / h if len(xyz) else np.inf
print(f"{int(mask.sum())} medial voxels, {points.GetNumberOfPoints()} points, "
      f"farthest {far:.2f} spacings from the centre")
if mask.sum() == 0 or points.GetNumberOfPoints() != int(mask.sum()) or far > 1.5:
    print("FAIL")
    sys.exit(1)
