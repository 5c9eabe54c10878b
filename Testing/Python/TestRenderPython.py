"""vtkSegmentedDistanceVolumeMapper from Python: an open disk's segmented field, seen at
60 degrees from its normal with a parallel projection, covers pi * cos(60) of the
picture's area, its boundary kept within a voxel (between pi r^2 cos 60 for r = 1 - 4% and
r = 1 + h), every covered pixel in the colour of the region on the viewer's side, and its
depth buffer is written; the same field with an extent that does not start at 0 gives the
same picture; Composite mode builds its table once across frames; PrintSelf and the
string helpers work."""
import math
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkDiskSource
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer,
                                         vtkRenderWindow, vtkVolume, vtkVolumeProperty)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)

from vtkdistancefields import vtkSegmentedDistanceField, vtkSegmentedDistanceVolumeMapper

disk = vtkDiskSource()
disk.SetInnerRadius(0.0)
disk.SetOuterRadius(1.0)
disk.SetCircumferentialResolution(64)
triangles = vtkTriangleFilter()
triangles.SetInputConnection(disk.GetOutputPort())
segment = vtkSegmentedDistanceField()
segment.SetInputConnection(triangles.GetOutputPort())
segment.SetResolution(40)
segment.SetBackendToCPU()
segment.Update()

mapper = vtkSegmentedDistanceVolumeMapper()
mapper.SetInputConnection(segment.GetOutputPort())
volume = vtkVolume()
volume.SetMapper(mapper)
volume.SetProperty(vtkVolumeProperty())
renderer = vtkRenderer()
renderer.AddVolume(volume)
window = vtkRenderWindow()
size = 200
window.SetSize(size, size)
window.SetMultiSamples(0)
window.OffScreenRenderingOn()
window.AddRenderer(renderer)
camera = renderer.GetActiveCamera()
camera.ParallelProjectionOn()
tilt = math.radians(60)
camera.SetFocalPoint(0, 0, 0)
camera.SetPosition(0, -5 * math.sin(tilt), 5 * math.cos(tilt))
camera.SetViewUp(0, 0, 1)
camera.OrthogonalizeViewUp()
camera.SetParallelScale(1.3)
camera.SetClippingRange(2, 8)
window.Render()

depth = vtkFloatArray()
window.GetZbufferData(0, 0, size - 1, size - 1, depth)
z = vtk_to_numpy(depth).copy()
rgb = vtkUnsignedCharArray()
window.GetPixelData(0, 0, size - 1, size - 1, 0, rgb, 0)
pixels = vtk_to_numpy(rgb).reshape(-1, 3).astype(int)
covered = z < 1.0
pixel_area = (2 * 1.3 / size) ** 2
area = covered.sum() * pixel_area
expected = math.pi * math.cos(tilt)
# The viewer sees the disk's front (+z) side: the region on that side, by the field.
front = int(segment.GetOutput().GetPointData().GetArray("RegionIndex").GetTuple1(
    segment.GetOutput().FindPoint(0, 0, 0.2)))
colour = [0.0, 0.0, 0.0]
mapper.GetRegionColor(front, colour)
in_colour = np.all(np.abs(pixels[covered] - 255 * np.array(colour)) <= 3, axis=1)
print(f"{mapper.GetLastRegionCount()} regions, {mapper.GetLastNumberOfSlices()} slices; "
      f"covered area {area:.3f} (pi cos 60 = {expected:.3f}); "
      f"{in_colour.mean() * 100:.1f}% of it in region {front}'s colour")
h = segment.GetOutput().GetSpacing()[0]
largest = math.pi * (1 + h) ** 2 * math.cos(tilt)
print(f"area bounds: {0.96 * expected:.3f} .. {largest:.3f} (h = {h:.4f})")
ok = (mapper.GetLastSegmented() and mapper.GetLastRegionCount() == 2
      and 0.96 * expected < area < largest and in_colour.mean() > 0.99)

# The same field as an image whose extent does not start at 0 (a piece of a grid, a
# cropped image), its points where they were: the same picture.
shifted = vtkImageData()
shifted.ShallowCopy(segment.GetOutput())
e, o, h = shifted.GetExtent(), shifted.GetOrigin(), shifted.GetSpacing()
shift = (5, -3, 7)
shifted.SetExtent(*[e[i] + shift[i // 2] for i in range(6)])
shifted.SetOrigin(*[o[a] - shift[a] * h[a] for a in range(3)])
mapper.SetInputData(shifted)
window.Render()
window.GetZbufferData(0, 0, size - 1, size - 1, depth)
window.GetPixelData(0, 0, size - 1, size - 1, 0, rgb, 0)
moved_z, moved_pixels = vtk_to_numpy(depth).copy(), vtk_to_numpy(rgb).reshape(-1, 3).copy()
differ = (np.abs(moved_z - z) > 1e-6) | np.any(np.abs(moved_pixels.astype(int) - pixels) > 2, axis=1)
print(f"extent starting at {shifted.GetExtent()[::2]}: {differ.sum()} of {differ.size} pixels differ")
ok = ok and differ.mean() < 0.001
mapper.SetInputConnection(segment.GetOutputPort())

# Composite: the table is built once over several frames.
mapper.SetModeToComposite()
ctf = vtkColorTransferFunction()
ctf.AddRGBPoint(0.0, 1, 1, 1)
ctf.AddRGBPoint(1.0, 1, 0, 0)
otf = vtkPiecewiseFunction()
otf.AddPoint(0.0, 0.0)
otf.AddPoint(1.0, 0.5)
volume.GetProperty().SetColor(ctf)
volume.GetProperty().SetScalarOpacity(otf)
for azimuth in (0, 10, 20):
    camera.Azimuth(azimuth)
    window.Render()
print(f"composite: {mapper.GetTableBuilds()} table build(s) over 3 frames, "
      f"mode {mapper.GetModeAsString()}, interpolation {mapper.GetInterpolationAsString()}")
ok = ok and mapper.GetTableBuilds() == 1 and "PreIntegrationTableSize: 256" in str(mapper)
print("ok" if ok else "FAILED")
sys.exit(0 if ok else 1)
