"""Runs cases.py's cases through the ParaView plugin:
pvbatch [--symmetric] run_in_paraview.py PLUGIN DATA_DIR OUT_DIR [distributed]

Each output port goes to OUT_DIR/<case>_<port>.<extension>. With "distributed" (under
mpiexec ... pvbatch --symmetric), the outputs are written by ParaView's parallel writers
(.pvti, .pvtp: one piece a rank), and every rank prints the extent of each image it
computed."""
import os
import sys

from paraview import simple
from paraview.modules.vtkRemotingCore import vtkProcessModule

plugin, data_dir, out_dir = sys.argv[1:4]
distributed = sys.argv[4:5] == ["distributed"]
# The plugin's filters become functions of paraview.simple.
simple.LoadPlugin(plugin, remote=True)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cases import CASES  # noqa: E402

process = vtkProcessModule.GetProcessModule()
rank, ranks = process.GetPartitionId(), process.GetNumberOfLocalPartitions()
made = {}
for case in CASES:
    if case.get("distributed_only") and not distributed:
        continue
    inputs = {}
    for name, source in case["inputs"].items():
        if source.startswith("partitioned:"):
            # Global ids while the mesh is whole (on rank 0: a one-piece file gives the
            # other ranks nothing), then a part of it on every rank.
            reader = simple.XMLPolyDataReader(FileName=[os.path.join(data_dir, source[12:])])
            ids = simple.GenerateGlobalIds(Input=reader)
            parts = simple.RedistributeDataSet(Input=ids)
            inputs[name] = simple.ExtractSurface(Input=parts)
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
            write = (simple.XMLPImageDataWriter if extension == "vti"
                     else simple.XMLPPolyDataWriter)
            writer = write(Input=simple.OutputPort(proxy, port), FileName=path)
            writer.UpdatePipeline()
            output = proxy.GetClientSideObject().GetOutputDataObject(port)
            if extension == "vti":
                print(f"{case['name']}: rank {rank} of {ranks} computed extent "
                      f"{output.GetExtent()}", flush=True)
            simple.Delete(writer)
        else:
            path = os.path.join(out_dir, f"{case['name']}_{port}.{extension}")
            simple.SaveData(path, proxy=simple.OutputPort(proxy, port))
            print(f"{case['name']}: wrote {path}")
