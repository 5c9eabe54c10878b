"""vtkOpenVDBLevelSetWriter read back by Debian's python3-openvdb (pyopenvdb): the sparse
band of a closed mesh written as a .vdb is a FloatGrid of class level set, named
"surface", whose background is the band's half-width, whose transform maps voxel (i, j, k)
onto the grid's sample (i, j, k), whose active voxels are exactly the band's samples with
their distances bit for bit, and whose every other voxel is inactive at minus the
background inside and plus it outside, by the sides; the closest points ride in a
Vec3SGrid beside it. An anisotropic grid and pieces that are not the sparse filter's are
errors, and write nothing. With vtkdf's path as an argument, vtkdf linfac --band K --vdb
OUT.vdb writes the same level set."""
import os
import subprocess
import sys
import tempfile

import numpy as np
import pyopenvdb as vdb
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPartitionedDataSet
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from vtkdistancefields import vtkOpenVDBLevelSetWriter, vtkSparseDistanceField

failures = []


def check(condition, what):
    print(("ok: " if condition else "FAIL: ") + what)
    if not condition:
        failures.append(what)


data = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Data")
mesh = vtkXMLPolyDataReader()
mesh.SetFileName(os.path.join(data, "bunny_small.vtp"))
band, brick = 3.0, 8
sparse = vtkSparseDistanceField()
sparse.SetInputConnection(mesh.GetOutputPort())
sparse.SetResolution(48)
sparse.SetBandWidth(band)
sparse.SetBrickSize(brick)
sparse.SetSignModeToPseudoNormal()
sparse.SetComputeClosestPoint(True)
sparse.Update()
pieces, sides = sparse.GetOutputDataObject(0), sparse.GetOutputDataObject(1)
first = pieces.GetPartition(0)
h, origin = first.GetSpacing()[0], np.array(first.GetOrigin())
background = np.float32(band * h)

# The field the file must hold: every sample of the grid (the pieces where they are, the
# sides elsewhere), and which samples are the band's.
nb = [n - 1 for n in sides.GetDimensions()]
dims = [b * brick + 1 for b in nb]
value = np.full(dims, np.nan, np.float32)
active = np.zeros(dims, bool)
closest = np.zeros(dims + [3], np.float32)
side = vtk_to_numpy(sides.GetCellData().GetArray("Side")).reshape(nb[::-1])
for bk in range(nb[2]):
    for bj in range(nb[1]):
        for bi in range(nb[0]):
            if side[bk, bj, bi] != 0:
                block = np.s_[bi * brick:(bi + 1) * brick + 1, bj * brick:(bj + 1) * brick + 1,
                              bk * brick:(bk + 1) * brick + 1]
                value[block] = side[bk, bj, bi] * background
for p in range(pieces.GetNumberOfPartitions()):
    piece = pieces.GetPartition(p)
    e = piece.GetExtent()
    shape = (e[5] - e[4] + 1, e[3] - e[2] + 1, e[1] - e[0] + 1)
    block = np.s_[e[0]:e[1] + 1, e[2]:e[3] + 1, e[4]:e[5] + 1]
    d = vtk_to_numpy(piece.GetPointData().GetArray("Distance")).reshape(shape).transpose(2, 1, 0)
    hidden = vtk_to_numpy(piece.GetPointData().GetArray("vtkGhostType")).reshape(shape).transpose(2, 1, 0)
    points = vtk_to_numpy(piece.GetPointData().GetArray("ClosestPoint")).reshape(shape + (3,))
    value[block] = np.where(hidden != 0, np.sign(d) * background, d)
    active[block] = hidden == 0
    closest[block] = points.transpose(2, 1, 0, 3)
known = ~np.isnan(value)

