"""The values of vtkdf's outputs in TestCli.sh's folder, checked against what they must
be (usage: check_cli_values.py OUT_DIR DATA_DIR TIMING_LOG). Prints each failure; exits 1 on any.

- linfac (the bunny, signed, with closest points): |Distance| is the distance from each
  sample to its ClosestPoint (to float rounding), negative and positive samples both
  occur, every closest point lies in the bunny's box, x - Distance * Gradient is the
  closest point and the barycentric coordinates are a convex combination; the per-sample query route
  (linfac-queries) gives the same field.
- clip: every point kept inside the bunny (Distance at most 0).
- medial: the medial_voxels count printed is the number of points written.
- chamfer: the zero layer is exactly the Boundary mask of voxelize's output, and the
  largest |distance| is the layers count printed.
- blend: a segmented field blended with itself is itself.
"""
import re
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import (vtkXMLImageDataReader, vtkXMLPolyDataReader,
                                 vtkXMLUnstructuredGridReader)

out, data, log = sys.argv[1], sys.argv[2], open(sys.argv[3]).read()
failures = []


def read(name, reader=vtkXMLImageDataReader, folder=None):
    r = reader()
    r.SetFileName("%s/%s" % (folder or out, name))
    r.Update()
    return r.GetOutput()


def array(data, name):
    a = data.GetPointData().GetArray(name)
    if a is None:
        failures.append("%s: no %s array" % (data.GetClassName(), name))
        return np.zeros(0)
    return vtk_to_numpy(a).astype(np.float64)


def printed(subcommand, key):
    found = re.search(r"^vtkdf: %s .*\b%s=([0-9.]+)" % (subcommand, key), log, re.M)
    return float(found.group(1)) if found else None


field = read("linfac.vti")
distance = array(field, "Distance")
closest = array(field, "ClosestPoint").reshape(-1, 3)
samples = np.array([field.GetPoint(i) for i in range(field.GetNumberOfPoints())])
spacing = max(field.GetSpacing())
if distance.size == 0 or len(closest) != len(distance):
    failures.append("linfac: %d distances, %d closest points" % (distance.size, len(closest)))
else:
    error = np.abs(np.abs(distance) - np.linalg.norm(samples - closest, axis=1)).max()
    if error > 1e-5 * spacing * 24:
        failures.append("linfac: |Distance| differs from the distance to ClosestPoint by %g" % error)
    if not (distance.min() < 0 < distance.max()):
        failures.append("linfac: a signed field of a closed mesh without both signs (%g..%g)"
                        % (distance.min(), distance.max()))
    box = np.array(read("bunny_small.vtp", vtkXMLPolyDataReader, data).GetBounds()).reshape(3, 2)
    slack = 1e-6 * np.linalg.norm(box[:, 1] - box[:, 0])
    if ((closest < box[:, 0] - slack) | (closest > box[:, 1] + slack)).any():
        failures.append("linfac: a closest point outside the mesh's box")
    # Gradient: the unit vector from the closest point, signed, so x - d g is the closest
    # point; the barycentric coordinates of a triangle mesh's closest point are a convex
    # combination.
    gradient = array(field, "Gradient").reshape(-1, 3)
    bary = array(field, "ClosestBarycentric").reshape(-1, 3)
    if len(gradient) != len(distance) or len(bary) != len(distance):
        failures.append("linfac: %d gradients, %d barycentric coordinates"
                        % (len(gradient), len(bary)))
    else:
        moved = samples - distance[:, None] * gradient
        if np.abs(moved - closest).max() > 1e-5 * spacing * 24:
            failures.append("linfac: x - Distance * Gradient is not the closest point")
        if np.abs(bary.sum(axis=1) - 1).max() > 1e-5 or bary.min() < -1e-5:
            failures.append("linfac: barycentric coordinates not a convex combination")
queries = array(read("linfac-queries.vti"), "Distance")
if queries.shape != distance.shape or np.abs(queries - distance).max() > 1e-6 * spacing * 24:
    failures.append("linfac-queries: the per-sample query route differs from the scan")

# clip: the grid kept inside the bunny: every point's Distance at most 0 (the cut's
# points interpolated to it), and some cells.
clip = read("clip.vtu", vtkXMLUnstructuredGridReader)
clipped = array(clip, "Distance")
if clip.GetNumberOfCells() == 0 or clipped.size == 0 or clipped.max() > 1e-12 * spacing:
    failures.append("clip: %d cells, Distance up to %g" % (clip.GetNumberOfCells(),
                                                          clipped.max() if clipped.size else 0))

medial = read("medial.vtp", vtkXMLPolyDataReader).GetNumberOfPoints()
if printed("medial", "medial_voxels") != medial:
    failures.append("medial: printed %s medial voxels, wrote %d points"
                    % (printed("medial", "medial_voxels"), medial))

boundary = array(read("voxels.vti"), "Boundary")
chamfer = array(read("chamfer.vti"), "ChamferDistance")
if chamfer.shape != boundary.shape or not np.array_equal(chamfer == 0, boundary != 0):
    failures.append("chamfer: the zero layer is not the Boundary mask")
elif printed("chamfer", "layers") != np.abs(chamfer).max():
    failures.append("chamfer: printed %s layers, the field reaches %g"
                    % (printed("chamfer", "layers"), np.abs(chamfer).max()))

segmented = array(read("segment.vti"), "SegmentedDistance")
blended = array(read("blend.vti"), "SegmentedDistance")
if not np.array_equal(segmented, blended):
    failures.append("blend: a field blended with itself is not itself")

for failure in failures:
    print("FAIL: " + failure)
print("values: %d checks failed" % len(failures))
sys.exit(1 if failures else 0)
