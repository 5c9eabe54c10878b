"""Metamorphosis of non-manifold surfaces (Yamazaki et al., SMI 2003, section 5.2 and Figs. 9-10): a
ball divided by an inner wall blends into a rounded box divided the same way. Each is a
closed surface with a junction circle where the wall meets the shell, so its segmented
distance field has three regions (outside and two chambers) that a signed distance field
cannot hold; vtkDistanceFieldBlend moves every interface linearly from one shape to the
other, and vtkSegmentedDistanceVolumeMapper draws each frame translucent, each surface
in the colour of the region on the viewer's side, so the wall and both chambers show.

usage: /usr/bin/python3 blend_sequence.py OUT_DIR [FRAMES] [RESOLUTION]
       (needs an X display: xvfb-run -a ...)
Writes OUT_DIR/blend_00.png ... and prints the time of each stage. It also checks what it
shows, and exits with status 1 when a check fails: each field has three regions; the
blend's ends are the two fields exactly; along the +x axis the chamber's outer interface
moves linearly from the ball's radius to the box's; every frame draws the shapes.
"""
import math
import os
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkRenderer, vtkRenderWindow, vtkTextActor, vtkVolume,
                                         vtkVolumeProperty, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingFreeType  # noqa: F401 (the caption's text)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)

from vtkdistancefields import (vtkDistanceFieldBlend, vtkSegmentedDistanceField,
                               vtkSegmentedDistanceVolumeMapper)

out = sys.argv[1]
frames = int(sys.argv[2]) if len(sys.argv) > 2 else 9
resolution = int(sys.argv[3]) if len(sys.argv) > 3 else 64
os.makedirs(out, exist_ok=True)


def walled_shape(radius, rings=24, sectors=48):
    """A star-shaped closed surface r = radius(u) around the origin, split by the wall
    x = 0 into its left and right shells, plus the wall: three patches meeting along the
    circle x = 0, built alike for every shape so that their patches (and so their
    regions) correspond."""
    points, polys = vtkPoints(), vtkCellArray()

    def point(theta, phi, scale=1.0):
        u = (math.cos(theta), math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi))
        r = scale * radius(u)
        return points.InsertNextPoint(r * u[0], r * u[1], r * u[2])

    def shell(theta0, theta1):
        # rings from theta0 (a pole) to theta1 (the junction circle), outward facing.
        pole = point(theta0, 0.0)
        grid = [[point(theta0 + (theta1 - theta0) * i / rings, 2 * math.pi * j / sectors)
                 for j in range(sectors)] for i in range(1, rings + 1)]
        flip = theta1 < theta0
        for j in range(sectors):
            a, b = grid[0][j], grid[0][(j + 1) % sectors]
            polys.InsertNextCell(3, [pole, b, a] if flip else [pole, a, b])
        for i in range(rings - 1):
            for j in range(sectors):
                a, b = grid[i][j], grid[i][(j + 1) % sectors]
                c, d = grid[i + 1][j], grid[i + 1][(j + 1) % sectors]
                polys.InsertNextCell(3, [a, d, b] if flip else [a, b, d])
                polys.InsertNextCell(3, [a, c, d] if flip else [a, d, c])

    shell(math.pi, math.pi / 2)  # left shell (x < 0)
    shell(0.0, math.pi / 2)      # right shell (x > 0)
    # The wall: the disk x = 0 out to the junction circle, facing +x.
    centre = points.InsertNextPoint(0, 0, 0)
    wall = [[point(math.pi / 2, 2 * math.pi * j / sectors, i / rings) for j in range(sectors)]
            for i in range(1, rings + 1)]
    for j in range(sectors):
        polys.InsertNextCell(3, [centre, wall[0][(j + 1) % sectors], wall[0][j]])
    for i in range(rings - 1):
        for j in range(sectors):
            a, b = wall[i][j], wall[i][(j + 1) % sectors]
            c, d = wall[i + 1][j], wall[i + 1][(j + 1) % sectors]
            polys.InsertNextCell(3, [a, d, c])
            polys.InsertNextCell(3, [a, b, d])
    mesh = vtkPolyData()
    mesh.SetPoints(points)
    mesh.SetPolys(polys)
    return mesh


def ball(u):
    return 0.7


def rounded_box(u):
    return 1.05 / sum(abs(c) ** 8 for c in u) ** (1 / 8)


# Both fields on one grid (the blend needs it): the box around both shapes, padded.
n, lo, hi = resolution, -1.3, 1.3
spacing = (hi - lo) / (n - 1)
fields = []
start = time.perf_counter()
for shape in (ball, rounded_box):
    segment = vtkSegmentedDistanceField()
    segment.SetInputData(walled_shape(shape))
    segment.ExplicitGridOn()
    segment.SetGridOrigin(lo, lo, lo)
    segment.SetGridSpacing(spacing, spacing, spacing)
    segment.SetGridDimensions(n, n, n)
    segment.Update()
    fields.append(segment.GetOutput())
