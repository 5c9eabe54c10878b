"""Two deforming bunnies moving into and out of contact (vtkDistanceFieldProximity, after
Sud et al., ACM I3D 2006, section 6.2): A waves in place, B (turned half a turn about the vertical, breathing)
swings through it twice in 100 frames. One filter runs every frame (each model keeps its
topology between frames). Writes OUT_DIR/deforming_plot.png (separation and both maximum
penetrations per frame) and OUT_DIR/deforming_frame_NNN.png for a few frames (both models
coloured by DistanceToOther: blue inside the other, white at contact, red outside), and
prints the per-frame time.

usage: /usr/bin/python3 deforming_bunnies.py DATA_DIR OUT_DIR [RESOLUTION [FRAMES]]
(needs an X display for the pictures: xvfb-run)
"""
import math
import os
import statistics
import sys

from vtkmodules.vtkChartsCore import vtkChart, vtkChartXY
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkLookupTable, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData, vtkTable
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkTextActor,
                                         vtkWindowToImageFilter)
from vtkmodules.vtkViewsContext2D import vtkContextView
import vtkmodules.vtkRenderingContextOpenGL2  # noqa: F401 (the chart's drawing)
import vtkmodules.vtkRenderingFreeType  # noqa: F401 (text)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)

from vtkdistancefields import vtkDistanceFieldProximity

data, out = sys.argv[1], sys.argv[2]
resolution = int(sys.argv[3]) if len(sys.argv) > 3 else 128
frames = int(sys.argv[4]) if len(sys.argv) > 4 else 100
os.makedirs(out, exist_ok=True)

# bunny_small (3,674 triangles) in a unit box centred at the origin.
reader = vtkXMLPolyDataReader()
reader.SetFileName(f"{data}/bunny_small.vtp")
triangles = vtkTriangleFilter()
triangles.SetInputConnection(reader.GetOutputPort())
triangles.Update()
rest = triangles.GetOutput()
b = rest.GetBounds()
size = max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
centre = [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])]
unit = [[(rest.GetPoint(i)[k] - centre[k]) / size for k in range(3)]
        for i in range(rest.GetNumberOfPoints())]


def pose(frame):
    """Frame f: A waves; B swings along x from 1.2 (apart) to -0.3 (deep in A)."""
    swing = 0.45 + 0.75 * math.cos(2 * math.pi * frame / 50.0)
    breath = 1 + 0.1 * math.sin(0.3 * frame)
    pa, pb = vtkPoints(), vtkPoints()
    pa.SetDataTypeToDouble()
    pb.SetDataTypeToDouble()
    for x, y, z in unit:
        pa.InsertNextPoint(x + 0.04 * math.sin(6 * y + 0.2 * frame), y, z)
        pb.InsertNextPoint(-x * breath + swing, y * breath + 0.05, -z * breath)
    a, b = vtkPolyData(), vtkPolyData()
    a.ShallowCopy(rest)
    a.SetPoints(pa)
    b.ShallowCopy(rest)
    b.SetPoints(pb)
    return a, b


def picture(proximity, frame, path):
    lut = vtkLookupTable()
    lut.SetTableRange(-0.08, 0.08)
    lut.SetNumberOfTableValues(256)
    for i in range(256):
        t = i / 255.0
        r, g, bl = (2 * t if t < 0.5 else 1.0), 1 - abs(2 * t - 1), (1.0 if t < 0.5 else 2 - 2 * t)
        lut.SetTableValue(i, 0.15 + 0.85 * r, 0.15 + 0.85 * g, 0.15 + 0.85 * bl, 1)
    lut.Build()
    renderer = vtkRenderer()
    renderer.SetBackground(1, 1, 1)
    for port, opacity in ((2, 1.0), (3, 0.45)):
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(proximity.GetOutput(port))
        mapper.SetScalarModeToUsePointFieldData()
        mapper.SelectColorArray("DistanceToOther")
        mapper.SetLookupTable(lut)
        mapper.UseLookupTableScalarRangeOn()
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetOpacity(opacity)
        renderer.AddActor(actor)
    text = vtkTextActor()
    text.SetInput(f"frame {frame}: " + (
        f"colliding, penetration {proximity.GetLastPenetrationAB():.3f} / "
        f"{proximity.GetLastPenetrationBA():.3f}" if proximity.GetLastColliding()
        else f"apart, separation {proximity.GetLastSeparationDistance():.4f}"))
    text.GetTextProperty().SetColor(0, 0, 0)
    text.GetTextProperty().SetFontSize(16)
    text.SetPosition(10, 10)
    renderer.AddActor2D(text)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(480, 360)
    window.AddRenderer(renderer)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(0.9, 0.9, 2.4)
    camera.SetFocalPoint(0.45, 0, 0)
    camera.SetViewUp(0, 1, 0)
    renderer.ResetCamera()
    window.Render()
    save(window, path)


