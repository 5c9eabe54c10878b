"""Checks that two folders of outputs (the ParaView plugin's and the system-VTK build's,
or one process's and several's) hold the same outputs (by name: a .pvti, assembled from
its pieces, stands for the .vti of the same name) with equal data bit for bit:
python3 compare_outputs.py A B. Images
must have the same extent, origin and spacing; poly data the same points and cells;
both the same point, cell and field arrays (names, types, components, bytes)."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import (vtkXMLImageDataReader, vtkXMLPImageDataReader,
                                 vtkXMLPolyDataReader, vtkXMLPPolyDataReader)


def read(path):
    """A .vti, a .vtp, or a .pvti or .pvtp assembled from its pieces."""
    readers = {".vti": vtkXMLImageDataReader, ".vtp": vtkXMLPolyDataReader,
               ".pvti": vtkXMLPImageDataReader, ".pvtp": vtkXMLPPolyDataReader}
    reader = readers[os.path.splitext(path)[1]]()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def arrays(data):
    """Every array of a data object, as {(association, name): (type, components, bytes)}."""
    found = {}
    for association, attributes in (("point", data.GetPointData()),
                                    ("cell", data.GetCellData()),
                                    ("field", data.GetFieldData())):
        for i in range(attributes.GetNumberOfArrays()):
            array = attributes.GetAbstractArray(i)
            if array.IsA("vtkDataArray"):
                values = np.ascontiguousarray(vtk_to_numpy(array)).tobytes()
            else:
                values = "\n".join(array.GetValue(j) for j in range(array.GetNumberOfValues()))
            found[(association, array.GetName())] = (
                array.GetDataTypeAsString(), array.GetNumberOfComponents(), values)
    return found


def geometry(data):
    if data.IsA("vtkImageData"):
        return (tuple(data.GetExtent()), tuple(data.GetOrigin()), tuple(data.GetSpacing()))
    parts = [vtk_to_numpy(data.GetPoints().GetData()).tobytes() if data.GetPoints() else b""]
    for cells in (data.GetVerts(), data.GetLines(), data.GetPolys(), data.GetStrips()):
        parts.append(vtk_to_numpy(cells.GetOffsetsArray()).astype(np.int64).tobytes())
        parts.append(vtk_to_numpy(cells.GetConnectivityArray()).astype(np.int64).tobytes())
    return tuple(parts)


def outputs(folder):
    """The output files of a folder by name without extension (a .pvti's pieces are in
    its own subfolder)."""
    return {os.path.splitext(name)[0]: os.path.join(folder, name)
            for name in os.listdir(folder) if os.path.splitext(name)[1] in (".vti", ".vtp", ".pvti", ".pvtp")}


def compare(first_folder, second_folder):
    """Prints each output's comparison; returns the failures."""
    first, second = outputs(first_folder), outputs(second_folder)
    names = sorted(first)
    failures = []
    if names != sorted(second):
        failures.append(f"different outputs: {names} and {sorted(second)}")
    for name in names:
        if name not in second:
            continue
        a, b = read(first[name]), read(second[name])
        if a.GetNumberOfPoints() == 0:
            failures.append(f"{name}: empty")
            continue
        if geometry(a) != geometry(b):
            failures.append(f"{name}: the grids or geometries differ")
        arrays_a, arrays_b = arrays(a), arrays(b)
        if sorted(arrays_a) != sorted(arrays_b):
            failures.append(f"{name}: arrays {sorted(arrays_a)} and {sorted(arrays_b)}")
        differing = [key[1] for key in arrays_a
                     if key in arrays_b and arrays_a[key] != arrays_b[key]]
        if differing:
            failures.append(f"{name}: arrays differ: {differing}")
        print(f"{name}: {a.GetNumberOfPoints()} points, {len(arrays_a)} arrays "
              f"({', '.join(sorted(key[1] for key in arrays_a))}): "
              f"{'differ' if differing else 'equal bit for bit'}")
    return failures


if __name__ == "__main__":
    failures = compare(sys.argv[1], sys.argv[2])
    for failure in failures:
        print("FAIL:", failure)
    sys.exit(1 if failures else 0)
