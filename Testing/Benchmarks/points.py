"""Query points for the point benchmarks (Testing/Benchmarks/versus-peers-points.sh):
N points uniform in the mesh's bounding box padded by 10 % of its longest side on every
side (the grid convention's box), and N points within 1 % of the box's diagonal of the
surface (a point drawn on the triangles by area, moved along a random direction by a
random distance up to that). Seeded: the same files on every machine.
usage: /usr/bin/python3 points.py MESH.vtp N UNIFORM.npy NEAR.npy"""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

path, n, uniform_path, near_path = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
reader = vtkXMLPolyDataReader()
reader.SetFileName(path)
triangles = vtkTriangleFilter()
triangles.SetInputConnection(reader.GetOutputPort())
triangles.Update()
mesh = triangles.GetOutput()
bounds = np.array(mesh.GetBounds()).reshape(3, 2)
side = (bounds[:, 1] - bounds[:, 0]).max()
rng = np.random.default_rng(5)
np.save(uniform_path, rng.uniform(bounds[:, 0] - 0.1 * side, bounds[:, 1] + 0.1 * side, (n, 3)))
xyz = vtk_to_numpy(mesh.GetPoints().GetData()).astype(np.float64)
corners = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 3)
a, b, c = xyz[corners[:, 0]], xyz[corners[:, 1]], xyz[corners[:, 2]]
area = np.linalg.norm(np.cross(b - a, c - a), axis=1)
t = rng.choice(len(corners), n, p=area / area.sum())
u, v = rng.random(n), rng.random(n)
flip = u + v > 1
u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
on_surface = a[t] + u[:, None] * (b[t] - a[t]) + v[:, None] * (c[t] - a[t])
direction = rng.normal(size=(n, 3))
direction /= np.linalg.norm(direction, axis=1)[:, None]
diagonal = np.linalg.norm(bounds[:, 1] - bounds[:, 0])
np.save(near_path, on_surface + direction * (rng.random(n) * 0.01 * diagonal)[:, None])
