"""The representation "Segmented Distance Volume" on ParaView's distributed server (run by
pvpython, under an X server): pvpython server_representation.py PLUGIN MESH PNG PORT.

A signed field is shown with the representation in one process (the built-in session),
then on the server at localhost:PORT (mpiexec -n R pvserver), whose ranks each hold and
draw their block of the image, composited by ParaView. The two pictures must cover the
same pixels (drawn by one only: under 1% of those drawn by either) in the same colours.
(The plugin is loaded on both sides: a representation has a client-side object too.)"""
import os
import sys

# pvpython run from python3-paraview unpacked elsewhere puts the system's dist-packages
# (python3-vtk9's vtkmodules, another VTK) before PYTHONPATH: take ParaView's.
sys.path = [p for p in sys.path if p.rstrip("/") != "//lib/python3/dist-packages"]

import numpy as np  # noqa: E402
from paraview import simple  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import screenshot  # noqa: E402

plugin, mesh_file, png, port = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])


def render(path):
    simple.LoadPlugin(plugin, remote=True)
    simple.LoadPlugin(plugin, remote=False)
    mesh = simple.XMLPolyDataReader(FileName=[mesh_file])
    field = simple.LinearFactorDistanceField(Input=mesh, Resolution=48,
                                             SignMode="WindingNumber", Backend="CPU")
    view = screenshot.white_view()
    display = simple.Show(field, view)
    display.SetRepresentationType("Segmented Distance Volume")
    simple.ColorBy(display, ("POINTS", "Distance"))
    view.CameraPosition = [0, 0, 40]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    simple.ResetCamera(view)
    rgb = screenshot.picture(view, path)
    simple.Delete(view)
    return rgb


alone = render(png.replace(".png", "-builtin.png"))
simple.Disconnect()
simple.Connect("localhost", port)
served = render(png)
simple.Disconnect()
drawn_alone, drawn_served = ~(alone >= 250).all(axis=2), ~(served >= 250).all(axis=2)
either, one = (drawn_alone | drawn_served).sum(), (drawn_alone ^ drawn_served).sum()
both = drawn_alone & drawn_served
colour = np.abs(alone - served)[both].max() if both.any() else 255
print(f"one process covers {drawn_alone.mean():.2%}, the server {drawn_served.mean():.2%}; "
      f"drawn by one only: {one / max(1, either):.3%}; largest colour difference {colour}")
ok = drawn_alone.mean() > 0.05 and one <= 0.01 * either and colour <= 8
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
