"""Backend Auto beside a GPU: the field on the CPU, the winding-number sign on the GPU
(Common/BackendPolicy.h, ChoosePlan; vtkDistanceFieldExecution.h, SignContext). CI has no hardware GPU, so the test sets
VTKDF_AUTO_GPU_SIGN=1 (llvmpipe taken as if it were one) and checks, on an open and a
closed mesh, that Auto signs every sample as the CPU backend does (the distances bit for
bit), that the winding numbers agree within the evaluation's bound, and that the filter
says where the sign ran (without the winding numbers the sign stays on the CPU wherever
its crossings along the lines decide it, in less time than any winding pass), and that
the medial axis (winding sign) gives the CPU backend's voxels; then, in a second process with VTKDF_AUTO_GPU_SIGN=0, that Auto keeps it on the
CPU: python3 TestAutoSignPython.py DATA."""
import os
import subprocess
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from vtkdistancefields import vtkLinearFactorDistanceField, vtkMedialAxisFilter

data = sys.argv[1]
setting = os.environ.get("VTKDF_AUTO_GPU_SIGN")
if setting is None:
    # The driver: one process with each setting.
    failed = False
    for value in ("1", "0"):
        result = subprocess.run([sys.executable, __file__, data],
                                env=dict(os.environ, VTKDF_AUTO_GPU_SIGN=value))
        failed = failed or result.returncode != 0
    sys.exit(1 if failed else 0)


def field(mesh, auto, values=True):
    f = vtkLinearFactorDistanceField()
    f.SetInputData(mesh)
    f.SetResolution(20)
    f.SetSignModeToWindingNumber()
    f.SetComputeWindingNumber(values)
    if auto:
        f.SetBackendToAuto()
    else:
        f.SetBackendToCPU()
    f.Update()
    return f


ok = True
for name in ("aneurysm.vtp", "bunny_small.vtp"):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(os.path.join(data, name))
    reader.Update()
    auto, cpu = field(reader.GetOutput(), True), field(reader.GetOutput(), False)
    a, c = auto.GetOutput().GetPointData(), cpu.GetOutput().GetPointData()
    same = (vtk_to_numpy(a.GetArray("Distance")).tobytes() ==
            vtk_to_numpy(c.GetArray("Distance")).tobytes())
    w = np.abs(vtk_to_numpy(a.GetArray("WindingNumber")) -
               vtk_to_numpy(c.GetArray("WindingNumber"))).max()
    expected = "gpu" if setting == "1" else "cpu"
    where = auto.GetLastSignBackend()
    good = (same and w < 1e-3 and where == expected and cpu.GetLastSignBackend() == "cpu" and
            auto.GetLastBackend() == "cpu")
    ok = ok and good
    print(f"VTKDF_AUTO_GPU_SIGN={setting} {name}: Auto's sign on {where} (expected {expected}), "
          f"distances {'equal to the CPU backend bit for bit' if same else 'DIFFER'}, "
          f"winding numbers within {w:.2e}: {'ok' if good else 'FAIL'}", flush=True)

# Signs only: on the CPU under Auto all the same, by the crossings (the aneurysm and the
# soup closed by cones over their boundaries).
for name, closed in (("aneurysm.vtp", True), ("bunny_small.vtp", True),
                     ("boeing_soup.vtp", True)):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(os.path.join(data, name))
    reader.Update()
    auto, cpu = field(reader.GetOutput(), True, False), field(reader.GetOutput(), False, False)
    same = (vtk_to_numpy(auto.GetOutput().GetPointData().GetArray("Distance")).tobytes() ==
            vtk_to_numpy(cpu.GetOutput().GetPointData().GetArray("Distance")).tobytes())
    expected = "gpu" if setting == "1" and not closed else "cpu"
    where = auto.GetLastSignBackend()
    lines = auto.GetLastWindingLineSamples()
    good = same and where == expected and (lines > 0) == closed
    ok = ok and good
    print(f"VTKDF_AUTO_GPU_SIGN={setting} {name} signs only: Auto's sign on {where} (expected "
          f"{expected}), {lines} samples by crossings, distances "
          f"{'equal to the CPU backend bit for bit' if same else 'DIFFER'}: "
          f"{'ok' if good else 'FAIL'}", flush=True)

# The medial axis of a mesh with the winding sign: Auto's voxels equal the CPU backend's.
reader = vtkXMLPolyDataReader()
reader.SetFileName(os.path.join(data, "bunny_small.vtp"))
reader.Update()
medial = {}
for auto in (True, False):
    m = vtkMedialAxisFilter()
    m.SetInputData(reader.GetOutput())
    m.SetResolution(20)
    m.SetSignModeToWindingNumber()
    if auto:
        m.SetBackendToAuto()
    else:
        m.SetBackendToCPU()
    m.Update()
    medial[auto] = [vtk_to_numpy(m.GetOutput().GetPointData().GetArray(name)).tobytes()
                    for name in ("Medial", "SeparationAngle", "Radius")]
same = medial[True] == medial[False]
ok = ok and same
print(f"VTKDF_AUTO_GPU_SIGN={setting} medial axis: Auto's voxels "
      f"{'equal to the CPU backend bit for bit' if same else 'DIFFER'}", flush=True)
sys.exit(0 if ok else 1)
