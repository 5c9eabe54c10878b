"""Frame rates of vtkSegmentedDistanceVolumeMapper next to VTK's GPU ray caster on the
same field, window and camera (Yamazaki et al.'s Table 1 gives 12.3 fps
at 128^3 / 256 slices and 1.5 fps at 256^3 / 256 slices on a GeForce4):
- the bunny's signed field (vtkLinearFactorDistanceField) at N^3;
- mapper surface (RegionAware, lit) and mapper composite (pre-integrated distance
  shells), with 32, 64, 128 and 256 slices;
- vtkOpenGLGPUVolumeRayCastMapper in ISOSURFACE (at 0) and COMPOSITE modes (the same
  transfer functions), its sample distance set to the depth of the volume divided by
  the same number of slices;
at 512^2 and 1920x1080. Each figure is the mean of FRAMES frames after a first one
(uploads, table, shader builds), with WaitForCompletion after the last.

usage: xvfb-run -a -s "-screen 0 1920x1200x24 -noreset" /usr/bin/python3 render.py \
         BUILD MESHES [SIZES] [SLICES] [FRAMES]
  e.g. ... render.py build MESH_DIR 128,256 32,64,128,256 3
"""
import math
import sys
import time

from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer, vtkRenderWindow,
                                         vtkVolume, vtkVolumeProperty)
from vtkmodules.vtkRenderingVolumeOpenGL2 import vtkOpenGLGPUVolumeRayCastMapper
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

build, meshes = sys.argv[1], sys.argv[2]
sizes = [int(n) for n in (sys.argv[3] if len(sys.argv) > 3 else "128,256").split(",")]
slice_counts = [int(n) for n in (sys.argv[4] if len(sys.argv) > 4 else "32,64,128,256").split(",")]
frames = int(sys.argv[5]) if len(sys.argv) > 5 else 3
sys.path.insert(0, f"{build}/lib/python3/dist-packages")
from vtkdistancefields import vtkLinearFactorDistanceField, vtkSegmentedDistanceVolumeMapper  # noqa

window = vtkRenderWindow()
window.SetMultiSamples(0)
window.OffScreenRenderingOn()
renderer = vtkRenderer()
window.AddRenderer(renderer)
renderer.SetBackground(0.1, 0.1, 0.15)
print(f"renderer: {window.ReportCapabilities().split('OpenGL renderer string:')[1].split(chr(10))[0].strip()}"
      if "OpenGL renderer string:" in window.ReportCapabilities() else "")


def fps(prop, width, height):
    window.SetSize(width, height)
    renderer.RemoveAllViewProps()
    renderer.AddViewProp(prop)
    window.Render()
    window.WaitForCompletion()
    start = time.perf_counter()
    for _ in range(frames):
        window.Render()
    window.WaitForCompletion()
    return frames / (time.perf_counter() - start)


reader = vtkXMLPolyDataReader()
reader.SetFileName(f"{meshes}/bunny_75k.vtp")
print("| N | window | slices | mapper surface fps | mapper composite fps | VTK isosurface fps | "
      "VTK composite fps |")
print("|---|---|---|---|---|---|---|")
for n in sizes:
    field = vtkLinearFactorDistanceField()
    field.SetInputConnection(reader.GetOutputPort())
    field.SetResolution(n)
    field.SetSignModeToPseudoNormal()
    field.SetBackendToCPU()
    field.Update()
    image = field.GetOutput()
    image.GetPointData().SetActiveScalars("Distance")
    h = min(image.GetSpacing())
    lo, hi = image.GetPointData().GetArray("Distance").GetRange()
    colour = vtkColorTransferFunction()
    colour.AddRGBPoint(lo, 0.25, 0.45, 0.95)
    colour.AddRGBPoint(0, 0.95, 0.85, 0.6)
    colour.AddRGBPoint(hi, 0.95, 0.4, 0.2)
    opacity = vtkPiecewiseFunction()
    for value, alpha in ((lo, 0.02), (-h, 0.02), (0, 1.0), (h, 0.0), (3 * h, 0.0), (4 * h, 0.25),
                         (5 * h, 0.0), (hi, 0.0)):
        opacity.AddPoint(value, alpha)
    shells = vtkVolumeProperty()
    shells.ShadeOn()
    shells.SetColor(colour)
    shells.SetScalarOpacity(opacity)
    shells.SetScalarOpacityUnitDistance(h)
    surface = vtkVolumeProperty()
    surface.ShadeOn()
    iso = vtkVolumeProperty()
    iso.ShadeOn()
    iso.GetIsoSurfaceValues().SetValue(0, 0.0)
    solid = vtkPiecewiseFunction()
    solid.AddPoint(lo, 1.0)
    solid.AddPoint(hi, 1.0)
    iso.SetScalarOpacity(solid)

    mapper = vtkSegmentedDistanceVolumeMapper()
    mapper.SetInputData(image)
    ours = vtkVolume()
    ours.SetMapper(mapper)
    caster = vtkOpenGLGPUVolumeRayCastMapper()
    caster.SetInputData(image)
    caster.AutoAdjustSampleDistancesOff()
    theirs = vtkVolume()
    theirs.SetMapper(caster)
    renderer.ResetCamera(image.GetBounds())
    camera = renderer.GetActiveCamera()
    camera.Azimuth(30)
    camera.Elevation(20)
    camera.OrthogonalizeViewUp()
    renderer.ResetCamera(image.GetBounds())
    b = image.GetBounds()
    diagonal = math.sqrt((b[1] - b[0]) ** 2 + (b[3] - b[2]) ** 2 + (b[5] - b[4]) ** 2)
    for width, height in ((512, 512), (1920, 1080)):
        for slices in slice_counts:
            mapper.SetNumberOfSlices(slices)
            caster.SetSampleDistance(diagonal / slices)
            ours.SetProperty(surface)
            mapper.SetModeToSurface()
            surface_fps = fps(ours, width, height)
            ours.SetProperty(shells)
            mapper.SetModeToComposite()
            composite_fps = fps(ours, width, height)
            theirs.SetProperty(iso)
            caster.SetBlendModeToIsoSurface()
            iso_fps = fps(theirs, width, height)
            theirs.SetProperty(shells)
            caster.SetBlendModeToComposite()
            vtk_composite_fps = fps(theirs, width, height)
            print(f"| {n} | {width}x{height} | {slices} | {surface_fps:.2f} | {composite_fps:.2f} | "
                  f"{iso_fps:.2f} | {vtk_composite_fps:.2f} |", flush=True)
