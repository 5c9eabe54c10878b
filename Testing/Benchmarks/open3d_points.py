"""Benchmark (not a test): vtkMeshDistanceFilter (winding-number sign, CPU) next to
Open3D's RaycastingScene (compute_distance, compute_signed_distance: Embree inside),
what Python users reach for, at the same points: time (median of REPS interleaved runs
of both; Open3D's scene built in each run, as ours is), Open3D's largest |difference| of
the magnitudes from ours, and the share of points whose sign differs from ours (our
winding number's, exact where the triangles form a closed chain).
usage: PYTHONPATH=BUILD/lib/python3/dist-packages /usr/bin/python3 open3d_points.py
       MESH.vtp POINTS.npy [REPS]   (Debian: apt-get install python3-open3d)
POINTS from Testing/Benchmarks/points.py. Both sides use the machine's threads:
vtkSMPTools for ours (VTK_SMP_MAX_THREADS), Open3D's own pool."""
import statistics
import sys
import time

import numpy as np
import open3d as o3d
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkTriangleFilter
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from vtkdistancefields import vtkMeshDistanceFilter

mesh_path, points_path = sys.argv[1], sys.argv[2]
reps = int(sys.argv[3]) if len(sys.argv) > 3 else 5
reader = vtkXMLPolyDataReader()
reader.SetFileName(mesh_path)
triangles = vtkTriangleFilter()
triangles.SetInputConnection(reader.GetOutputPort())
triangles.Update()
surface = triangles.GetOutput()
vertices = vtk_to_numpy(surface.GetPoints().GetData()).astype(np.float32)
faces = vtk_to_numpy(surface.GetPolys().GetConnectivityArray()).reshape(-1, 3).astype(np.uint32)
xyz = np.load(points_path)
points = vtkPoints()
points.SetData(numpy_to_vtk(xyz, deep=True))
cloud = vtkPolyData()
cloud.SetPoints(points)
queries = o3d.core.Tensor(xyz.astype(np.float32))


def ours():
    probe = vtkMeshDistanceFilter()
    probe.SetInputData(cloud)
    probe.SetSurfaceData(surface)
    probe.SetSignModeToWindingNumber()
    start = time.perf_counter()
    probe.Update()
    seconds = time.perf_counter() - start
    return seconds, vtk_to_numpy(probe.GetOutput().GetPointData().GetArray("Distance")).copy()


def open3d(signed):
    start = time.perf_counter()
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.core.Tensor(vertices), o3d.core.Tensor(faces))
    result = (scene.compute_signed_distance if signed else scene.compute_distance)(queries)
    seconds = time.perf_counter() - start
    return seconds, result.numpy().astype(np.float64)


times = {"ours": [], "open3d": [], "open3d_signed": []}
for _ in range(reps):
    t, d = ours()
    times["ours"].append(t)
    t, unsigned = open3d(False)
    times["open3d"].append(t)
    t, signed = open3d(True)
    times["open3d_signed"].append(t)
m = {k: statistics.median(v) for k, v in times.items()}
error = np.abs(np.abs(signed) - np.abs(d)).max()
wrong = np.mean((signed < 0) != (d < 0))
print(f"{mesh_path.split('/')[-1]} {points_path.split('/')[-1]} points {len(xyz)} "
      f"ours_s {m['ours']:.4f} open3d_distance_s {m['open3d']:.4f} "
      f"open3d_signed_s {m['open3d_signed']:.4f} ratio_signed {m['open3d_signed'] / m['ours']:.2f} "
      f"max_abs_error {error:.3g} wrong_signs {100 * wrong:.2f} % inside_ours "
      f"{100 * np.mean(d < 0):.2f} % inside_open3d {100 * np.mean(signed < 0):.2f} %")
