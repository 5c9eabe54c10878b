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
                                 vtkXMLPolyDataReader, vtkXMLPPolyDataReader,
                                 vtkXMLPUnstructuredGridReader,
                                 vtkXMLUnstructuredGridReader)


READERS = {".vti": vtkXMLImageDataReader, ".vtp": vtkXMLPolyDataReader,
           ".vtu": vtkXMLUnstructuredGridReader, ".pvti": vtkXMLPImageDataReader,
           ".pvtp": vtkXMLPPolyDataReader, ".pvtu": vtkXMLPUnstructuredGridReader}


def read(path):
    """A .vti, .vtp or .vtu, or a .pvti, .pvtp or .pvtu assembled from its pieces."""
    reader = READERS[os.path.splitext(path)[1]]()
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


def cell_arrays(data):
    """A point set's cells as (tag, offsets, connectivity) triples: a poly data's four
    kinds, an unstructured grid's cells (tagged with their types)."""
    if data.IsA("vtkUnstructuredGrid"):
        cells = data.GetCells()
        return [(vtk_to_numpy(data.GetCellTypesArray()).astype(np.int64),
                 vtk_to_numpy(cells.GetOffsetsArray()).astype(np.int64),
                 vtk_to_numpy(cells.GetConnectivityArray()).astype(np.int64))]
    found = []
    for tag, cells in enumerate((data.GetVerts(), data.GetLines(), data.GetPolys(),
                                 data.GetStrips())):
        offsets = vtk_to_numpy(cells.GetOffsetsArray()).astype(np.int64)
        found.append((np.full(max(len(offsets) - 1, 0), tag, np.int64), offsets,
                      vtk_to_numpy(cells.GetConnectivityArray()).astype(np.int64)))
    return found


def geometry(data):
    if data.IsA("vtkImageData"):
        return (tuple(data.GetExtent()), tuple(data.GetOrigin()), tuple(data.GetSpacing()))
    parts = [vtk_to_numpy(data.GetPoints().GetData()).tobytes() if data.GetPoints() else b""]
    for tags, offsets, connectivity in cell_arrays(data):
        parts += [tags.tobytes(), offsets.tobytes(), connectivity.tobytes()]
    return tuple(parts)


# What a partition adds to a piece, not the filter: ghost flags, original ids.
PARTITION_ARRAYS = ("vtkGhostType", "vtkOriginalCellIds", "vtkOriginalPointIds")


def row_bytes(values, count, rounded=False):
    """Each of `count` rows of an array (any components) as bytes (doubles rounded to
    float when `rounded`)."""
    if count == 0:
        return np.zeros((0, 0), np.uint8)
    if rounded and values.dtype == np.float64:
        values = values.astype(np.float32)
    values = np.ascontiguousarray(values).reshape(count, -1)
    return values.view(np.uint8).reshape(count, -1)


