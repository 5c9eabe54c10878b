"""Pieces of a field equal the whole field bit for bit, as a distributed run (ParaView's
MPI engine, a streaming writer) needs: the linear factorization (both backends, signed)
and the voxelizer computed on three uneven slabs, each compared with the same samples of
the whole grid; and a chamfer transform asked for one piece of two still gets all of its
voxelizer input (every voxel depends on every other): python3 TestPiecesPython.py DATA."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from vtkdistancefields import (vtkChamferVoxelDistance, vtkLinearFactorDistanceField,
                               vtkPolyDataVoxelizer)

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
for label, f in filters:
    f.SetInputConnection(reader.GetOutputPort())
    f.SetResolution(28)
    f.Update()
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
    print(f"{label}: three slabs {'equal the whole grid bit for bit' if same else 'DIFFER'}")
    ok = ok and same

# The chamfer asked for piece 0 of 2: its voxelizer input must still be whole.
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
got = vtk_to_numpy(chamfer.GetOutput().GetPointData().GetArray("ChamferDistance"))
whole_input = list(voxels) == list(voxelizer.GetOutputInformation(0).Get(
    chamfer.GetExecutive().WHOLE_EXTENT()))
same = whole_input and got.shape == expected.shape and np.array_equal(got, expected)
print(f"chamfer asked for piece 0 of 2: voxelizer input {voxels}, "
      f"{'the whole transform' if same else 'WRONG'}")
ok = ok and same
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