def save(window, path):
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtkPNGWriter()
    writer.SetInputConnection(grab.GetOutputPort())
    writer.SetFileName(path)
    writer.Write()
    print(f"wrote {path}")


proximity = vtkDistanceFieldProximity()
proximity.SetResolution(resolution)
shown = {0, 12, 20, 25}
rows, times = [], []
for frame in range(frames):
    a, b = pose(frame)
    proximity.SetInputData(0, a)
    proximity.SetInputData(1, b)
    proximity.Update()
    if proximity.GetErrorCode():
        sys.exit(f"frame {frame}: the filter failed")
    times.append(proximity.GetLastSeconds())
    rows.append((frame, proximity.GetLastSeparationDistance(), proximity.GetLastPenetrationAB(),
                 proximity.GetLastPenetrationBA()))
    if frame in shown:
        picture(proximity, frame, os.path.join(out, f"deforming_frame_{frame:03d}.png"))

print(f"{frames} frames at resolution {resolution}: per frame mean "
      f"{1e3 * statistics.mean(times):.1f} ms, median {1e3 * statistics.median(times):.1f} ms, "
      f"max {1e3 * max(times):.1f} ms (first frame {1e3 * times[0]:.1f} ms, topology built); "
      f"colliding in {sum(1 for r in rows if r[1] == 0)} frames")

# The plot: one line per answer.
table = vtkTable()
for name in ("frame", "separation", "penetration A in B", "penetration B in A"):
    column = vtkFloatArray()
    column.SetName(name)
    table.AddColumn(column)
table.SetNumberOfRows(len(rows))
for i, row in enumerate(rows):
    for k, value in enumerate(row):
        table.SetValue(i, k, value)
view = vtkContextView()
view.GetRenderer().SetBackground(1, 1, 1)
view.GetRenderWindow().SetOffScreenRendering(1)
view.GetRenderWindow().SetSize(640, 360)
chart = vtkChartXY()
chart.SetShowLegend(True)
chart.GetAxis(1).SetTitle("frame")  # 0: left, 1: bottom
chart.GetAxis(0).SetTitle("distance (unit box)")
view.GetScene().AddItem(chart)
for column, colour in ((1, (40, 90, 200)), (2, (200, 40, 40)), (3, (230, 140, 20))):
    line = chart.AddPlot(vtkChart.LINE)
    line.SetInputData(table, 0, column)
    line.SetColor(*colour, 255)
    line.SetWidth(2.0)
view.GetRenderWindow().Render()
save(view.GetRenderWindow(), os.path.join(out, "deforming_plot.png"))

# Its own checks (CTest runs it small): apart first, in contact later, pictures written.
touching = [r for r in rows if r[1] == 0]
if frames >= 12 and not (rows[0][1] > 0 and touching and max(r[2] for r in touching) > 0):
    sys.exit("FAIL: the bunnies should start apart and then collide")
for frame in sorted(f for f in shown if f < frames):
    if not os.path.exists(os.path.join(out, f"deforming_frame_{frame:03d}.png")):
        sys.exit(f"FAIL: frame {frame} was not drawn")
