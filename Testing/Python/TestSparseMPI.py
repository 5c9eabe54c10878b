"""vtkSparseDistanceField in a distributed run without ParaView: mpiexec -n R
/usr/bin/python3 TestSparseMPI.py DATA, with VTK's vtkMPIController as the global
controller. Every rank holds the mesh whole and computes its share of the bricks; the
ranks' pieces together must be one process's pieces (the same extents, every array bit for
bit), each piece on one rank, no rank with all of them, and every rank's sides (output 1,
the whole grid of bricks here) and pieces' numbers must be one process's: a closed mesh
(pseudonormal and winding signs), an open one (winding: the bricks beyond the band
decided on the ranks that own them) and an unsigned field."""
import sys

import numpy as np
from mpi4py import MPI
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkParallelCore import vtkDummyController, vtkMultiProcessController
from mpi_support import read, start_controller

from vtkdistancefields import vtkSparseDistanceField

controller, rank, ranks = start_controller()
CASES = [("bunny_small.vtp", 40, 2, 6, 1), ("bunny_small.vtp", 40, 2, 6, 2),
         ("aneurysm.vtp", 64, 1, 3, 2), ("teapot.vtp", 32, 2, 4, 0)]


def run(mesh, resolution, band, brick, sign):
    sparse = vtkSparseDistanceField()
    sparse.SetInputData(mesh)
    sparse.SetResolution(resolution)
    sparse.SetBandWidth(band)
    sparse.SetBrickSize(brick)
    sparse.SetSignMode(sign)
    sparse.SetComputeClosestCellId(True)
    sparse.SetComputeClosestPoint(True)
    sparse.Update()
    return sparse


def pieces(sparse):
    """Every piece as (extent, {array: bytes})."""
    found = {}
    output = sparse.GetOutputDataObject(0)
    for p in range(output.GetNumberOfPartitions()):
        piece = output.GetPartition(p)
        data = piece.GetPointData()
        found[tuple(piece.GetExtent())] = {
            data.GetArray(k).GetName(): vtk_to_numpy(data.GetArray(k)).tobytes()
            for k in range(data.GetNumberOfArrays())}
    return found


def sides(sparse):
    cells = sparse.GetOutputDataObject(1).GetCellData()
    return (tuple(sparse.GetOutputDataObject(1).GetExtent()),
            vtk_to_numpy(cells.GetArray("Side")).tobytes(),
            vtk_to_numpy(cells.GetArray("Piece")).tobytes())


failures = []
for name, resolution, band, brick, sign in CASES:
    case = f"{name} {resolution} band {band} brick {brick} sign {sign}"
    mesh = read(sys.argv[1], name)
    distributed = run(mesh, resolution, band, brick, sign)
    if distributed.GetErrorCode():
        failures.append(f"{case}: rank {rank} failed")
        continue
    mine = pieces(distributed)
    gathered = MPI.COMM_WORLD.gather((mine, sides(distributed)), root=0)
    if rank != 0:
        continue
    vtkMultiProcessController.SetGlobalController(vtkDummyController())
    alone = run(mesh, resolution, band, brick, sign)
    vtkMultiProcessController.SetGlobalController(controller)
    expected, expected_sides = pieces(alone), sides(alone)
    merged, duplicates = {}, 0
    for their_pieces, their_sides in gathered:
        duplicates += sum(1 for e in their_pieces if e in merged)
        merged.update(their_pieces)
        if their_sides != expected_sides:
            failures.append(f"{case}: a rank's sides differ from one process's")
    counts = [len(p) for p, _ in gathered]
    print(f"{case}: {len(expected)} pieces alone; on the {ranks} ranks {counts}", flush=True)
    if merged != expected:
        failures.append(f"{case}: the ranks' pieces are not one process's")
    if duplicates or max(counts) == len(expected):
        failures.append(f"{case}: a piece on several ranks, or one rank with all of them")

MPI.COMM_WORLD.barrier()
for failure in failures:
    print("FAIL:", failure, flush=True)
sys.exit(1 if failures else 0)
