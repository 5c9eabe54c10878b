"""Runs cases.py's cases through the ParaView plugin: pvbatch run_in_paraview.py PLUGIN
DATA_DIR OUT_DIR. Each output port goes to OUT_DIR/<case>_<port>.<extension>."""
import os
import sys

from paraview import simple

plugin, data_dir, out_dir = sys.argv[1:4]
# The plugin's filters become functions of paraview.simple.
simple.LoadPlugin(plugin, remote=True)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cases import CASES  # noqa: E402

made = {}
for case in CASES:
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
        path = os.path.join(out_dir, f"{case['name']}_{port}.{extension}")
        simple.SaveData(path, proxy=simple.OutputPort(proxy, port))
        print(f"{case['name']}: wrote {path}")
