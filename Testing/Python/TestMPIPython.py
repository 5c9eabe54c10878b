"""A distributed run without ParaView: mpiexec -n R /usr/bin/python3 TestMPIPython.py DATA,
with VTK's own vtkMPIController as the global controller. Each rank holds a part of the
mesh (a range of its cells, with global point and cell ids: their original indices) and
asks the linear factorization for its piece of the grid; the filter gathers the parts.
Every rank's slab must equal, bit for bit, the same samples of the field of the whole mesh
without ids (which every rank also computes), and the slabs must cover the grid. The
medial axis of the parts likewise: each rank's slab equal to one process's, and rank 0's
medial points (gathered from the ranks) all of one process's; on a grid of 2 samples a
side (ranks with an empty piece) too; of a field computed upstream, which then computes
only the slab and one voxel around it. The segmented field of the parts: each rank computes
its slab and one sample around it (LastComputedExtent), the ranks add up their region
evidence, and each slab equals one process's bit for bit, on the 2-sample grid too; every
rank asking for one sub-extent gets it cut from the whole grid; the contour of the
distributed field (rank 0 gathers it) equals one process's; the blend of two distributed
fields computes slabs equal to one process's."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_ID_TYPE
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkParallelCore import vtkDummyController, vtkMultiProcessController
from mpi_support import read, start_controller

from vtkdistancefields import (vtkDistanceFieldBlend, vtkLinearFactorDistanceField,
                               vtkMedialAxisFilter, vtkSegmentedDistanceContour,
                               vtkSegmentedDistanceField)

controller, rank, ranks = start_controller()
whole = read(sys.argv[1], "bunny_small.vtp")

# This rank's part: a range of cells, with every point (unused ones are ignored), and
# global ids = original indices.
cells = whole.GetNumberOfCells()
first, last = rank * cells // ranks, (rank + 1) * cells // ranks
part = vtkPolyData()
part.SetPoints(whole.GetPoints())
polys = whole.GetPolys()
offsets = vtk_to_numpy(polys.GetOffsetsArray())
connectivity = vtk_to_numpy(polys.GetConnectivityArray())
mine = vtkCellArray()
mine.SetData(numpy_to_vtk(offsets[first:last + 1] - offsets[first], deep=True,
                          array_type=VTK_ID_TYPE),
             numpy_to_vtk(connectivity[offsets[first]:offsets[last]], deep=True,
                          array_type=VTK_ID_TYPE))
part.SetPolys(mine)
point_ids = numpy_to_vtk(np.arange(whole.GetNumberOfPoints(), dtype=np.int64), deep=True,
                         array_type=VTK_ID_TYPE)
point_ids.SetName("GlobalPointIds")
cell_ids = numpy_to_vtk(np.arange(first, last, dtype=np.int64), deep=True,
                        array_type=VTK_ID_TYPE)
cell_ids.SetName("GlobalCellIds")
part.GetPointData().SetGlobalIds(point_ids)
part.GetCellData().SetGlobalIds(cell_ids)


def field(mesh):
    f = vtkLinearFactorDistanceField()
    f.SetInputData(mesh)
    f.SetResolution(24)
    f.SetSignModeToWindingNumber()
    f.ComputeClosestPointOn()
    f.SetBackendToCPU()
    return f


reference = field(whole)  # every rank holds the same mesh: nothing is gathered
reference.Update()
distributed = field(part)
distributed.UpdatePiece(rank, ranks, 0)
slab = distributed.GetOutput()
extent = slab.GetExtent()
full = reference.GetOutput()
wx, wy = full.GetDimensions()[0], full.GetDimensions()[1]
ok = True
for name in ("Distance", "ClosestCellId", "ClosestPoint"):
    values = vtk_to_numpy(full.GetPointData().GetArray(name))
    grid = values.reshape((-1, wy, wx) + values.shape[1:])
    expected = grid[extent[4]:extent[5] + 1, extent[2]:extent[3] + 1, extent[0]:extent[1] + 1]
    got = vtk_to_numpy(slab.GetPointData().GetArray(name))
    same = got.tobytes() == np.ascontiguousarray(expected).reshape(got.shape).tobytes()
    ok = ok and same
print(f"rank {rank} of {ranks}: cells {first}..{last - 1}, extent {extent}: "
      f"{'equal to the whole mesh field bit for bit' if ok else 'DIFFERS'}", flush=True)
# Each rank computed a slab, not the whole grid.
is_slab = ranks == 1 or tuple(extent) != tuple(full.GetExtent())

# The medial axis of the parts: each rank its slab (from the field on it and one voxel
# around), rank 0 every medial point, both as the whole mesh's in one process.
def medial(mesh):
    m = vtkMedialAxisFilter()
    m.SetInputData(mesh)
    m.SetResolution(24)
    m.SetRegionToBoth()
    m.SetBackendToCPU()
    return m


distributed = medial(part)
distributed.UpdatePiece(rank, ranks, 0)
slab = distributed.GetOutput()
medial_extent = slab.GetExtent()
vtkMultiProcessController.SetGlobalController(vtkDummyController())
alone = medial(whole)
alone.Update()
vtkMultiProcessController.SetGlobalController(controller)
full = alone.GetOutput()
medial_ok = True
for name in ("Medial", "SeparationAngle", "Radius"):
    values = vtk_to_numpy(full.GetPointData().GetArray(name))
    grid = values.reshape((-1, wy, wx))
    e = medial_extent
    expected = grid[e[4]:e[5] + 1, e[2]:e[3] + 1, e[0]:e[1] + 1]
    got = vtk_to_numpy(slab.GetPointData().GetArray(name))
    medial_ok = medial_ok and got.tobytes() == np.ascontiguousarray(expected).reshape(-1).tobytes()
points = distributed.GetOutputDataObject(1)
every = alone.GetOutputDataObject(1)
if rank == 0:
    medial_ok = medial_ok and points.GetNumberOfPoints() == every.GetNumberOfPoints() > 0
    for get in (lambda d: d.GetPoints().GetData(),
                lambda d: d.GetPointData().GetArray("SeparationAngle"),
                lambda d: d.GetPointData().GetArray("Radius")):
        medial_ok = medial_ok and vtk_to_numpy(get(points)).tobytes() == \
            vtk_to_numpy(get(every)).tobytes()
else:
    medial_ok = medial_ok and points.GetNumberOfPoints() == 0
medial_slab = ranks == 1 or tuple(medial_extent) != tuple(full.GetExtent())

# The medial axis of a field computed upstream: the field is asked for this rank's slab
# and one voxel around it (as one ghost level), not the whole grid.
source = field(whole)
of_field = vtkMedialAxisFilter()
of_field.SetInputConnection(source.GetOutputPort())
of_field.SetRegionToBoth()
of_field.SetBackendToCPU()
of_field.UpdatePiece(rank, ranks, 0)
fe, me = source.GetOutput().GetExtent(), of_field.GetOutput().GetExtent()
grown = tuple(max(me[i] - 1, 0) if i % 2 == 0 else min(me[i] + 1, full.GetExtent()[i])
              for i in range(6))
vtkMultiProcessController.SetGlobalController(vtkDummyController())
alone_source = field(whole)  # held: a pipeline's upstream must outlive its Python name
alone_field = vtkMedialAxisFilter()
alone_field.SetInputConnection(alone_source.GetOutputPort())
alone_field.SetRegionToBoth()
alone_field.SetBackendToCPU()
alone_field.Update()
vtkMultiProcessController.SetGlobalController(controller)
of_field_ok = ranks == 1 or tuple(fe) == grown
values = vtk_to_numpy(alone_field.GetOutput().GetPointData().GetArray("Medial")).reshape((-1, wy, wx))
expected = np.ascontiguousarray(values[me[4]:me[5] + 1, me[2]:me[3] + 1, me[0]:me[1] + 1])
got = vtk_to_numpy(of_field.GetOutput().GetPointData().GetArray("Medial"))
of_field_ok = of_field_ok and got.tobytes() == expected.reshape(-1).tobytes()
medial_ok = medial_ok and of_field_ok
print(f"rank {rank} of {ranks}: medial axis of a field, slab {me}, the field computed on {fe} "
      f"(expected {grown}): {'equal to one process bit for bit' if of_field_ok else 'DIFFERS'}",
      flush=True)

# More ranks than the grid has slabs (2 samples a side): a rank with an empty piece still
# takes part in the gather, and rank 0 answers as one process.
tiny = medial(part)
tiny.SetResolution(2)
tiny.UpdatePiece(rank, ranks, 0)
vtkMultiProcessController.SetGlobalController(vtkDummyController())
tiny_alone = medial(whole)
tiny_alone.SetResolution(2)
tiny_alone.Update()
vtkMultiProcessController.SetGlobalController(controller)
tiny_points = tiny.GetOutputDataObject(1).GetNumberOfPoints()
expected_points = tiny_alone.GetOutputDataObject(1).GetNumberOfPoints() if rank == 0 else 0
medial_ok = medial_ok and tiny.GetErrorCode() == 0 and tiny_points == expected_points
print(f"rank {rank} of {ranks}: 2-sample grid, piece {tiny.GetOutput().GetExtent()}, "
      f"{tiny_points} medial points (expected {expected_points})", flush=True)
print(f"rank {rank} of {ranks}: medial axis extent {medial_extent}, "
      f"{points.GetNumberOfPoints()} of {every.GetNumberOfPoints()} medial points: "
      f"{'equal to one process bit for bit' if medial_ok else 'DIFFERS'}", flush=True)


# The segmented field of the parts: regions are global, yet each rank computes its slab.
def segmented(mesh, resolution):
    f = vtkSegmentedDistanceField()
    f.SetInputData(mesh)
    f.SetResolution(resolution)
    f.SetBackendToCPU()
    return f


segment_ok = True
for resolution in (24, 2):
    distributed = segmented(part, resolution)
    distributed.UpdatePiece(rank, ranks, 0)
    slab = distributed.GetOutput()
    e = slab.GetExtent()
    computed = distributed.GetLastComputedExtent()
    vtkMultiProcessController.SetGlobalController(vtkDummyController())
    alone = segmented(whole, resolution)
    alone.Update()
    vtkMultiProcessController.SetGlobalController(controller)
    full = alone.GetOutput()
    wx, wy = full.GetDimensions()[0], full.GetDimensions()[1]
    same = distributed.GetErrorCode() == 0
    if e[1] >= e[0]:
        for name in ("SegmentedDistance", "RegionIndex", "Distance", "PatchId", "ClosestPoint"):
            values = vtk_to_numpy(full.GetPointData().GetArray(name))
            grid = values.reshape((-1, wy, wx) + values.shape[1:])
            expected = np.ascontiguousarray(
                grid[e[4]:e[5] + 1, e[2]:e[3] + 1, e[0]:e[1] + 1])
            got = vtk_to_numpy(slab.GetPointData().GetArray(name))
            same = same and got.tobytes() == expected.tobytes()
        same = same and vtk_to_numpy(slab.GetFieldData().GetArray("RegionSides")).tobytes() == \
            vtk_to_numpy(full.GetFieldData().GetArray("RegionSides")).tobytes()
    # Each rank computed its slab and one sample around it, not the whole grid.
    if resolution > 2 and ranks > 1:
        same = same and tuple(computed) != tuple(full.GetExtent())
    segment_ok = segment_ok and same
    print(f"rank {rank} of {ranks}: segmented field at resolution {resolution}, extent {e}, "
          f"computed {computed}, {alone.GetLastRegionCount()} regions: "
          f"{'equal to one process bit for bit' if same else 'DIFFERS'}", flush=True)

# Every rank asking for the same sub-extent: the pieces leave samples out, so each rank
# computes the whole grid and cuts its sub-extent from it (no evidence is exchanged).
box = (3, 14, 2, 9, 5, 11)
distributed = segmented(part, 24)
distributed.UpdateExtent(box)
cut = distributed.GetOutput()
vtkMultiProcessController.SetGlobalController(vtkDummyController())
alone = segmented(whole, 24)
alone.Update()
vtkMultiProcessController.SetGlobalController(controller)
full = alone.GetOutput()
wx, wy = full.GetDimensions()[0], full.GetDimensions()[1]
values = vtk_to_numpy(full.GetPointData().GetArray("SegmentedDistance")).reshape((-1, wy, wx))
expected = np.ascontiguousarray(values[box[4]:box[5] + 1, box[2]:box[3] + 1, box[0]:box[1] + 1])
got = vtk_to_numpy(cut.GetPointData().GetArray("SegmentedDistance"))
cut_ok = (tuple(cut.GetExtent()) == box and got.tobytes() == expected.tobytes() and
          tuple(distributed.GetLastComputedExtent()) == tuple(full.GetExtent()))
print(f"rank {rank} of {ranks}: the same sub-extent on every rank {cut.GetExtent()}, computed "
      f"{distributed.GetLastComputedExtent()}: "
      f"{'equal to one process bit for bit' if cut_ok else 'DIFFERS'}", flush=True)

# The contour of the distributed field: each rank's segmented field computes its slab,
# rank 0 gathers them and outputs the surface of one process, the other ranks nothing.
producers = []  # a pipeline's upstream filters must outlive the Python names


def contour(mesh):
    c = vtkSegmentedDistanceContour()
    producers.append(segmented(mesh, 24))
    c.SetInputConnection(producers[-1].GetOutputPort())
    return c


distributed = contour(part)
distributed.UpdatePiece(rank, ranks, 0)
surface = distributed.GetOutput()
computed = distributed.GetInputAlgorithm().GetLastComputedExtent()
vtkMultiProcessController.SetGlobalController(vtkDummyController())
alone = contour(whole)
alone.Update()
vtkMultiProcessController.SetGlobalController(controller)
every = alone.GetOutput()
if rank == 0:
    contour_ok = surface.GetNumberOfCells() == every.GetNumberOfCells() > 0 and \
        vtk_to_numpy(surface.GetPoints().GetData()).tobytes() == \
        vtk_to_numpy(every.GetPoints().GetData()).tobytes() and \
        vtk_to_numpy(surface.GetPolys().GetConnectivityArray()).tobytes() == \
        vtk_to_numpy(every.GetPolys().GetConnectivityArray()).tobytes()
else:
    contour_ok = surface.GetNumberOfCells() == 0
contour_ok = contour_ok and distributed.GetErrorCode() == 0 and \
    (ranks == 1 or tuple(computed) != tuple(alone.GetInputAlgorithm().GetLastComputedExtent()))
if rank == 0 and not contour_ok:
    print("points", surface.GetNumberOfPoints(), every.GetNumberOfPoints(),
          np.abs(vtk_to_numpy(surface.GetPoints().GetData()) -
                 vtk_to_numpy(every.GetPoints().GetData())).max()
          if surface.GetNumberOfPoints() == every.GetNumberOfPoints() else "")
print(f"rank {rank} of {ranks}: contour of the field computed on {computed}: "
      f"{surface.GetNumberOfCells()} of {every.GetNumberOfCells()} triangles, "
      f"{'equal to one process bit for bit' if contour_ok else 'DIFFERS'}", flush=True)

# The blend of the distributed field with the same mesh moved by 1.5 spacings: each rank
# blends its slab from the fields' slabs (the segmented fields compute pieces) and the
# regions every rank shares; the slabs equal one process's blend bit for bit.
bounds = whole.GetBounds()
spacing = [(bounds[2 * a + 1] - bounds[2 * a]) * 1.3 / 23 for a in range(3)]
origin = [bounds[2 * a] - 0.15 * (bounds[2 * a + 1] - bounds[2 * a]) for a in range(3)]


def moved(mesh):
    copy = vtkPolyData()
    copy.DeepCopy(mesh)
    points = vtk_to_numpy(copy.GetPoints().GetData())
    points[:, 0] += 1.5 * spacing[0]
    copy.GetPoints().Modified()
    return copy


def blend(mesh):
    b = vtkDistanceFieldBlend()
    for port, m in enumerate((mesh, moved(mesh))):
        f = vtkSegmentedDistanceField()
        f.SetInputData(m)
        f.ExplicitGridOn()
        f.SetGridOrigin(origin)
        f.SetGridSpacing(spacing)
        f.SetGridDimensions(24, 24, 24)
        f.SetBackendToCPU()
        producers.append(f)
        b.SetInputConnection(port, f.GetOutputPort())
    b.SetT(0.4)
    return b


distributed = blend(part)
distributed.UpdatePiece(rank, ranks, 0)
slab = distributed.GetOutput()
e = slab.GetExtent()
computed = distributed.GetInputAlgorithm(0, 0).GetLastComputedExtent()
vtkMultiProcessController.SetGlobalController(vtkDummyController())
alone = blend(whole)
alone.Update()
vtkMultiProcessController.SetGlobalController(controller)
full = alone.GetOutput()
wx, wy = full.GetDimensions()[0], full.GetDimensions()[1]
blend_ok = distributed.GetErrorCode() == 0 and e[1] >= e[0]
differing = 0
for name in ("SegmentedDistance", "RegionIndex", "Distance"):
    values = vtk_to_numpy(full.GetPointData().GetArray(name)).reshape((-1, wy, wx))
    expected = np.ascontiguousarray(values[e[4]:e[5] + 1, e[2]:e[3] + 1, e[0]:e[1] + 1])
    got = vtk_to_numpy(slab.GetPointData().GetArray(name))
    blend_ok = blend_ok and got.tobytes() == expected.reshape(-1).tobytes()
regions = vtk_to_numpy(full.GetPointData().GetArray("RegionIndex"))
blend_ok = blend_ok and (ranks == 1 or (tuple(e) != tuple(full.GetExtent()) and
                                        tuple(computed) != tuple(full.GetExtent())))
print(f"rank {rank} of {ranks}: blend slab {e} of fields computed on {computed} "
      f"({np.unique(regions).size} regions in the blend): "
      f"{'equal to one process bit for bit' if blend_ok else 'DIFFERS'}", flush=True)
controller.Finalize()
sys.exit(0 if ok and is_slab and medial_ok and medial_slab and segment_ok and cut_ok and
         contour_ok and blend_ok else 1)
