"""Runs cases.py's cases through the system-VTK build's Python package (the same filters
as plain VTK classes): python3 run_in_vtk.py DATA_DIR OUT_DIR."""
import os
import sys

from vtkmodules.vtkIOXML import (vtkXMLImageDataWriter, vtkXMLPolyDataReader,
                                 vtkXMLPolyDataWriter, vtkXMLUnstructuredGridWriter)

import vtkdistancefields

data_dir, out_dir = sys.argv[1:3]
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cases import CASES, INPUT_PORTS  # noqa: E402

made = {}
for case in CASES:
    if case.get("distributed_only"):
        continue
    algorithm = getattr(vtkdistancefields, "vtk" + case["filter"])()
    for name, source in case["inputs"].items():
        if ":" in source:
            earlier, port = source.split(":")
            connection = made[earlier].GetOutputPort(int(port))
        else:
            reader = vtkXMLPolyDataReader()
            reader.SetFileName(os.path.join(data_dir, source))
            connection = reader.GetOutputPort()
        algorithm.SetInputConnection(INPUT_PORTS[name], connection)
    for name, value in case["properties"].items():
        if isinstance(value, str):
            getattr(algorithm, f"Set{name}To{value}")()
        elif isinstance(value, list):
            getattr(algorithm, f"Set{name}")(*value)
        else:
            getattr(algorithm, f"Set{name}")(value)
    made[case["name"]] = algorithm
    for port, extension in case["outputs"].items():
        algorithm.Update(port)
        writer = {"vti": vtkXMLImageDataWriter, "vtp": vtkXMLPolyDataWriter,
                  "vtu": vtkXMLUnstructuredGridWriter}[extension]()
        path = os.path.join(out_dir, f"{case['name']}_{port}.{extension}")
        writer.SetFileName(path)
        writer.SetInputData(algorithm.GetOutputDataObject(port))
        if not writer.Write():
            sys.exit(f"{case['name']}: could not write {path}")
        print(f"{case['name']}: wrote {path}")
