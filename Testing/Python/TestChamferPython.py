"""vtkPolyDataVoxelizer and vtkChamferVoxelDistance from Python: a mesh voxelized, its
masks handed to the chamfer filter as an image, and the layers checked on every voxel
against a numpy breadth-first search (repeated 6-neighbour dilation)."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from vtkdistancefields import vtkChamferVoxelDistance, vtkPolyDataVoxelizer

reader = vtkXMLPolyDataReader()
reader.SetFileName(sys.argv[1] + "/bunny_small.vtp")

voxelizer = vtkPolyDataVoxelizer()
voxelizer.SetInputConnection(reader.GetOutputPort())
voxelizer.SetResolution(32)
voxelizer.SetModeToBoth()
voxelizer.SetBackendToCPU()

chamfer = vtkChamferVoxelDistance()
chamfer.SetInputConnection(voxelizer.GetOutputPort())
chamfer.SetMetricToManhattan()
chamfer.SetMaximumLayers(5)
chamfer.SignedOn()
chamfer.SetBackendToCPU()
chamfer.Update()

image = voxelizer.GetOutput()
nx, ny, nz = image.GetDimensions()
shape = (nz, ny, nx)  # VTK point order: x fastest
boundary = vtk_to_numpy(image.GetPointData().GetArray("Boundary")).reshape(shape) != 0
solid = vtk_to_numpy(image.GetPointData().GetArray("Solid")).reshape(shape) != 0
field = vtk_to_numpy(chamfer.GetOutput().GetPointData().GetArray("ChamferDistance")).reshape(shape)
unreached = chamfer.GetOutput().GetFieldData().GetArray("UnreachedValue").GetValue(0)

# Breadth-first search by dilation: layer n+1 = neighbours of layer n not yet reached.
expected = np.full(shape, unreached, dtype=np.int64)
expected[boundary] = 0
reached = boundary.copy()
front = boundary.copy()
for layer in range(1, 6):
    grown = np.zeros_like(front)
    grown[1:, :, :] |= front[:-1, :, :]
    grown[:-1, :, :] |= front[1:, :, :]
    grown[:, 1:, :] |= front[:, :-1, :]
    grown[:, :-1, :] |= front[:, 1:, :]
    grown[:, :, 1:] |= front[:, :, :-1]
    grown[:, :, :-1] |= front[:, :, 1:]
    front = grown & ~reached
    reached |= front
    expected[front] = layer
expected[solid] *= -1

wrong = int(np.count_nonzero(field != expected))
print(f"{nx}x{ny}x{nz}: {int(boundary.sum())} boundary, {int(solid.sum())} solid voxels, "
      f"{chamfer.GetLastLayers()} layers, unreached {unreached}, {wrong} voxels differ")
if unreached != 6 or wrong or not (field < 0).any() or chamfer.GetLastLayers() != 5:
    print("FAIL")
    sys.exit(1)