with tempfile.TemporaryDirectory() as folder:
    path = os.path.join(folder, "band.vdb")
    writer = vtkOpenVDBLevelSetWriter()
    writer.SetInputConnection(sparse.GetOutputPort(0))
    writer.SetSidesConnection(sparse.GetOutputPort(1))
    writer.SetFileName(path)
    writer.Write()
    check(writer.GetErrorCode() == 0 and os.path.exists(path),
          f"written: {writer.GetLastActiveVoxels()} active voxels, {writer.GetLastLeafNodes()} leaves")
    names = [g.name for g in vdb.readAllGridMetadata(path)]
    check(sorted(names) == ["closest_point", "surface"], f"grids {names}")
    grid = vdb.read(path, "surface")
    check(grid.gridClass == vdb.GridClass.LEVEL_SET, f"class {grid.gridClass}")
    check(np.float32(grid.background) == background, f"background {grid.background} = {band:g} h")
    check(np.allclose(grid.transform.voxelSize(), (h, h, h), rtol=0, atol=0),
          f"voxel size {grid.transform.voxelSize()}")
    check(np.allclose(grid.transform.indexToWorld((0, 0, 0)), origin, rtol=1e-12, atol=0),
          f"voxel (0, 0, 0) at {grid.transform.indexToWorld((0, 0, 0))}, the grid's origin {origin}")
    check(grid.activeVoxelCount() == np.count_nonzero(active),
          f"{grid.activeVoxelCount()} active voxels, {np.count_nonzero(active)} band samples")
    dense = np.zeros(dims, np.float32)
    grid.copyToArray(dense, ijk=(0, 0, 0))
    on = np.zeros(dims, bool)
    for item in grid.citerOnValues():
        lo, hi = item["min"], item["max"]
        on[lo[0]:hi[0] + 1, lo[1]:hi[1] + 1, lo[2]:hi[2] + 1] = True
    check(np.array_equal(on, active), "the active voxels are the band's samples")
    check(np.array_equal(dense[known].view(np.uint32), value[known].view(np.uint32)),
          f"every voxel's value, bit for bit ({np.count_nonzero(known)} voxels; "
          f"{np.count_nonzero(dense < 0)} negative)")
    points = vdb.read(path, "closest_point")
    copy = np.zeros(dims + [3], np.float32)
    points.copyToArray(copy, ijk=(0, 0, 0))
    check(points.activeVoxelCount() == grid.activeVoxelCount() and
          np.array_equal(copy[active].view(np.uint32), closest[active].view(np.uint32)),
          "the closest points of the band's samples")

    # vtkdf linfac MESH --signed --band K --vdb OUT.vdb (no -o): the same level set.
    if len(sys.argv) > 1:
        target = os.path.join(folder, "vtkdf.vdb")
        subprocess.run([sys.argv[1], "linfac", os.path.join(data, "bunny_small.vtp"),
                        "--signed", "--band", str(band), "--brick-size", str(brick),
                        "--resolution", "48", "--vdb", target], check=True)
        theirs = vdb.read(target, "surface")
        copy = np.zeros(dims, np.float32)
        theirs.copyToArray(copy, ijk=(0, 0, 0))
        check(theirs.activeVoxelCount() == grid.activeVoxelCount() and
              np.array_equal(copy.view(np.uint32), dense.view(np.uint32)),
              "vtkdf linfac --band --vdb: the same level set")

    # Errors: an anisotropic grid, and pieces without the sparse filter's field data.
    anisotropic = vtkSparseDistanceField()
    anisotropic.SetInputConnection(mesh.GetOutputPort())
    anisotropic.SetExplicitGrid(True)
    anisotropic.SetGridOrigin(-6, -1, -5)
    anisotropic.SetGridSpacing(0.3, 0.3, 0.4)
    anisotropic.SetGridDimensions(40, 40, 30)
    for name, source in (("anisotropic", anisotropic.GetOutputPort(0)), ("foreign", None)):
        bad = vtkOpenVDBLevelSetWriter()
        bad.GlobalWarningDisplayOff()
        if source is None:
            bad.SetInputData(vtkPartitionedDataSet())
        else:
            bad.SetInputConnection(source)
        target = os.path.join(folder, name + ".vdb")
        bad.SetFileName(target)
        bad.Write()
        check(bad.GetErrorCode() != 0 and not os.path.exists(target), f"{name}: refused")

sys.exit(1 if failures else 0)
