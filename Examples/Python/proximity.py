"""Proximity by chamfer distance (Martinek et al. (VMV 2011) §6.3): the chamfer field of one mesh (the
cow), and a second mesh (a bunny next to it) whose vertices are coloured by the field's
value there, in spacings: red where the bunny comes close to the cow.

usage: /usr/bin/python3 proximity.py DATA_DIR OUT.png   (needs an X display: xvfb-run)
"""
import sys
import time

from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersCore import vtkProbeFilter
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkTextActor, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingFreeType  # noqa: F401 (the legend's text)
from vtkmodules.vtkCommonCore import vtkLookupTable
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)

from vtkdistancefields import vtkChamferVoxelDistance

data, out = sys.argv[1], sys.argv[2]


def read(name):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(f"{data}/{name}.vtp")
    reader.Update()
    return reader.GetOutput()


cow = read("cow")
bunny = read("bunny_small")
# Scale the bunny to about half the cow and put it against the cow's flank.
bb, cb = bunny.GetBounds(), cow.GetBounds()
scale = 0.5 * (cb[1] - cb[0]) / (bb[1] - bb[0])
move = vtkTransform()
move.Translate(0.5 * (cb[0] + cb[1]), cb[3] - 0.12 * (cb[3] - cb[2]), 0.5 * (cb[4] + cb[5]))
move.Scale(scale, scale, scale)
move.Translate(-0.5 * (bb[0] + bb[1]), -bb[2], -0.5 * (bb[4] + bb[5]))
placed = vtkTransformPolyDataFilter()
placed.SetInputData(bunny)
placed.SetTransform(move)
placed.Update()

# The cow's chamfer field on a grid that also covers the bunny.
chamfer = vtkChamferVoxelDistance()
chamfer.SetInputData(cow)
chamfer.SetMetricToChessboard18()
chamfer.SetResolution(128)
chamfer.SetPadding(0.6)
chamfer.Update()
print(f"chamfer field {chamfer.GetOutput().GetDimensions()}: {chamfer.GetLastTime():.4f} s "
      f"({chamfer.GetLastBackend()}, {chamfer.GetLastLayers()} layers)")

# The field at the bunny's vertices.
start = time.perf_counter()
probe = vtkProbeFilter()
probe.SetInputConnection(placed.GetOutputPort())
probe.SetSourceConnection(chamfer.GetOutputPort())
probe.Update()
print(f"probe of {placed.GetOutput().GetNumberOfPoints()} vertices: "
      f"{time.perf_counter() - start:.4f} s")
near = probe.GetOutput().GetPointData().GetArray("ChamferDistance").GetRange()
print(f"bunny vertices lie {near[0]:.0f} to {near[1]:.0f} layers from the cow")

lut = vtkLookupTable()
lut.SetHueRange(0.0, 0.66)  # red (close) to blue (far)
lut.SetTableRange(near[0], near[0] + 12)
lut.Build()
renderer = vtkRenderer()
renderer.SetBackground(1, 1, 1)
for poly, colour in ((cow, False), (probe.GetOutputPort(), True)):
    mapper = vtkPolyDataMapper()
    if colour:
        mapper.SetInputConnection(poly)
        mapper.SetScalarModeToUsePointFieldData()
        mapper.SelectColorArray("ChamferDistance")
        mapper.SetLookupTable(lut)
        mapper.UseLookupTableScalarRangeOn()
        mapper.ScalarVisibilityOn()
    else:
        mapper.SetInputData(poly)
        mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    if not colour:
        actor.GetProperty().SetColor(0.85, 0.85, 0.8)
    renderer.AddActor(actor)
# The legend: the colour bar of the bunny's colours, and what the picture shows.
bar = vtkScalarBarActor()
bar.SetLookupTable(lut)
bar.SetTitle("layers")
bar.SetLabelFormat("%.0f")
bar.SetNumberOfLabels(4)
bar.SetPosition(0.86, 0.1)
bar.SetWidth(0.12)
bar.SetHeight(0.8)
for text in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
    text.SetColor(0, 0, 0)
    text.ShadowOff()
renderer.AddActor2D(bar)
caption = vtkTextActor()
caption.SetInput("grey: the cow; the bunny's vertices coloured by the cow's chamfer\n"
                 "distance there, in voxel layers (18-neighbour chessboard metric): red is closest")
caption.GetTextProperty().SetFontSize(14)
caption.GetTextProperty().SetColor(0, 0, 0)
caption.SetDisplayPosition(10, 10)
renderer.AddActor2D(caption)
window = vtkRenderWindow()
window.SetOffScreenRendering(1)
window.SetSize(640, 480)
window.AddRenderer(renderer)
renderer.ResetCamera()
camera = renderer.GetActiveCamera()
camera.Elevation(25)
camera.Azimuth(-30)
renderer.ResetCamera()
window.Render()
grab = vtkWindowToImageFilter()
grab.SetInput(window)
writer = vtkPNGWriter()
writer.SetFileName(out)
writer.SetInputConnection(grab.GetOutputPort())
writer.Write()
print(f"wrote {out}")
