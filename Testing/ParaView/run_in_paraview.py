"""Runs cases.py's cases through the ParaView plugin:
pvbatch [--symmetric] run_in_paraview.py PLUGIN DATA_DIR OUT_DIR [distributed]

Each output port goes to OUT_DIR/<case>_<port>.<extension>. With "distributed" (under
mpiexec ... pvbatch --symmetric), only the image outputs are written, by ParaView's
parallel writer (.pvti: one piece a rank), and every rank prints the extent it computed."""
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
    if distributed and "vti" not in case["outputs"].values():
        continue
    inputs = {}
    for name, source in case["inputs"].items():
        if ":" in source:
            earlier, port = source.split(":")
            inputs[name] = simple.OutputPort(made[earlier], int(port))
        else:
            inputs[name] = simple.XMLPolyDataReader(FileName=[os.path.join(data_dir, source)])
    proxy = getattr(simple, case["filter"])(**inputs, **case["properties"])
    made[case["name"]] = proxy
    for port, extension in case["outputs"].items():
        if distributed and extension != "vti":
            continue
        if distributed:
            path = os.path.join(out_dir, f"{case['name']}_{port}.pvti")
            writer = simple.XMLPImageDataWriter(Input=simple.OutputPort(proxy, port),
                                                FileName=path)
            writer.UpdatePipeline()
            extent = proxy.GetClientSideObject().GetOutputDataObject(port).GetExtent()
            print(f"{case['name']}: rank {rank} of {ranks} computed extent {extent}", flush=True)
            simple.Delete(writer)
        else:
            path = os.path.join(out_dir, f"{case['name']}_{port}.{extension}")
            simple.SaveData(path, proxy=simple.OutputPort(proxy, port))
            print(f"{case['name']}: wrote {path}")
