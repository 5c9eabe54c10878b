"""The exact reference of the corpus's "exact" cases: check_output.py MESH FIELD.vti.

Every sample's Distance must equal the exact distance to the mesh's polygons (each an
exact planar polygon, concave ones included; degenerate triangles as the segments and
points they are) within 1e-3 of the smallest spacing, capped at the field's
MaximumDistance when it has one (read back as the largest value). Brute force in numpy.
"""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOGeometry import vtkOBJReader
from vtkmodules.vtkIOLegacy import vtkPolyDataReader
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader


def read(path):
    reader = {"vtp": vtkXMLPolyDataReader, "vtk": vtkPolyDataReader, "obj": vtkOBJReader}[
        path.rsplit(".", 1)[1]]()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def segment_distance(x, a, b):
    ab = b - a
    length2 = ab @ ab
    t = np.zeros(len(x)) if length2 == 0 else np.clip((x - a) @ ab / length2, 0, 1)
    return np.linalg.norm(x - (a + t[:, None] * ab), axis=1)


def polygon_distance(x, corners):
    best = np.full(len(x), np.inf)
    for i in range(len(corners)):
        best = np.minimum(best, segment_distance(x, corners[i], corners[(i + 1) % len(corners)]))
    # Newell's normal: zero for a degenerate polygon, which has no interior.
    normal = np.zeros(3)
    for i in range(len(corners)):
        p, q = corners[i], corners[(i + 1) % len(corners)]
        normal += np.cross(p, q)
    if np.linalg.norm(normal) == 0:
        return best
    normal /= np.linalg.norm(normal)
    drop = np.argmax(np.abs(normal))
    keep = [a for a in range(3) if a != drop]
    height = (x - corners[0]) @ normal
    foot = x - height[:, None] * normal
    u, v = foot[:, keep[0]], foot[:, keep[1]]
    inside = np.zeros(len(x), bool)
    for i in range(len(corners)):  # crossing number in the projection plane
        p, q = corners[i][keep], corners[(i + 1) % len(corners)][keep]
        crosses = (p[1] > v) != (q[1] > v)
        with np.errstate(divide="ignore", invalid="ignore"):
            at = p[0] + (v - p[1]) * (q[0] - p[0]) / (q[1] - p[1])
        inside ^= crosses & (u < at)
    return np.where(inside, np.minimum(best, np.abs(height)), best)


def main(mesh_path, field_path):
    mesh = read(mesh_path)
    image_reader = vtkXMLImageDataReader()
    image_reader.SetFileName(field_path)
    image_reader.Update()
    image = image_reader.GetOutput()
    points = vtk_to_numpy(mesh.GetPoints().GetData()).astype(np.float64)
    samples = np.array([image.GetPoint(i) for i in range(image.GetNumberOfPoints())])
    # Magnitudes: a signed field (--sign) is checked for its distances, not its signs.
    distance = np.abs(vtk_to_numpy(image.GetPointData().GetArray("Distance")).astype(np.float64))
    exact = np.full(len(samples), np.inf)
    polys = mesh.GetPolys()
    ids = vtk_to_numpy(polys.GetConnectivityArray())
    offsets = vtk_to_numpy(polys.GetOffsetsArray())
    for c in range(polys.GetNumberOfCells()):
        corners = points[ids[offsets[c]:offsets[c + 1]]]
        exact = np.minimum(exact, polygon_distance(samples, corners))
    cap = distance.max()
    if np.any(exact > cap + 1e-9 * cap):  # a narrow band: farther samples hold the cap
        exact = np.minimum(exact, cap)
    h = min(image.GetSpacing())
    error = np.abs(distance - exact) / h
    worst = int(np.argmax(error))
    print(f"{len(samples)} samples, {polys.GetNumberOfCells()} polygons: largest error "
          f"{error[worst]:.3g} h at {samples[worst]} ({distance[worst]} against {exact[worst]})")
    return 0 if np.all(np.isfinite(distance)) and error.max() <= 1e-3 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
