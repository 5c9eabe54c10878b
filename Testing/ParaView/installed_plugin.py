"""The plugin as the Debian package vtkdistancefields-paraview installs it, loaded by
pvbatch as a user would: pvbatch installed_plugin.py MESH.

Loaded by path (LoadPlugin with remote=True) in one process, and in another found through
PV_PLUGIN_PATH (the caller sets it to the plugin's folder and passes "auto"), which
ParaView loads at start-up; then the linear factorization and the medial axis of its
field run on the bundled mesh and their outputs must have the arrays the filters make."""
import sys

from paraview import servermanager, simple
from vtkmodules.util.numpy_support import vtk_to_numpy

PLUGIN = "/usr/lib/x86_64-linux-gnu/paraview-5.11/plugins/DistanceFields/DistanceFields.so"
mesh_file = sys.argv[1]
automatic = sys.argv[2:3] == ["auto"]
if not automatic:
    simple.LoadPlugin(PLUGIN, remote=True)
if not hasattr(simple, "LinearFactorDistanceField"):
    sys.exit("FAIL: the plugin's filters are not in paraview.simple")
mesh = simple.XMLPolyDataReader(FileName=[mesh_file])
failures = []
field = simple.LinearFactorDistanceField(Input=mesh, Resolution=20, Backend="CPU",
                                         ComputeClosestPoint=1)
image = servermanager.Fetch(field)
if image.GetDimensions()[0] != 20 or image.GetPointData().GetArray("Distance") is None:
    failures.append(f"linear factorization: dimensions {image.GetDimensions()}")
medial = simple.MedialAxisFilter(Input=field, Region="Both", Backend="CPU")
medial_image = servermanager.Fetch(medial)
marks = medial_image.GetPointData().GetArray("Medial")
voxels = int(vtk_to_numpy(marks).sum()) if marks is not None else 0
if voxels == 0:
    failures.append("medial axis: no medial voxel")
print(f"plugin {'from PV_PLUGIN_PATH' if automatic else 'by path'}: field "
      f"{image.GetDimensions()}, {voxels} medial voxels", flush=True)
for failure in failures:
    print("FAIL:", failure)
sys.exit(1 if failures else 0)
