#!/usr/bin/env python3
"""Runs one of the README's examples and checks the field it makes, sample by sample,
against the exact signed distance to the mesh it was given (VTK's default sphere, a
closed convex polyhedron), by brute force over its triangles.

usage: check_readme_example.py cxx EXAMPLE_EXECUTABLE WORK_DIR
       check_readme_example.py python EXAMPLE.py WORK_DIR
"""
import glob
import os
import runpy
import shutil
import subprocess
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOXML import vtkXMLImageDataReader


def segment_distance(p, a, b):
    ab = b - a
    t = np.clip(((p - a) @ ab) / max(ab @ ab, 1e-300), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)


def exact_signed_distance(points, corners):
    """Exact distance from each point to the closed convex polyhedron with these
    triangles, negative inside."""
    centre = corners.reshape(-1, 3).mean(axis=0)
    distance = np.full(len(points), np.inf)
    inside = np.ones(len(points), dtype=bool)
    for a, b, c in corners:
        n = np.cross(b - a, c - a)
        area2 = np.linalg.norm(n)
        if area2 == 0.0:
            continue
        n /= area2
        if n @ (a - centre) < 0:  # outward
            n = -n
        height = (points - a) @ n
        inside &= height <= 0.0
        foot = points - height[:, None] * n
        # Barycentric signs of the foot: inside the triangle when all agree.
        s = [np.cross(q - p0, foot - p0) @ n for p0, q in ((a, b), (b, c), (c, a))]
        over = (s[0] >= 0) & (s[1] >= 0) & (s[2] >= 0)
        d = np.minimum(np.minimum(segment_distance(points, a, b), segment_distance(points, b, c)),
                       segment_distance(points, c, a))
        d = np.where(over, np.abs(height), d)
        distance = np.minimum(distance, d)
    return np.where(inside, -distance, distance)


def check(image, mesh):
    dims = image.GetDimensions()
    if image.GetNumberOfPoints() < 8 or image.GetPointData().GetArray("Distance") is None:
        sys.exit(f"the example's image has no Distance field (dimensions {dims})")
    field = vtk_to_numpy(image.GetPointData().GetArray("Distance")).astype(np.float64)
    points = np.array([image.GetPoint(i) for i in range(image.GetNumberOfPoints())])
    polys = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    corners = vtk_to_numpy(mesh.GetPoints().GetData()).astype(np.float64)[polys]
    exact = exact_signed_distance(points, corners)
    spacing = min(image.GetSpacing())
    error = np.abs(field - exact).max() / spacing
    wrong_side = np.count_nonzero((np.abs(exact) > 1e-6 * spacing) & (np.sign(field) != np.sign(exact)))
    print(f"dimensions {dims}, {len(field)} samples: max error {error:.2e} spacings, "
          f"{wrong_side} on the wrong side")
    if error > 1e-4 or wrong_side:
        sys.exit("the example's field is not the exact signed distance")


def main():
    mode, example, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.chdir(work)
    sphere = vtkSphereSource()
    sphere.Update()
    if mode == "cxx":
        subprocess.run([example], check=True)
        written = glob.glob("*.vti")
        if len(written) != 1:
            sys.exit(f"expected the example to write one .vti, found {written}")
        reader = vtkXMLImageDataReader()
        reader.SetFileName(written[0])
        reader.Update()
        check(reader.GetOutput(), sphere.GetOutput())
    else:
        names = runpy.run_path(example)
        images = [v for v in names.values() if isinstance(v, vtkImageData)]
        if len(images) != 1:
            sys.exit(f"expected the example to leave one vtkImageData, found {len(images)}")
        check(images[0], sphere.GetOutput())


if __name__ == "__main__":
    main()
