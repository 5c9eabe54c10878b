"""The exact reference of the corpus's "exact" cases: check_output.py MESH FIELD.vti.

Every sample's Distance must equal the exact distance to the mesh's polygons and vertex
cells, or to its points when it has no cells (each polygon its
area in its best-fit plane, concave ones included; degenerate triangles as the segments
and points they are) within 1e-3 of the smallest spacing plus, for a polygon that is not
planar, its corners' largest distance from that plane, capped at the field's
MaximumDistance when it has one (read back as the largest value). Brute force in numpy.
"""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOGeometry import vtkOBJReader
from vtkmodules.vtkIOLegacy import vtkPolyDataReader
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader


def read(path):
    reader = {"vtp": vtkXMLPolyDataReader, "vtk": vtkPolyDataReader, "obj": vtkOBJReader,
              "ply": vtkPLYReader}[
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
    """The distance from x to the polygon's area in its best-fit plane (Newell's normal
    through the corners' mean), and the polygon's largest distance from that plane."""
    # Newell's normal: zero for a degenerate polygon, which has no interior.
    centre = corners.mean(axis=0)
    normal = np.zeros(3)
    for i in range(len(corners)):
        normal += np.cross(corners[i] - centre, corners[(i + 1) % len(corners)] - centre)
    if np.linalg.norm(normal) == 0:
        best = np.full(len(x), np.inf)
        for i in range(len(corners)):
            best = np.minimum(best, segment_distance(x, corners[i], corners[(i + 1) % len(corners)]))
        return best, 0.0
    normal /= np.linalg.norm(normal)
    flat = corners - np.outer((corners - centre) @ normal, normal)
    best = np.full(len(x), np.inf)
    for i in range(len(flat)):
        best = np.minimum(best, segment_distance(x, flat[i], flat[(i + 1) % len(flat)]))
    drop = np.argmax(np.abs(normal))
    keep = [a for a in range(3) if a != drop]
    height = (x - centre) @ normal
    foot = x - height[:, None] * normal
    u, v = foot[:, keep[0]], foot[:, keep[1]]
    inside = np.zeros(len(x), bool)
    for i in range(len(flat)):  # crossing number in the projection plane
        p, q = flat[i][keep], flat[(i + 1) % len(flat)][keep]
        crosses = (p[1] > v) != (q[1] > v)
        with np.errstate(divide="ignore", invalid="ignore"):
            at = p[0] + (v - p[1]) * (q[0] - p[0]) / (q[1] - p[1])
        inside ^= crosses & (u < at)
    planarity = float(np.abs((corners - centre) @ normal).max())
    return np.where(inside, np.minimum(best, np.abs(height)), best), planarity


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
    # A polygon p corners off its plane is triangulated through its corners: its
    # triangles lie within p of its area in the plane, so its distance is exact +- p.
    exact = np.full(len(samples), np.inf)
    low = np.full(len(samples), np.inf)
    high = np.full(len(samples), np.inf)
    polys = mesh.GetPolys()
    ids = vtk_to_numpy(polys.GetConnectivityArray())
    offsets = vtk_to_numpy(polys.GetOffsetsArray())
    for c in range(polys.GetNumberOfCells()):
        corners = points[ids[offsets[c]:offsets[c + 1]]]
        d, planarity = polygon_distance(samples, corners)
        exact = np.minimum(exact, d)
        low = np.minimum(low, np.maximum(d - planarity, 0))
        high = np.minimum(high, d + planarity)
    # Vertex cells are points; a mesh without cells is taken as its points alone.
    verts = vtk_to_numpy(mesh.GetVerts().GetConnectivityArray()) if mesh.GetNumberOfVerts() else []
    sites = points if mesh.GetNumberOfCells() == 0 else points[verts]
    for site in sites:
        d = np.linalg.norm(samples - site, axis=1)
        exact, low, high = (np.minimum(a, d) for a in (exact, low, high))
    cap = distance.max()
    if np.any(exact > cap + 1e-9 * cap):  # a narrow band: farther samples hold the cap
        exact, low, high = (np.minimum(a, cap) for a in (exact, low, high))
    h = min(image.GetSpacing())
    error = np.maximum(np.maximum(low - distance, distance - high), 0) / h
    worst = int(np.argmax(error))
    print(f"{len(samples)} samples, {polys.GetNumberOfCells()} polygons: largest error "
          f"{error[worst]:.3g} h at {samples[worst]} ({distance[worst]} against {exact[worst]})")
    return 0 if np.all(np.isfinite(distance)) and error.max() <= 1e-3 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
