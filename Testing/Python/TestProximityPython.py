"""vtkDistanceFieldProximity from Python: a unit cube A and a box B = [x, x+1] x [0.2, 0.8]^2.
At x = 0.7 they collide; every vertex's DistanceToOther equals the box's exact signed
distance (numpy, closed form); each model's maximum penetration is at most 0.3 (the
deepest point of either surface inside the other) and within one step of it; the
contacts' depths are positive and their normals unit. At x = 1.5 they are 0.5 apart, the
witness line 0.5 long, and no contact. Both backends; the GPU's answers equal the CPU's."""
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkCleanPolyData, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkCubeSource

from vtkdistancefields import vtkDistanceFieldProximity

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def box(bounds):
    source = vtkCubeSource()
    source.SetBounds(*bounds)
    clean = vtkCleanPolyData()
    clean.SetInputConnection(source.GetOutputPort())
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(clean.GetOutputPort())
    triangles.Update()
    mesh = vtkPolyData()
    mesh.DeepCopy(triangles.GetOutput())
    return mesh


def box_distance(points, lo, hi):
    """Signed distance to an axis-aligned box (negative inside)."""
    q = np.maximum(lo - points, points - hi)
    outside = np.linalg.norm(np.maximum(q, 0), axis=1)
    inside = np.minimum(np.max(q, axis=1), 0)
    return outside + inside


def field(output, name, component=0):
    return output.GetFieldData().GetArray(name).GetComponent(0, component)


a_bounds = (0, 1, 0, 1, 0, 1)
a = box(a_bounds)
answered = {}
for backend, x, colliding in [(k, x, c) for k in ("CPU", "GPU") for x, c in ((0.7, 1), (1.5, 0))]:
    b_bounds = (x, x + 1, 0.2, 0.8, 0.2, 0.8)
    b = box(b_bounds)
    proximity = vtkDistanceFieldProximity()
    proximity.SetModelAData(a)
    proximity.SetModelBData(b)
    proximity.SetResolution(32)
    getattr(proximity, "SetBackendTo" + backend)()
    proximity.Update()
    check(proximity.GetErrorCode() == 0, f"x={x}: the filter failed on the {backend}")
    check(proximity.GetLastBackend() == backend.lower(), f"x={x}: ran on the {backend}")
    answers = proximity.GetOutput(0)
    answered[backend, x] = [field(answers, name) for name in (
        "Colliding", "SeparationDistance", "MaximumPenetrationAB", "MaximumPenetrationBA")]
    if backend == "GPU":
        check(answered[backend, x] == answered["CPU", x], f"x={x}: the GPU's answers as the CPU's")
    check(field(answers, "Colliding") == colliding, f"x={x}: Colliding")
    step = field(answers, "Step")
    # vtkCubeSource writes float coordinates: the boxes as they are.
    for port, mesh, other in ((2, a, b.GetBounds()), (3, b, a.GetBounds())):
        out = proximity.GetOutput(port)
        points = vtk_to_numpy(out.GetPoints().GetData()).astype(float)
        expected = box_distance(points, np.array(other[0::2]), np.array(other[1::2]))
        got = vtk_to_numpy(out.GetPointData().GetArray("DistanceToOther"))
        check(np.allclose(got, expected, rtol=0, atol=1e-12), f"x={x}: DistanceToOther on port {port}")
    contacts = proximity.GetOutput(1)
    if colliding:
        for name in ("MaximumPenetrationAB", "MaximumPenetrationBA"):
            depth = field(answers, name)
            check(0.3 - step <= depth <= 0.3 + 1e-7, f"x={x}: {name} = {depth}")
        depths = vtk_to_numpy(contacts.GetPointData().GetArray("Depth"))
        normals = vtk_to_numpy(contacts.GetPointData().GetArray("Normal"))
        check(len(depths) > 0 and np.all(depths > 0), f"x={x}: contact depths")
        check(np.allclose(np.linalg.norm(normals, axis=1), 1, atol=1e-12), f"x={x}: unit normals")
    else:
        separation = field(answers, "SeparationDistance")
        check(abs(separation - 0.5) <= 1e-7, f"x={x}: SeparationDistance = {separation}")
        line = vtk_to_numpy(answers.GetPoints().GetData())
        check(abs(np.linalg.norm(line[1] - line[0]) - separation) <= 1e-12, f"x={x}: witness line")
        check(contacts.GetNumberOfPoints() == 0, f"x={x}: no contact")
    print(f"{backend} x={x}: colliding {proximity.GetLastColliding()} separation "
          f"{proximity.GetLastSeparationDistance():.6g} penetration "
          f"{proximity.GetLastPenetrationAB():.6g} / {proximity.GetLastPenetrationBA():.6g} "
          f"step {step:.4g} contacts {contacts.GetNumberOfPoints()}")

sys.exit(1 if failures else 0)
