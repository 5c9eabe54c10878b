"""The volume mapper in ParaView, as the representation "Segmented Distance Volume" of
image data (run under xvfb-run pvbatch): pvbatch render_representation.py PLUGIN MESH PNG.

The mesh's signed field is shown in a render view with that representation (Mode
Surface: the field's zero set, opaque); then the mesh itself as ParaView's "Surface" in
the same view and camera. The two pictures must cover the same pixels (the mapper's
surface lies within a voxel of the mesh: at this size, the pixels where exactly one of
them is drawn stay below 4% of those where either is), with white corners; the
representation's mapper must be vtkSegmentedDistanceVolumeMapper, SurfaceOpacity 0.5 must
change the picture (the far side shows through) but not what it covers, and Mode
Composite must draw too (some pixels, a different picture)."""
import os
import sys

import numpy as np
from paraview import simple

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import screenshot  # noqa: E402

plugin, mesh_file, png = sys.argv[1:4]
simple.LoadPlugin(plugin, remote=True)
mesh = simple.XMLPolyDataReader(FileName=[mesh_file])
field = simple.LinearFactorDistanceField(Input=mesh, Resolution=48, SignMode="WindingNumber",
                                         ComputeClosestPoint=1, Backend="CPU")
view = screenshot.white_view()


def picture(path):
    return screenshot.picture(view, path)


ok = True
display = simple.Show(field, view)
types = display.Representation.Available
if "Segmented Distance Volume" not in types:
    print(f"FAIL: the representation is not offered for image data: {types}")
    sys.exit(1)
display.SetRepresentationType("Segmented Distance Volume")
simple.ColorBy(display, ("POINTS", "Distance"))
display.Mode = "Surface"
view.CameraPosition = [0, 0, 40]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
simple.ResetCamera(view)
camera = view.GetActiveCamera()
state = (camera.GetPosition(), camera.GetFocalPoint(), camera.GetViewUp(), camera.GetViewAngle())
volume = picture(png)
drawn_volume = ~(volume >= 250).all(axis=2)

# The mapper behind the representation, and its properties reaching it: half-opaque
# surfaces (blended back to front, the far side showing through) change the picture
# but not what it covers; then opaque again.
mapper = display.GetClientSideObject().GetActiveRepresentation().GetActor().GetMapper()
print(f"the representation's mapper: {mapper.GetClassName()}")
ok = ok and mapper.GetClassName() == "vtkSegmentedDistanceVolumeMapper"
display.SurfaceOpacity = 0.5
display.FieldInterpolation = "Linear"
half = picture(png.replace(".png", "-half.png"))
change = np.abs(half - volume)[drawn_volume].mean()
drawn_half = ~(half >= 250).all(axis=2)
moved = (drawn_half ^ drawn_volume).sum() / max(1, drawn_volume.sum())
print(f"SurfaceOpacity 0.5: the drawn pixels change by {change:.1f} levels on average; "
      f"coverage differs on {moved:.2%} of them")
ok = ok and change > 5 and moved < 0.02
display.SurfaceOpacity = 1.0
display.FieldInterpolation = "RegionAware"

# The mesh as ParaView's own surface, same view and camera.
simple.Hide(field, view)
surface = simple.Show(mesh, view)
surface.SetRepresentationType("Surface")
camera.SetPosition(state[0])
camera.SetFocalPoint(state[1])
camera.SetViewUp(state[2])
camera.SetViewAngle(state[3])
reference = picture(png.replace(".png", "-mesh.png"))
drawn_mesh = ~(reference >= 250).all(axis=2)
either, one = (drawn_volume | drawn_mesh).sum(), (drawn_volume ^ drawn_mesh).sum()
corners = all(not drawn_volume[y, x] for y in (0, -1) for x in (0, -1))
print(f"Segmented Distance Volume covers {drawn_volume.mean():.1%} of the picture, the mesh "
      f"{drawn_mesh.mean():.1%}; drawn by one only: {one / max(1, either):.2%} of {either} "
      f"pixels; corners white: {corners}")
ok = ok and 0.05 <= drawn_volume.mean() <= 0.8 and one <= 0.04 * either and corners

# Composite: the pre-integrated volume of the coloured array draws something else.
simple.Hide(mesh, view)
simple.Show(field, view)
display.Mode = "Composite"
composite = picture(png.replace(".png", "-composite.png"))
drawn = ~(composite >= 250).all(axis=2)
different = np.abs(composite - volume).max() > 10
print(f"Composite: {drawn.mean():.1%} of the picture drawn, "
      f"{'a different picture' if different else 'THE SAME PICTURE'}")
ok = ok and drawn.mean() > 0.05 and different
print("PASS" if ok else "FAIL")
# The view goes before the interpreter ends (see render_then_gpu.py).
simple.Delete(view)
del view
sys.exit(0 if ok else 1)
