#!/usr/bin/env python3
"""Benchmark inputs (not a test): the second meshes of the Hausdorff benchmark.

usage: python3 Testing/Benchmarks/hausdorff_inputs.py MESH_DIR OUT_DIR

Writes OUT_DIR/bunny_75k_decimated.vtp (vtkQuadricDecimation, TargetReduction 0.9: 10 %
of the triangles left) and OUT_DIR/dragon_871k_smoothed.vtp (vtkWindowedSincPolyDataFilter,
20 iterations, pass band 0.1), the pairs docs/benchmarks.md measures: bunny_75k against the
first, dragon_871k against the second.
"""
import os
import sys

from vtkmodules.vtkFiltersCore import (vtkQuadricDecimation, vtkTriangleFilter,
                                       vtkWindowedSincPolyDataFilter)
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter


def read(path):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(reader.GetOutputPort())
    triangles.Update()
    return triangles.GetOutput()


def write(data, path):
    writer = vtkXMLPolyDataWriter()
    writer.SetFileName(path)
    writer.SetInputData(data)
    writer.SetDataModeToBinary()
    if not writer.Write():
        sys.exit(f"cannot write {path}")
    print(f"{path}: {data.GetNumberOfPoints()} points, {data.GetNumberOfCells()} cells")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    meshes, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    decimate = vtkQuadricDecimation()
    decimate.SetInputData(read(os.path.join(meshes, "bunny_75k.vtp")))
    decimate.SetTargetReduction(0.9)
    decimate.Update()
    write(decimate.GetOutput(), os.path.join(out, "bunny_75k_decimated.vtp"))
    smooth = vtkWindowedSincPolyDataFilter()
    smooth.SetInputData(read(os.path.join(meshes, "dragon_871k.vtp")))
    smooth.SetNumberOfIterations(20)
    smooth.SetPassBand(0.1)
    smooth.Update()
    write(smooth.GetOutput(), os.path.join(out, "dragon_871k_smoothed.vtp"))


if __name__ == "__main__":
    main()
