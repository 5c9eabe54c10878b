"""The sparse band in ParaView (run under xvfb-run pvbatch): pvbatch render_sparse.py PLUGIN
MESH PNG.

ParaView's Contour of the Sparse Distance Field's pieces at 0 must be the dense field's
contour: the bricks tile the grid's cells, each cell in one piece, so the triangles are
the same in number and area as those of the contour of Linear Factor Distance Field with
the same band. Its render, red on white, is checked by numbers: the surface over a
plausible share of the pixels, white corners, red (lit) pixels only where it is covered."""
import os
import sys

from paraview import simple
from paraview import servermanager

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import screenshot  # noqa: E402

plugin, mesh_file, png = sys.argv[1:4]
simple.LoadPlugin(plugin, remote=True)
mesh = simple.XMLPolyDataReader(FileName=[mesh_file])
band = 3.0
sparse = simple.SparseDistanceField(Input=mesh, Resolution=40, BandWidth=band, BrickSize=8,
                                    SignMode="PseudoNormal")
dense = simple.LinearFactorDistanceField(Input=mesh, Resolution=40, SignMode="PseudoNormal",
                                         Backend="CPU", Route="SiteScan")
sides = servermanager.Fetch(sparse, idx=1)
h = sides.GetSpacing()[0] / 8
dense.MaximumDistance = band * h


def surface(source):
    """The contour at 0, merged into one mesh, and its triangles' count and area."""
    contour = simple.Contour(Input=source, ContourBy=["POINTS", "Distance"], Isosurfaces=[0.0])
    merged = simple.MergeBlocks(Input=contour)
    integrated = simple.IntegrateVariables(Input=merged)
    area = servermanager.Fetch(integrated).GetCellData().GetArray("Area").GetValue(0)
    return contour, merged.GetDataInformation().GetNumberOfCells(), area


piece_contour, piece_cells, piece_area = surface(simple.OutputPort(sparse, 0))
_, dense_cells, dense_area = surface(dense)
print(f"contour of the pieces: {piece_cells} triangles, area {piece_area:.6f}; "
      f"of the dense band: {dense_cells} triangles, area {dense_area:.6f}")
ok = piece_cells == dense_cells and abs(piece_area - dense_area) <= 1e-9 * dense_area

view = screenshot.white_view()
display = simple.Show(piece_contour, view)
simple.ColorBy(display, None)
display.DiffuseColor = [1, 0, 0]
display.AmbientColor = [1, 0, 0]
view.CameraPosition = [0, 5, 40]
view.CameraFocalPoint = [0, 5, 0]
view.CameraViewUp = [0, 1, 0]
simple.ResetCamera(view)
ok = screenshot.red_on_white(screenshot.picture(view, png), "render") and ok
print("PASS" if ok else "FAIL")
# The view goes before the interpreter ends (ParaView's finalization needs its context).
simple.Delete(view)
del view
sys.exit(0 if ok else 1)
