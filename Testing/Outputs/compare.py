"""Compares two folders of vtkdf outputs bit for bit.

usage: compare.py EXPECTED_DIR ACTUAL_DIR

VTK XML files (.vti, .vtp) are compared by content: the grid (extent, origin, spacing) or
the points and cells, and every point-, cell- and field-data array by name, type and bytes
(NaNs included). Other files (PNGs) are compared byte for byte. Exits 1 on any difference,
printing each one.
"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader


def read(path):
    reader = vtkXMLImageDataReader() if path.endswith(".vti") else vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def array_bytes(array):
    if array is None:
        return None
    values = vtk_to_numpy(array) if array.GetNumberOfTuples() else np.zeros(0)
    return (array.GetDataTypeAsString(), array.GetNumberOfComponents(),
            np.ascontiguousarray(values).tobytes())


def describe(name, a, b):
    """Where two arrays of one name differ."""
    if a is None or b is None:
        return "%s: only in %s" % (name, "the expected" if b is None else "the actual")
    if a[:2] != b[:2]:
        return "%s: type or components %s against %s" % (name, a[:2], b[:2])
    if len(a[2]) != len(b[2]):
        return "%s: %d bytes against %d" % (name, len(a[2]), len(b[2]))
    x = np.frombuffer(a[2], dtype=np.uint8)
    y = np.frombuffer(b[2], dtype=np.uint8)
    return "%s: %d of %d bytes differ" % (name, int(np.count_nonzero(x != y)), x.size)


def collect(data):
    """Everything compared, as (name, value) in a fixed order."""
    items = []
    if data.IsA("vtkImageData"):
        items.append(("extent", tuple(data.GetExtent())))
        items.append(("origin", tuple(data.GetOrigin())))
        items.append(("spacing", tuple(data.GetSpacing())))
    else:
        points = data.GetPoints()
        items.append(("points", array_bytes(points.GetData()) if points else None))
        for kind in ("Verts", "Lines", "Polys", "Strips"):
            cells = getattr(data, "Get" + kind)()
            items.append((kind + ".offsets", array_bytes(cells.GetOffsetsArray())))
            items.append((kind + ".connectivity", array_bytes(cells.GetConnectivityArray())))
    for label, fields in (("point", data.GetPointData()), ("cell", data.GetCellData()),
                          ("field", data.GetFieldData())):
        names = [fields.GetArrayName(i) for i in range(fields.GetNumberOfArrays())]
        items.append((label + " arrays", tuple(names)))
        for name in names:
            items.append(("%s %s" % (label, name), array_bytes(fields.GetAbstractArray(name))))
    return items


def compare_file(expected, actual):
    if not expected.endswith((".vti", ".vtp")):
        with open(expected, "rb") as a, open(actual, "rb") as b:
            return [] if a.read() == b.read() else ["the bytes differ"]
    differences = []
    a, b = dict(collect(read(expected))), dict(collect(read(actual)))
    for name in list(a) + [n for n in b if n not in a]:
        if a.get(name) != b.get(name):
            va, vb = a.get(name), b.get(name)
            if isinstance(va, tuple) and len(va) == 3 and isinstance(va[2], bytes) or \
                    isinstance(vb, tuple) and len(vb) == 3 and isinstance(vb[2], bytes):
                differences.append(describe(name, va, vb))
            else:
                differences.append("%s: %s against %s" % (name, va, vb))
    return differences


def main():
    expected_dir, actual_dir = sys.argv[1], sys.argv[2]
    expected = sorted(os.listdir(expected_dir))
    actual = sorted(os.listdir(actual_dir))
    failures = 0
    for name in sorted(set(expected) | set(actual)):
        if name not in actual or name not in expected:
            print("DIFFERENT %s: only in %s" % (name, "the expected" if name in expected
                                                 else "the actual"))
            failures += 1
            continue
        differences = compare_file(os.path.join(expected_dir, name),
                                   os.path.join(actual_dir, name))
        if differences:
            failures += 1
            print("DIFFERENT %s: %s" % (name, "; ".join(differences)))
        else:
            print("same      %s" % name)
    print("%d files, %d different" % (len(expected), failures))
    return 1 if failures or not expected else 0


if __name__ == "__main__":
    sys.exit(main())
