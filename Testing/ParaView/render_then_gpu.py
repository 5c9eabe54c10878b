"""A render through ParaView with the plugin loaded, checked by numbers, then a GPU filter
run after it (run under xvfb-run pvbatch): pvbatch render_then_gpu.py PLUGIN MESH PNG.

The field's zero contour is drawn in red on white; the screenshot must have the red
surface over a plausible share of the pixels, white corners, and red (lit) pixels only
where it is covered. Then the first GPU filter of the process runs while ParaView's GLX
context is current: it must get its own EGL context (not fall back to OSMesa, which it did
when creating the context did not release the caller's) and leave ParaView's context
working: a second render gives the same picture."""
import os
import sys

import numpy as np
from paraview import simple

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import screenshot  # noqa: E402

plugin, mesh_file, png = sys.argv[1:4]
simple.LoadPlugin(plugin, remote=True)
mesh = simple.XMLPolyDataReader(FileName=[mesh_file])
field = simple.LinearFactorDistanceField(Input=mesh, Resolution=40, SignMode="PseudoNormal",
                                         Backend="CPU")
contour = simple.Contour(Input=field, ContourBy=["POINTS", "Distance"], Isosurfaces=[0.0])
view = screenshot.white_view()
display = simple.Show(contour, view)
simple.ColorBy(display, None)
display.DiffuseColor = [1, 0, 0]
display.AmbientColor = [1, 0, 0]
view.CameraPosition = [0, 5, 40]
view.CameraFocalPoint = [0, 5, 0]
view.CameraViewUp = [0, 1, 0]
simple.ResetCamera(view)


def picture(path):
    return screenshot.picture(view, path)


check = screenshot.red_on_white


first = picture(png)
ok = check(first, "render")
print(f"contour: {contour.GetDataInformation().GetNumberOfCells()} triangles")

gpu = simple.LinearFactorDistanceField(Input=mesh, Resolution=16, SignMode="PseudoNormal",
                                       Backend="GPU")
gpu.UpdatePipeline()
gpu.UpdatePropertyInformation()
platform = gpu.GetProperty("LastPlatform").GetElement(0)
renderer = gpu.GetProperty("LastRenderer").GetElement(0)
points = gpu.GetDataInformation().GetNumberOfPoints()
print(f"GPU filter after the render: {points} points on {renderer} through {platform}")
ok = ok and points > 0 and platform.startswith("EGL")

second = picture(png.replace(".png", "-again.png"))
same = np.abs(second - first).max() <= 2
print(f"render after the GPU filter: {'the same picture' if same else 'differs'}")
ok = ok and check(second, "render again") and same
print("PASS" if ok else "FAIL")
# The view goes before the interpreter ends: exiting with a view alive makes ParaView's
# finalization use a GLX context that is gone (an X error, exit status 1).
simple.Delete(view)
del view
sys.exit(0 if ok else 1)
