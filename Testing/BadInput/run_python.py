"""The corpus of cases.txt through the Python API: run_python.py CORPUS DATA SUBCOMMAND.

Each case's options become the filter's setters. A case vtkdf refuses ("usage") must be
refused here too: the value cannot be passed (a setter raises, or the text is no
number), or the filter fails. An "error" case must fail with an ErrorEvent whose text
matches, a non-zero GetErrorCode() and an empty output, without a Python exception or a
crash; "empty" warns and outputs nothing; "exact" is compared with check_output.py's
brute force. One process runs every case of a subcommand, so a crash fails them all.
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_output  # noqa: E402

from vtkmodules.util.misc import calldata_type  # noqa: E402
from vtkmodules.util.vtkConstants import VTK_STRING  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLImageDataWriter  # noqa: E402
from vtkdistancefields import (vtkChamferVoxelDistance, vtkClipByMeshDistance,  # noqa: E402
                               vtkLinearFactorDistanceField,
                               vtkDistanceFieldProximity, vtkMedialAxisFilter,
                               vtkMeshDistanceFilter, vtkMeshHausdorffDistance,
                               vtkPolyDataVoxelizer, vtkPenetrationDepth,
                               vtkSegmentedDistanceContour, vtkSegmentedDistanceField,
                               vtkSparseDistanceField, vtkUnionClosestPoint)

FILTERS = {"linfac": vtkLinearFactorDistanceField, "voxelize": vtkPolyDataVoxelizer,
           "chamfer": vtkChamferVoxelDistance, "medial": vtkMedialAxisFilter,
           "segment": vtkSegmentedDistanceField, "union": vtkUnionClosestPoint,
           "pd": vtkPenetrationDepth, "proximity": vtkDistanceFieldProximity,
           "probe": vtkMeshDistanceFilter, "hausdorff": vtkMeshHausdorffDistance,
           "clip": vtkClipByMeshDistance, "band": vtkSparseDistanceField}
# The subcommands with no grid and no Backend property, and their own cases.
OWN_CASES = ("union", "pd", "proximity", "probe", "hausdorff", "clip")


class NotPassable(Exception):
    """The value cannot be handed to the API (vtkdf refuses it as a usage error)."""


def number(text, kind):
    try:
        return kind(text)
    except ValueError as error:
        raise NotPassable(str(error))


def configure(f, sub, options, contour=None):
    """The vtkdf options as setter calls (segment's surface options on `contour`)."""
    words = options.split()
    grid = {}
    i = 0
    while i < len(words):
        option = words[i]
        if option == "--paper-vertices" and contour is not None:
            contour.UseClosestPointsOff()
            i += 1
            continue
        if option == "--uncut":
            f.CutSelfIntersectionsOff()
            i += 1
            continue
        if option == "--query":
            f.SetQueryPoint(*[number(w, float) for w in words[i + 1:i + 4]])
            i += 4
            continue
        if option == "--convex-hulls":
            f.UseConvexHullsOn()
            i += 1
            continue
        if option in ("--origin", "--spacing", "--dims"):
            kind = int if option == "--dims" else float
            grid[option] = [number(w, kind) for w in words[i + 1:i + 4]]
            i += 4
            continue
        value = words[i + 1] if i + 1 < len(words) else None
        i += 2
        enums = {"--backend": ("Backend", ["auto", "gpu", "cpu"]),
                 "--domains": ("DomainShape", ["auto", "nonmanifold", "manifold"]),
                 "--culling": ("DomainShape", ["auto", "nonmanifold", "manifold"]),
                 "--route": ("Route", ["auto", "scan", "queries"]),
                 "--mode": ("Mode", ["boundary", "solid", "both"]),
                 "--metric": ("Metric", ["manhattan", "chessboard18", "chessboard26"]),
                 "--region": ("Region", ["inside", "outside", "both"])}
        if option == "--resolution":
            f.SetResolution(number(value, int))
        elif option == "--margin":
            f.SetContactMargin(number(value, float))
        elif option == "--padding":
            f.SetPadding(number(value, float))
        elif option == "--relative-error":
            f.SetRelativeError(number(value, float))
        elif option == "--band":
            f.SetBandWidth(number(value, float))
        elif option == "--brick-size":
            f.SetBrickSize(number(value, int))
        elif option == "--max-distance":
            if sub == "band":
                raise NotPassable("the sparse band's cap is BandWidth")
            f.SetMaximumDistance(number(value, float))
        elif option == "--layers":
            f.SetMaximumLayers(number(value, int))
        elif option == "--angle":
            f.SetSeparationAngle(number(value, float))
        elif option == "--piece-array":
            f.SetPieceArray(value)
        elif option == "--delta":
            f.SetDelta(number(value, float))
        elif option == "--region-offset":
            f.SetRegionOffset(number(value, float))
        elif option == "--surface" and contour is not None:
            contour.SetInputConnection(f.GetOutputPort())  # the path is vtkdf's business
        elif option == "--feature-angle" and contour is not None:
            contour.SetFeatureAngle(number(value, float))
        elif option == "--sign":
            if value not in ("pseudonormal", "winding"):
                raise NotPassable(f"{option} {value}")
            getattr(f, "SetSignModeTo" + ("PseudoNormal" if value == "pseudonormal"
                                          else "WindingNumber"))()
        elif option in enums:
            name, values = enums[option]
            if value not in values:
                raise NotPassable(f"{option} {value}")
            getattr(f, "Set" + name)(values.index(value))
        else:
            raise NotPassable(f"unknown option {option}")
    if grid:
        f.ExplicitGridOn()
        f.SetGridOrigin(*grid["--origin"])
        f.SetGridSpacing(*grid["--spacing"])
        f.SetGridDimensions(*grid["--dims"])


def read(path):
    if path.endswith(".vti"):
        reader = vtkXMLImageDataReader()
        reader.SetFileName(path)
        reader.Update()
        return reader.GetOutput()
    return check_output.read(path)


def run_case(corpus, data, sub, name, path, options, kind, pattern, workdir):
    f = FILTERS[sub]()
    if sub not in OWN_CASES:
        f.SetBackend(f.BACKEND_CPU if sub != "voxelize" else f.BACKEND_AUTO)
    errors, warnings = [], []

    @calldata_type(VTK_STRING)
    def on_error(_obj, _event, text):
        errors.append(text)

    @calldata_type(VTK_STRING)
    def on_warning(_obj, _event, text):
        warnings.append(text)

    f.AddObserver("ErrorEvent", on_error)
    f.AddObserver("WarningEvent", on_warning)
    if not os.path.exists(path) or kind == "usage" and "cannot read" in pattern:
        # A file vtkdf cannot read: the readers must fail without crashing.
        if os.path.exists(path):
            data_object = read(path)
            return data_object.GetNumberOfPoints() == 0, "the reader returned no points"
        return True, "no such file"
    # segment --surface: the field's vtkSegmentedDistanceContour is the filter judged.
    contour = vtkSegmentedDistanceContour() if sub == "segment" and "--surface" in options else None
    try:
        configure(f, sub, options, contour)
    except (NotPassable, TypeError, OverflowError, ValueError) as refused:
        return kind == "usage", f"not passable ({refused})"
    if sub in ("probe", "clip"):  # the bad input is the surface; the points the plane's
        f.SetInputData(0, read(os.path.join(data, "plane.vtp")))
        f.SetInputData(1, read(path))
    else:
        f.SetInputData(0, read(path))
    if sub == "hausdorff":  # the bad input is mesh A; mesh B is the teapot
        f.SetInputData(1, read(os.path.join(data, "teapot.vtp")))
    if sub == "pd":  # the bad input is P; Q is a good solid
        f.SetInputData(1, read(os.path.join(data, "hubo_ankle_convex4.vtp")))
    if sub == "proximity":  # the bad input is model A; model B is the teapot
        f.SetInputData(1, read(os.path.join(data, "teapot.vtp")))
    f.Update()
    if contour is not None and f.GetErrorCode() == 0:
        f.RemoveAllObservers()
        contour.AddObserver("ErrorEvent", on_error)
        contour.AddObserver("WarningEvent", on_warning)
        contour.Update()
        f = contour
    output = f.GetOutputDataObject(0)  # band's: a vtkPartitionedDataSet of pieces
    empty = output.GetNumberOfPoints() == 0
    if kind in ("error", "usage"):
        text = " | ".join(errors)
        ok = f.GetErrorCode() != 0 and empty and bool(errors) and (
            kind == "usage" or re.search(pattern, text))
        return ok, f"error code {f.GetErrorCode()}, {output.GetNumberOfPoints()} points, errors: {text}"
    if kind == "empty":
        text = " | ".join(warnings)
        return empty and f.GetErrorCode() == 0 and bool(re.search(pattern, text)), f"warnings: {text}"
    # exact
    if f.GetErrorCode() != 0 or empty:
        return False, f"failed: {' | '.join(errors)}"
    result = os.path.join(workdir, f"{sub}-{name}.vti")
    writer = vtkXMLImageDataWriter()
    writer.SetFileName(result)
    writer.SetInputData(output)
    writer.Write()
    return check_output.main(path, result) == 0, "compared with the brute force"


def main(corpus, data, sub, workdir):
    os.makedirs(workdir, exist_ok=True)
    failures = count = 0
    for line in open(os.path.join(corpus, "cases.txt")):
        if not line.strip() or line.startswith("#"):
            continue
        name, subs, input_name, options, expect = [w.strip() for w in line.split("|", 4)]
        if subs != "all" and sub not in subs.split() or subs == "all" and sub in OWN_CASES:
            continue
        kind, _, pattern = expect.partition(" ")
        path = os.path.join(corpus, input_name)
        if not os.path.exists(path):
            path = os.path.join(data, input_name)
        ok, detail = run_case(corpus, data, sub, name, path, options, kind, pattern, workdir)
        count += 1
        failures += not ok
        detail = " ".join(detail.split())
        print(f"{'ok  ' if ok else 'FAIL'} {name}: {kind} {pattern} -- {detail}")
    print(f"{count - failures} passed, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))