print(f"two segmented fields, {n}^3: {time.perf_counter() - start:.2f} s "
      f"({fields[0].GetFieldData().GetArray('RegionCount').GetValue(0):.0f} regions each)")

blend = vtkDistanceFieldBlend()
blend.SetInputData(0, fields[0])
blend.SetInputData(1, fields[1])
mapper = vtkSegmentedDistanceVolumeMapper()
mapper.SetInputConnection(blend.GetOutputPort())
mapper.SetSurfaceOpacity(0.55)
prop = vtkVolumeProperty()
prop.ShadeOn()
prop.SetAmbient(0.25)
prop.SetDiffuse(0.7)
prop.SetSpecular(0.3)
prop.SetSpecularPower(30)
volume = vtkVolume()
volume.SetMapper(mapper)
volume.SetProperty(prop)
renderer = vtkRenderer()
renderer.AddVolume(volume)
renderer.SetBackground(0.1, 0.1, 0.15)
# What each frame shows, in its top-left corner.
caption = vtkTextActor()
caption.GetTextProperty().SetFontSize(12)
caption.GetTextProperty().SetColor(0.95, 0.95, 0.95)
caption.GetTextProperty().SetVerticalJustificationToTop()
caption.SetDisplayPosition(8, 352)
renderer.AddActor2D(caption)
window = vtkRenderWindow()
window.SetSize(360, 360)
window.SetMultiSamples(0)
window.OffScreenRenderingOn()
window.AddRenderer(renderer)
camera = renderer.GetActiveCamera()
camera.SetPosition(3.0, -4.9, 3.3)
camera.SetFocalPoint(0, 0, 0)
camera.SetViewUp(0, 0, 1)
renderer.ResetCameraClippingRange(lo, hi, lo, hi, lo, hi)
grab = vtkWindowToImageFilter()
grab.SetInput(window)
grab.ReadFrontBufferOff()
writer = vtkPNGWriter()
writer.SetInputConnection(grab.GetOutputPort())
failures = []


def check(ok, what):
    print(("ok      " if ok else "FAILED  ") + what)
    if not ok:
        failures.append(what)


def arrays(image):
    point_data = image.GetPointData()
    return (vtk_to_numpy(point_data.GetArray("Distance")),
            vtk_to_numpy(point_data.GetArray("RegionIndex")))


def chamber_radius(image):
    """Where the chamber at +x ends along the +x axis (the samples nearest y = z = 0): the
    last chamber sample plus its distance to the surface."""
    distance, region = arrays(image)
    distance = distance.reshape(n, n, n)  # z, y, x
    region = region.reshape(n, n, n)
    j = k = int(round((0.0 - lo) / spacing))
    i0 = int(math.floor((0.0 - lo) / spacing)) + 1  # the first sample with x > 0
    chamber = region[k, j, i0]
    i = i0
    while i + 1 < n and region[k, j, i + 1] == chamber:
        i += 1
    return lo + i * spacing + float(distance[k, j, i])


for field in fields:
    check(field.GetFieldData().GetArray("RegionCount").GetValue(0) == 3,
          "a walled shape's field has three regions (outside and two chambers)")
background = np.array([0.1, 0.1, 0.15]) * 255
for k in range(frames):
    t = k / (frames - 1) if frames > 1 else 0.0
    blend.SetT(t)
    caption.SetInput(f"t = {t:.2f}: walled ball (t = 0) to walled box (t = 1)\n"
                     "translucent surfaces, each in the colour of the\n"
                     "region on the viewer's side (outside, two chambers)")
    start = time.perf_counter()
    blend.Update()
    blended = time.perf_counter() - start
    start = time.perf_counter()
    window.Render()
    window.WaitForCompletion()
    rendered = time.perf_counter() - start
    grab.Modified()
    writer.SetFileName(f"{out}/blend_{k:02d}.png")
    writer.Write()
    print(f"t = {t:.3f}: blend {blended:.3f} s, render {rendered:.3f} s "
          f"({mapper.GetLastNumberOfSlices()} slices)")
    output = blend.GetOutput()
    if t in (0.0, 1.0):
        end = arrays(fields[0 if t == 0.0 else 1])
        check(all(np.array_equal(a, b) for a, b in zip(arrays(output), end)),
              f"t = {t:g}: the blend is the {'first' if t == 0.0 else 'second'} field exactly")
    radius = chamber_radius(output)
    expected = (1 - t) * ball((1, 0, 0)) + t * rounded_box((1, 0, 0))
    check(abs(radius - expected) <= spacing,
          f"t = {t:.3f}: the chamber ends at x = {radius:.3f} along +x, expected "
          f"{expected:.3f} within a spacing ({spacing:.3f})")
    pixels = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars())[:, :3]
    covered = float(np.mean(np.any(np.abs(pixels - background) > 2, axis=1)))
    check(mapper.GetLastNumberOfSlices() > 0 and covered > 0.05,
          f"t = {t:.3f}: the frame shows the shapes ({100 * covered:.0f}% of the pixels)")
print(f"wrote {frames} frames to {out}")
if failures:
    print(f"{len(failures)} checks failed")
    sys.exit(1)
