"""Frame times and surface accuracy of vtkSegmentedDistanceVolumeMapper next to VTK's own
routes to a distance field's surface, on the same field, window and camera:
- mapper surface: this module's mapper, Surface mode (RegionAware);
- mapper composite: the same, Composite mode (pre-integrated, distance shells);
- vtk isosurface: vtkGPUVolumeRayCastMapper with SetBlendModeToIsoSurface at 0 (sample
  distance = the voxel spacing, as the mapper's slices);
- vtk contour: vtkFlyingEdges3D at 0, then vtkPolyDataMapper (contouring time separate).
Depth accuracy: the median and 90th percentile, in voxels, of the depth difference from
the contour's picture where both cover a pixel (the contour is the field's trilinear...
linear-on-edges zero level set, the reference a surface renderer should reproduce).

usage: xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" /usr/bin/python3 render.py \
         BUILD MESHES [N] [SIZE]
"""
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkRenderingCore import (vtkActor, vtkColorTransferFunction, vtkPolyDataMapper,
                                         vtkRenderer, vtkRenderWindow, vtkVolume,
                                         vtkVolumeProperty)
from vtkmodules.vtkRenderingVolumeOpenGL2 import vtkOpenGLGPUVolumeRayCastMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

build, meshes = sys.argv[1], sys.argv[2]
n = int(sys.argv[3]) if len(sys.argv) > 3 else 128
size = int(sys.argv[4]) if len(sys.argv) > 4 else 512
sys.path.insert(0, f"{build}/lib/python3/dist-packages")
from vtkdistancefields import (vtkLinearFactorDistanceField, vtkSegmentedDistanceField,  # noqa
                               vtkSegmentedDistanceVolumeMapper)

window = vtkRenderWindow()
window.SetSize(size, size)
window.SetMultiSamples(0)
window.OffScreenRenderingOn()
renderer = vtkRenderer()
window.AddRenderer(renderer)


def frame_times(prop, frames=5):
    renderer.RemoveAllViewProps()
    renderer.AddViewProp(prop)
    start = time.perf_counter()
    window.Render()
    window.WaitForCompletion()
    first = time.perf_counter() - start
    start = time.perf_counter()
    for _ in range(frames):
        window.Render()
    window.WaitForCompletion()
    steady = (time.perf_counter() - start) / frames
    depth = vtkFloatArray()
    window.GetZbufferData(0, 0, size - 1, size - 1, depth)
    return first, steady, vtk_to_numpy(depth).copy()


def view_depth(z):
    near, far = renderer.GetActiveCamera().GetClippingRange()
    ndc = 2.0 * z - 1.0
    return 2.0 * near * far / ((far + near) - ndc * (far - near))


def depth_error(z, reference, h):
    both = (z < 1) & (reference < 1)
    if not both.any():
        return float("nan"), float("nan"), 0.0
    e = np.abs(view_depth(z[both]) - view_depth(reference[both])) / h
    differ = ((z < 1) != (reference < 1)).sum() / max(((z < 1) | (reference < 1)).sum(), 1)
    return np.median(e), np.percentile(e, 90), differ


print(f"| field | N | window | route | first frame s | frame s | depth median (voxels) | "
      f"depth p90 (voxels) | pixels differing |")
print("|---|---|---|---|---|---|---|---|---|")
for name, kind in (("bunny_75k", "signed"), ("max3ds_export", "segmented")):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(f"{meshes}/{name}.vtp")
    reader.Update()
    if kind == "signed":
        field = vtkLinearFactorDistanceField()
        field.SetSignModeToPseudoNormal()
    else:
        field = vtkSegmentedDistanceField()
    field.SetInputConnection(reader.GetOutputPort())
    field.SetResolution(n)
    field.SetBackendToCPU()
    field.Update()
    image = field.GetOutput()
    array = "Distance" if kind == "signed" else "SegmentedDistance"
    image.GetPointData().SetActiveScalars(array)
    h = min(image.GetSpacing())
    renderer.ResetCamera(image.GetBounds())
    renderer.GetActiveCamera().Azimuth(30)
    renderer.GetActiveCamera().Elevation(20)
    renderer.GetActiveCamera().OrthogonalizeViewUp()
    renderer.ResetCamera(image.GetBounds())
    rows = []
    reference = None
    if kind == "signed":
        start = time.perf_counter()
        contour = vtkFlyingEdges3D()
        contour.SetInputData(image)
        contour.SetValue(0, 0.0)
        contour.Update()
        contouring = time.perf_counter() - start
        pm = vtkPolyDataMapper()
        pm.SetInputConnection(contour.GetOutputPort())
        actor = vtkActor()
        actor.SetMapper(pm)
        first, steady, reference = frame_times(actor)
        rows.append((f"vtk contour (+{contouring:.2f} s contouring)", first, steady, reference))
    prop = vtkVolumeProperty()
    prop.ShadeOn()
    mapper = vtkSegmentedDistanceVolumeMapper()
    mapper.SetInputData(image)
    volume = vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)
    first, steady, z = frame_times(volume)
    rows.append(("mapper surface", first, steady, z))
    if kind == "signed":
        iso = vtkOpenGLGPUVolumeRayCastMapper()
        iso.SetInputData(image)
        iso.SetBlendModeToIsoSurface()
        iso.AutoAdjustSampleDistancesOff()
        iso.SetSampleDistance(h)
        iprop = vtkVolumeProperty()
        iprop.ShadeOn()
        iprop.GetIsoSurfaceValues().SetValue(0, 0.0)
        otf = vtkPiecewiseFunction()
        otf.AddPoint(-1e6, 1.0)
        otf.AddPoint(1e6, 1.0)
        iprop.SetScalarOpacity(otf)
        ctf = vtkColorTransferFunction()
        ctf.AddRGBPoint(0.0, 1, 1, 1)
        iprop.SetColor(ctf)
        ivolume = vtkVolume()
        ivolume.SetMapper(iso)
        ivolume.SetProperty(iprop)
        first, steady, z = frame_times(ivolume)
        rows.append(("vtk isosurface (ray caster)", first, steady, z))
        mapper.SetModeToComposite()
        r0, r1 = image.GetPointData().GetArray("Distance").GetRange()
        ctf2 = vtkColorTransferFunction()
        ctf2.AddRGBPoint(r0, 0.25, 0.45, 0.95)
        ctf2.AddRGBPoint(0, 0.95, 0.85, 0.6)
        ctf2.AddRGBPoint(r1, 0.95, 0.4, 0.2)
        otf2 = vtkPiecewiseFunction()
        for value, alpha in ((r0, 0.02), (-h, 0.02), (0, 1.0), (h, 0.0), (r1, 0.0)):
            otf2.AddPoint(value, alpha)
        prop.SetColor(ctf2)
        prop.SetScalarOpacity(otf2)
        prop.SetScalarOpacityUnitDistance(h)
        first, steady, _ = frame_times(volume)
        rows.append(("mapper composite", first, steady, None))
    for route, first, steady, z in rows:
        if reference is not None and z is not None and route.startswith(("mapper", "vtk iso")):
            median, p90, differ = depth_error(z, reference, h)
            accuracy = f"{median:.3f} | {p90:.3f} | {100 * differ:.2f}%"
        else:
            accuracy = "— | — | —"
        print(f"| {name} ({kind}) | {n} | {size}² | {route} | {first:.3f} | {steady:.3f} | "
              f"{accuracy} |", flush=True)