def canonical(data, rounded=False):
    """A point set in an order that does not depend on how it was split among ranks: its
    cells but ghost cells (a piece's copies of its neighbours'), each as its type, its
    points (coordinates and point data) in the cell's order and its cell data, sorted and
    counted once; and the points those cells use (all the points but ghost ones where
    there are no cells), sorted and counted once. Arrays a partition adds
    (PARTITION_ARRAYS) are left out. With `rounded`, doubles count as floats."""
    count = data.GetNumberOfPoints()
    point_data, cell_data = data.GetPointData(), data.GetCellData()
    point_names = sorted(n for n in (point_data.GetArrayName(i)
                                     for i in range(point_data.GetNumberOfArrays()))
                         if n not in PARTITION_ARRAYS)
    cell_names = sorted(n for n in (cell_data.GetArrayName(i)
                                    for i in range(cell_data.GetNumberOfArrays()))
                        if n not in PARTITION_ARRAYS)
    columns = [row_bytes(vtk_to_numpy(data.GetPoints().GetData()), count, rounded)] + [
        row_bytes(vtk_to_numpy(point_data.GetArray(name)), count, rounded)
        for name in point_names]
    rows = np.hstack(columns) if count else np.zeros((0, 0), np.uint8)
    keys = [bytes(row) for row in rows]
    ghost_cells = cell_data.GetArray("vtkGhostType")
    ghost_cells = vtk_to_numpy(ghost_cells) if ghost_cells else None
    cells, used, first = set(), set(), 0
    for tags, offsets, connectivity in cell_arrays(data):
        values = [row_bytes(vtk_to_numpy(cell_data.GetArray(name))[first:first + len(tags)],
                            len(tags), rounded) for name in cell_names]
        for c in range(len(tags)):
            if ghost_cells is not None and ghost_cells[first + c] & 1:
                continue
            ids = connectivity[offsets[c]:offsets[c + 1]].tolist()
            used.update(ids)
            cells.add((int(tags[c]), tuple(keys[i] for i in ids),
                       b"".join(bytes(v[c]) for v in values)))
        first += len(tags)
    if first == 0:
        ghost_points = point_data.GetArray("vtkGhostType")
        ghost_points = vtk_to_numpy(ghost_points) if ghost_points else np.zeros(count, int)
        used = [i for i in range(count) if not ghost_points[i] & 1]
    return tuple(sorted(set(keys[i] for i in used))), tuple(sorted(cells))


def outputs(folder):
    """The output files of a folder by name without extension (a .pvti's pieces are in
    its own subfolder)."""
    return {os.path.splitext(name)[0]: os.path.join(folder, name)
            for name in os.listdir(folder) if os.path.splitext(name)[1] in READERS}


def compare(first_folder, second_folder, canonical_points=False):
    """Prints each output's comparison; returns the failures. With `canonical_points`,
    poly data and unstructured grids are compared in canonical order (the points and
    cells that several ranks wrote, each once: canonical())."""
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
        arrays_a, arrays_b = arrays(a), arrays(b)
        failed = len(failures)
        # An unstructured grid (a clip's) in canonical order always, its doubles as
        # floats: VTK's versions order a clip's points and cells differently, and its
        # clip interpolates a cut edge from either end, by the order of the points
        # (which a partition changes), so that the new points agree to rounding.
        grid = a.IsA("vtkUnstructuredGrid")
        in_order = (canonical_points or grid) and not a.IsA("vtkImageData")
        if in_order:
            if canonical(a, rounded=grid) != canonical(b, rounded=grid):
                failures.append(f"{name}: the points, cells or their arrays differ")
        elif geometry(a) != geometry(b):
            failures.append(f"{name}: the grids or geometries differ")
        if in_order:
            arrays_a = {k: v for k, v in arrays_a.items() if k[1] not in PARTITION_ARRAYS}
            arrays_b = {k: v for k, v in arrays_b.items() if k[1] not in PARTITION_ARRAYS}
        if sorted(arrays_a) != sorted(arrays_b):
            failures.append(f"{name}: arrays {sorted(arrays_a)} and {sorted(arrays_b)}")
        # In canonical order the points' and cells' arrays were compared with them.
        compared = [key for key in arrays_a if key in arrays_b and
                    not (in_order and key[0] != "field")]
        differing = [key[1] for key in compared if arrays_a[key] != arrays_b[key]]
        if differing:
            failures.append(f"{name}: arrays differ: {differing}")
        print(f"{name}: {a.GetNumberOfPoints()} points, {len(arrays_a)} arrays "
              f"({', '.join(sorted(key[1] for key in arrays_a))}): "
              f"{'differ' if len(failures) > failed else 'equal bit for bit'}")
    return failures


if __name__ == "__main__":
    failures = compare(sys.argv[1], sys.argv[2])
    for failure in failures:
        print("FAIL:", failure)
    sys.exit(1 if failures else 0)
