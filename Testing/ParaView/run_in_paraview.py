"""Runs cases.py's cases through the ParaView plugin:
pvbatch [--symmetric] run_in_paraview.py PLUGIN DATA_DIR OUT_DIR [distributed]
pvpython run_in_paraview.py PLUGIN DATA_DIR OUT_DIR server:HOST:PORT

Each output port goes to OUT_DIR/<case>_<port>.<extension>. With "distributed" (under
mpiexec ... pvbatch --symmetric), the outputs are written by ParaView's parallel writers
(.pvti, .pvtp, .pvtu: one piece a rank), and every rank prints the extent of each image it
computed, and writes the extent and a digest of each piece of a case's "pieces_port" to
OUT_DIR/<case>.pieces.<rank>. With "server:HOST:PORT", pvpython connects to a pvserver there (mpiexec -n R
pvserver) and the server's ranks run the cases and write them likewise."""
import hashlib
import os
import sys

# pvpython run from python3-paraview unpacked elsewhere puts the system's dist-packages
# (python3-vtk9's vtkmodules, another VTK) before PYTHONPATH: take ParaView's.
sys.path = [p for p in sys.path if p.rstrip("/") != "//lib/python3/dist-packages"]

from paraview import simple  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from paraview.modules.vtkRemotingCore import vtkProcessModule  # noqa: E402

plugin, data_dir, out_dir = sys.argv[1:4]
mode = sys.argv[4] if len(sys.argv) > 4 else ""
server = mode.startswith("server:")
distributed = mode == "distributed" or server
if server:
    _, host, port = mode.split(":")
    simple.Connect(host, int(port))
# The plugin's filters become functions of paraview.simple.
simple.LoadPlugin(plugin, remote=True)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cases import CASES  # noqa: E402

process = vtkProcessModule.GetProcessModule()
rank, ranks = process.GetPartitionId(), process.GetNumberOfLocalPartitions()
made = {}
for case in CASES:
    if (case.get("distributed_only") and not distributed) or (
            case.get("serial_only") and distributed):
        continue
    inputs = {}
    for name, source in case["inputs"].items():
        if source.startswith(("partitioned:", "ghosted:")):
            # Global ids while the mesh is whole (on rank 0: a one-piece file gives the
            # other ranks nothing), then a part of it on every rank; "ghosted:" adds a
            # layer of ghost cells, and marks the copies of points that another rank
            # owns (VTK's ghost points).
            kind, file_name = source.split(":")
            reader = simple.XMLPolyDataReader(FileName=[os.path.join(data_dir, file_name)])
            ids = simple.GenerateGlobalIds(Input=reader)
            parts = simple.RedistributeDataSet(Input=ids)
            inputs[name] = simple.ExtractSurface(Input=parts)
            if kind == "ghosted":
                inputs[name] = simple.GhostCellsGenerator(Input=inputs[name])
        elif ":" in source:
            earlier, port = source.split(":")
            inputs[name] = simple.OutputPort(made[earlier], int(port))
        else:
            inputs[name] = simple.XMLPolyDataReader(FileName=[os.path.join(data_dir, source)])
    proxy = getattr(simple, case["filter"])(**inputs, **case["properties"])
    made[case["name"]] = proxy
    for port, extension in case["outputs"].items():
        if distributed:
            # One piece a rank, assembled by the reader of the .pvti/.pvtp.
            path = os.path.join(out_dir, f"{case['name']}_{port}.p{extension}")
            write = {"vti": simple.XMLPImageDataWriter, "vtp": simple.XMLPPolyDataWriter,
                     "vtu": simple.XMLPUnstructuredGridWriter}[extension]
            writer = write(Input=simple.OutputPort(proxy, port), FileName=path)
            writer.UpdatePipeline()
            if extension == "vti" and not server:
                output = proxy.GetClientSideObject().GetOutputDataObject(port)
                print(f"{case['name']}: rank {rank} of {ranks} computed extent "
                      f"{output.GetExtent()}", flush=True)
            simple.Delete(writer)
        else:
            path = os.path.join(out_dir, f"{case['name']}_{port}.{extension}")
            simple.SaveData(path, proxy=simple.OutputPort(proxy, port))
            print(f"{case['name']}: wrote {path}")
    if "pieces_port" in case and distributed and not server:
        # A vtkPartitionedDataSet: this rank's pieces, by extent and a digest of their
        # arrays, to OUT_DIR/<case>.pieces.<rank> (check_distributed.py compares them with
        # one rank's; a file, as the ranks' standard outputs run together).
        output = proxy.GetClientSideObject().GetOutputDataObject(case["pieces_port"])
        with open(os.path.join(out_dir, f"{case['name']}.pieces.{rank}"), "w") as listing:
            for p in range(output.GetNumberOfPartitions()):
                piece = output.GetPartition(p)
                digest = hashlib.sha1()
                data = piece.GetPointData()
                for k in range(data.GetNumberOfArrays()):
                    digest.update(data.GetArray(k).GetName().encode())
                    digest.update(vtk_to_numpy(data.GetArray(k)).tobytes())
                listing.write(f"{piece.GetExtent()} {digest.hexdigest()}\n")
