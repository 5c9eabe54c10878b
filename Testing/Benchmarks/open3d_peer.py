"""Benchmark (not a test): the exact signed field of vtkLinearFactorDistanceField (CPU,
pseudonormal and winding-number signs) next to Open3D's RaycastingScene
(compute_distance, compute_signed_distance: Embree inside), what Python users reach for,
on the same grid: time (median of REPS interleaved runs of both) and Open3D's error
against ours (the largest |difference| of the magnitudes in grid spacings, the share of
samples whose sign differs from ours, and the share inside by our winding number and by
Open3D: its sign comes from counting a ray's hits, and Debian 12's python3-open3d 0.16
finds no hit at all on the machines measured, so it calls every sample outside).
usage: PYTHONPATH=BUILD/lib/python3/dist-packages /usr/bin/python3 open3d_peer.py MESH_DIR
       [SIZES] [REPS] [THREADS] [MESHES]   (Debian: apt-get install python3-open3d)
MESHES defaults to "bunny_75k armadillo_52k": on dragon_871k, python3-open3d 0.16 aborts
(an Eigen assertion in its point query, "AlignedVector3 ... squaredNorm").
Both sides use THREADS threads (default: every core): vtkSMPTools for ours, Open3D's
own thread pool (it takes every core; the figure says how many it used)."""
import os
import statistics
import sys
import time

import numpy as np
import open3d as o3d
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkSMPTools
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from vtkdistancefields import vtkLinearFactorDistanceField

mesh_dir = sys.argv[1]
sizes = [int(n) for n in (sys.argv[2] if len(sys.argv) > 2 else "64 128").split()]
reps = int(sys.argv[3]) if len(sys.argv) > 3 else 5
threads = int(sys.argv[4]) if len(sys.argv) > 4 else os.cpu_count()
meshes = (sys.argv[5] if len(sys.argv) > 5 else "bunny_75k armadillo_52k").split()
vtkSMPTools.Initialize(threads)


def read(name):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(os.path.join(mesh_dir, name + ".vtp"))
    reader.Update()
    return reader.GetOutput()


def ours(mesh, n, sign):
    f = vtkLinearFactorDistanceField()
    f.SetInputData(mesh)
    f.SetResolution(n)
    getattr(f, f"SetSignModeTo{sign}")()
    f.SetBackendToCPU()
    start = time.perf_counter()
    f.Update()
    seconds = time.perf_counter() - start
    image = f.GetOutput()
    distance = vtk_to_numpy(image.GetPointData().GetArray("Distance")).copy()
    return seconds, distance, image


def open3d_scene(mesh):
    points = vtk_to_numpy(mesh.GetPoints().GetData()).astype(np.float32)
    polys = mesh.GetPolys()
    offsets = vtk_to_numpy(polys.GetOffsetsArray())
    if not np.all(np.diff(offsets) == 3):
        sys.exit("open3d_peer.py takes triangle meshes")
    triangles = vtk_to_numpy(polys.GetConnectivityArray()).reshape(-1, 3).astype(np.uint32)
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.core.Tensor(points), o3d.core.Tensor(triangles))
    return scene


def grid_points(image):
    """Every sample of the image, x fastest, as Open3D's float32 query tensor."""
    nx, ny, nz = image.GetDimensions()
    origin, spacing = np.array(image.GetOrigin()), np.array(image.GetSpacing())
    k, j, i = np.meshgrid(np.arange(nz), np.arange(ny), np.arange(nx), indexing="ij")
    xyz = origin + np.stack([i, j, k], axis=-1).reshape(-1, 3) * spacing
    return o3d.core.Tensor(xyz.astype(np.float32)), spacing.min()


print(f"threads: ours {threads} (vtkSMPTools), Open3D {o3d.core.Device('CPU:0')} with every "
      f"core ({os.cpu_count()}); median of {reps} interleaved runs")
print(f"{'mesh':14} {'N':>4} {'ours pn s':>9} {'ours wn s':>9} {'o3d uns s':>9} "
      f"{'o3d sgn s':>9} {'o3d/pn':>7} {'max err h':>9} {'signs pn':>9} {'signs wn':>9} "
      f"{'in (wn)':>9} {'in (o3d)':>9}")
for name in meshes:
    if not os.path.exists(os.path.join(mesh_dir, name + ".vtp")):
        continue
    mesh = read(name)
    for n in sizes:
        times = {"pn": [], "wn": [], "o3d": [], "o3ds": []}
        for _ in range(reps):
            t, pn, image = ours(mesh, n, "PseudoNormal")
            times["pn"].append(t)
            t, wn, _ = ours(mesh, n, "WindingNumber")
            times["wn"].append(t)
            # Open3D builds its scene (Embree's BVH) per query set, as a user would.
            query, h = grid_points(image)
            start = time.perf_counter()
            unsigned = open3d_scene(mesh).compute_distance(query).numpy()
            times["o3d"].append(time.perf_counter() - start)
            start = time.perf_counter()
            signed = open3d_scene(mesh).compute_signed_distance(query).numpy()
            times["o3ds"].append(time.perf_counter() - start)
        median = {key: statistics.median(value) for key, value in times.items()}
        error = np.max(np.abs(np.abs(signed) - np.abs(pn))) / h
        signs_pn = np.mean((signed < 0) != (pn < 0)) * 100
        signs_wn = np.mean((signed < 0) != (wn < 0)) * 100
        inside_o3d, inside_wn = np.mean(signed < 0) * 100, np.mean(wn < 0) * 100
        print(f"{name:14} {n:4d} {median['pn']:9.3f} {median['wn']:9.3f} {median['o3d']:9.3f} "
              f"{median['o3ds']:9.3f} {median['o3ds'] / median['pn']:6.1f}x {error:9.2e} "
              f"{signs_pn:8.2f}% {signs_wn:8.2f}% {inside_wn:8.2f}% {inside_o3d:8.2f}%",
              flush=True)
