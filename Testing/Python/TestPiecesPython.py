"""Pieces of a field equal the whole field bit for bit, as a distributed run (ParaView's
MPI engine, a streaming writer) needs: the linear factorization (both backends, signed),
the voxelizer and the medial axis (of a mesh on both backends and both signs, and of a
field, whose upstream then computes only the slab and one voxel around it) computed on
three uneven slabs, each compared with the same samples of the whole grid, the slabs'
medial points together the whole grid's; the chamfer transform with a layer limit (three
metrics, both backends, signed; and of masks, whose producer then gives the slab and the
limit's voxels around it) and without one (margins doubling) likewise; and a chamfer
transform of masks without a limit asked for one
piece of two still gets all of its voxelizer input (a voxel may depend on any other) and
gives the same voxels as the whole transform: python3 TestPiecesPython.py DATA."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from vtkdistancefields import (vtkChamferVoxelDistance, vtkLinearFactorDistanceField,
                               vtkMedialAxisFilter, vtkPolyDataVoxelizer)

reader = vtkXMLPolyDataReader()
reader.SetFileName(os.path.join(sys.argv[1], "bunny_small.vtp"))
reader.Update()


def arrays(image):
    data = image.GetPointData()
    return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i)).copy()
            for i in range(data.GetNumberOfArrays())}


def slab_of(whole_arrays, whole_extent, extent):
    """The samples of `extent` out of arrays over `whole_extent` (x fastest)."""
    nx, ny = whole_extent[1] - whole_extent[0] + 1, whole_extent[3] - whole_extent[2] + 1
    out = {}
    for name, values in whole_arrays.items():
        grid = values.reshape((-1, ny, nx) + values.shape[1:])
        out[name] = grid[extent[4]:extent[5] + 1, extent[2]:extent[3] + 1,
                         extent[0]:extent[1] + 1].reshape(values.shape[:0] + (-1,) + values.shape[1:])
    return out


ok = True
filters = []
resolutions = {}  # the filters that need a grid other than 28 samples a side
for backend in ("CPU", "GPU"):
    f = vtkLinearFactorDistanceField()
    f.SetSignModeToPseudoNormal()
    f.ComputeClosestPointOn()
    f.ComputeClosestFeatureOn()
    getattr(f, f"SetBackendTo{backend}")()
    filters.append((f"linear factorization, {backend}", f))
    v = vtkPolyDataVoxelizer()
    getattr(v, f"SetBackendTo{backend}")()
    filters.append((f"voxelizer, {backend}", v))
    for sign in ("PseudoNormal", "WindingNumber"):
        m = vtkMedialAxisFilter()
        getattr(m, f"SetSignModeTo{sign}")()
        m.SetRegionToBoth()
        m.SetSeparationAngle(60)
        getattr(m, f"SetBackendTo{backend}")()
        filters.append((f"medial axis, {sign}, {backend}", m))
    for metric, layers in (("Manhattan", 4), ("Chessboard18", 4), ("Chessboard26", 4),
                           ("Manhattan", 0), ("Chessboard26", 0)):
        c = vtkChamferVoxelDistance()
        getattr(c, f"SetMetricTo{metric}")()
        c.SetMaximumLayers(layers)
        c.SignedOn()
        c.OutputMasksOn()
        getattr(c, f"SetBackendTo{backend}")()
        filters.append((f"chamfer, {metric}, {layers or 'all'} layers, {backend}", c))
        if layers == 0:
            # A grid large enough for margins smaller than it (16 and 32 voxels).
            resolutions[c] = 96
# The chamfer of masks with 3 layers: the voxelizer upstream gives the slab and 3 voxels
# around it.
masks = vtkPolyDataVoxelizer()
masks.SetInputConnection(reader.GetOutputPort())
masks.SetResolution(28)
masks.SetModeToBoth()
masks.SetBackendToCPU()
chamfer_of_masks = vtkChamferVoxelDistance()
chamfer_of_masks.SetInputConnection(masks.GetOutputPort())
chamfer_of_masks.SetMaximumLayers(3)
chamfer_of_masks.SignedOn()
chamfer_of_masks.SetBackendToCPU()
filters.append(("chamfer of masks, 3 layers", chamfer_of_masks))
# The medial axis of a field: the field upstream computes the slab and one voxel around.
field = vtkLinearFactorDistanceField()
field.SetInputConnection(reader.GetOutputPort())
field.SetResolution(28)
field.ComputeClosestPointOn()
field.SetBackendToCPU()
medial_of_field = vtkMedialAxisFilter()
medial_of_field.SetInputConnection(field.GetOutputPort())
medial_of_field.SetRegionToBoth()
medial_of_field.SetBackendToCPU()
filters.append(("medial axis of a field", medial_of_field))


def medial_points(f):
    """The medial points (port 1) as rows x y z angle radius."""
    if f.GetNumberOfOutputPorts() < 2:
        return None
    points = f.GetOutputDataObject(1)
    if points.GetNumberOfPoints() == 0:
        return np.zeros((0, 5))
    data = points.GetPointData()
    return np.column_stack([vtk_to_numpy(points.GetPoints().GetData()),
                            vtk_to_numpy(data.GetArray("SeparationAngle")),
                            vtk_to_numpy(data.GetArray("Radius"))])


for label, f in filters:
    if f not in (medial_of_field, chamfer_of_masks):
        f.SetInputConnection(reader.GetOutputPort())
        f.SetResolution(resolutions.get(f, 28))
    f.Update()
    whole_points = medial_points(f)
    pieces_points = []
    whole = f.GetOutput()
    whole_extent = whole.GetExtent()
    whole_arrays = arrays(whole)
    # Three uneven slabs along y, as ParaView cuts a grid for three ranks (sharing planes).
    y0, y1 = whole_extent[2], whole_extent[3]
    cuts = [y0, y0 + (y1 - y0) // 4, y0 + (y1 - y0) // 2 + 3, y1]
    same = True
    for lo, hi in zip(cuts[:-1], cuts[1:]):
        extent = list(whole_extent)
        extent[2], extent[3] = lo, hi
        f.Modified()  # else the whole grid it holds already covers the slab
        field.Modified()
        masks.Modified()
        f.UpdateExtent(extent)
        piece = f.GetOutput()
        if list(piece.GetExtent()) != extent:
            print(f"{label}: asked for {extent}, got {piece.GetExtent()}")
            same = False
            continue
        expected = slab_of(whole_arrays, whole_extent, extent)
        for name, values in arrays(piece).items():
            if values.tobytes() != expected[name].tobytes():
                print(f"{label}: {name} differs on slab {extent}")
                same = False
        if whole_points is not None:
            pieces_points.append(medial_points(f))
        for consumer, producer, layers in ((medial_of_field, field, 1),
                                           (chamfer_of_masks, masks, 3)):
            if f is consumer:
                grown = list(extent)
                grown[2], grown[3] = max(lo - layers, y0), min(hi + layers, y1)
                if list(producer.GetOutput().GetExtent()) != grown:
                    print(f"{label}: the input upstream covers "
                          f"{producer.GetOutput().GetExtent()}, not {grown}")
                    same = False
    if whole_points is not None:
        # Each medial voxel from the one slab that owns it; in voxel (z, y, x) order.
        together = np.concatenate(pieces_points)
        together = together[np.lexsort((together[:, 0], together[:, 1], together[:, 2]))]
        if together.tobytes() != whole_points.tobytes():
            print(f"{label}: the slabs' {len(together)} medial points differ from the whole "
                  f"grid's {len(whole_points)}")
            same = False
        label += f" ({len(whole_points)} medial points)"
    print(f"{label}: three slabs {'equal the whole grid bit for bit' if same else 'DIFFER'}")
    ok = ok and same

# Without a layer limit, a small block of a fine grid near the surface is propagated over
# margins (16, 32 voxels) far smaller than the grid: it must equal the whole grid's
# voxels, and its layers must show that the margins, not the grid, were propagated. (A
# slab across a padded grid holds voxels far from the surface: the whole grid then.)
for backend in ("CPU", "GPU"):
    c = vtkChamferVoxelDistance()
    c.SetInputConnection(reader.GetOutputPort())
    c.SetResolution(192)
    c.SetMetricToChessboard18()
    c.SignedOn()
    getattr(c, f"SetBackendTo{backend}")()
    c.Update()
    whole_extent = c.GetOutput().GetExtent()
    expected = vtk_to_numpy(c.GetOutput().GetPointData().GetArray("ChamferDistance")).copy()
    all_layers = c.GetLastLayers()
    centre = [(whole_extent[2 * a] + whole_extent[2 * a + 1]) // 2 for a in range(3)]
    for offset in ((0, 0, 0), (12, -10, 6)):
        extent = []
        for a in range(3):
            extent += [centre[a] + offset[a] - 4, centre[a] + offset[a] + 4]
        c.Modified()
        c.UpdateExtent(extent)
        got = vtk_to_numpy(c.GetOutput().GetPointData().GetArray("ChamferDistance"))
        wanted = slab_of({"d": expected}, whole_extent, extent)["d"]
        same = got.tobytes() == wanted.tobytes() and c.GetLastLayers() < all_layers
        print(f"chamfer without a limit, {backend}, block {extent}: {c.GetLastLayers()} layers of "
              f"{all_layers}, {'the whole grid voxels' if same else 'WRONG'}")
        ok = ok and same

# The chamfer without a layer limit asked for piece 0 of 2: its voxelizer input must
# still be whole (any voxel may depend on any other), its piece the whole transform's.
voxelizer = vtkPolyDataVoxelizer()
voxelizer.SetInputConnection(reader.GetOutputPort())
voxelizer.SetResolution(28)
voxelizer.SetBackendToCPU()
chamfer = vtkChamferVoxelDistance()
chamfer.SetInputConnection(voxelizer.GetOutputPort())
chamfer.SetBackendToCPU()
chamfer.Update()
expected = vtk_to_numpy(chamfer.GetOutput().GetPointData().GetArray("ChamferDistance")).copy()
chamfer.Modified()
chamfer.UpdatePiece(0, 2, 0)
voxels = voxelizer.GetOutput().GetExtent()
piece = chamfer.GetOutput()
got = vtk_to_numpy(piece.GetPointData().GetArray("ChamferDistance"))
whole_extent = voxelizer.GetOutputInformation(0).Get(chamfer.GetExecutive().WHOLE_EXTENT())
whole_input = list(voxels) == list(whole_extent)
wanted = slab_of({"d": expected}, whole_extent, piece.GetExtent())["d"]
same = whole_input and got.tobytes() == wanted.tobytes()
print(f"chamfer asked for piece 0 of 2: voxelizer input {voxels}, piece {piece.GetExtent()} "
      f"{'the same voxels of the whole transform' if same else 'WRONG'}")
ok = ok and same
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
