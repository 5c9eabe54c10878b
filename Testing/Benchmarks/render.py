"""Frame rates of vtkSegmentedDistanceVolumeMapper next to VTK's GPU ray caster on the
same field, window and camera (Yamazaki et al.'s Table 1 gives 12.3 fps
at 128^3 / 256 slices and 1.5 fps at 256^3 / 256 slices on a GeForce4):
- the bunny's signed field (vtkLinearFactorDistanceField) at N^3;
- mapper surface (RegionAware, lit) and mapper composite (pre-integrated distance
  shells), with 32, 64, 128 and 256 sample planes across the volume's depth;
- vtkOpenGLGPUVolumeRayCastMapper in ISOSURFACE (at 0) and COMPOSITE modes (the same
  transfer functions), its sample distance set to the volume's depth along the view
  direction divided by the same number (the mapper's plane spacing);
with shading on and off (SHADING: on, off or both), at 512^2 and 1920x1080. A measure is the mean of FRAMES frames after a first one
(uploads, table, shader builds), with WaitForCompletion after the last; the four are
measured in turn REPEATS times and each figure is the median of its REPEATS measures.

usage: xvfb-run -a -s "-screen 0 1920x1200x24 -noreset" /usr/bin/python3 render.py \
         BUILD MESHES [SIZES] [SLICES] [FRAMES] [REPEATS] [SHADING]
  e.g. ... render.py build MESH_DIR 128,256 32,64,128,256 3 5 both
"""
import itertools
import statistics
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
repeats = int(sys.argv[6]) if len(sys.argv) > 6 else 5
shading = {"on": [True], "off": [False], "both": [True, False]}[
    sys.argv[7] if len(sys.argv) > 7 else "both"]
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
print("| N | window | planes | shading | mapper surface fps | VTK isosurface fps | ratio | "
      "mapper composite fps | VTK composite fps | ratio |")
print("|---|---|---|---|---|---|---|---|---|---|")
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
    # The volume's depth along the view direction: what the mapper divides into planes.
    b = image.GetBounds()
    direction = camera.GetDirectionOfProjection()
    depths = [sum(corner[i] * direction[i] for i in range(3))
              for corner in itertools.product((b[0], b[1]), (b[2], b[3]), (b[4], b[5]))]
    depth = max(depths) - min(depths)
    for (width, height), slices, shade in itertools.product(
            ((512, 512), (1920, 1080)), slice_counts, shading):
        for prop in (shells, surface, iso):
            prop.SetShade(shade)
        mapper.SetNumberOfSlices(slices)
        caster.SetSampleDistance(depth / slices)
        measures = {"surface": [], "composite": [], "iso": [], "vtk composite": []}
        for _ in range(repeats):
            ours.SetProperty(surface)
            mapper.SetModeToSurface()
            measures["surface"].append(fps(ours, width, height))
            theirs.SetProperty(iso)
            caster.SetBlendModeToIsoSurface()
            measures["iso"].append(fps(theirs, width, height))
            ours.SetProperty(shells)
            mapper.SetModeToComposite()
            measures["composite"].append(fps(ours, width, height))
            theirs.SetProperty(shells)
            caster.SetBlendModeToComposite()
            measures["vtk composite"].append(fps(theirs, width, height))
        m = {key: statistics.median(values) for key, values in measures.items()}
        print(f"| {n} | {width}x{height} | {slices} | {'on' if shade else 'off'} | "
              f"{m['surface']:.2f} | {m['iso']:.2f} | "
              f"{m['surface'] / m['iso']:.2f} | {m['composite']:.2f} | "
              f"{m['vtk composite']:.2f} | {m['composite'] / m['vtk composite']:.2f} |",
              flush=True)
