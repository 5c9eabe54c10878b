"""ParaView's server under MPI: mpiexec -n R pvserver, and pvpython connected to it runs
cases.py's cases (run_in_paraview.py server:localhost:PORT), each server rank writing
its piece of every output. The assembled outputs must equal one pvbatch process's bit
for bit, and the images of the filters that produce sub-extents must come in R pieces,
none the whole grid (each rank computed its slab):
python3 check_server.py MPIEXEC PVSERVER PVPYTHON PVBATCH PLUGIN DATA_DIR OUT_DIR R
(DF_PVBATCH_PYTHONPATH: python3-paraview's modules)."""
import os
import re
import shutil
import socket
import subprocess
import sys
import threading

from compare_outputs import compare

SLAB_FILTERS = ("linfac_", "voxelizer", "medial", "chamfer_of_masks")

mpiexec, pvserver, pvpython, pvbatch, plugin, data, out = sys.argv[1:8]
ranks = int(sys.argv[8])
here = os.path.dirname(os.path.abspath(__file__))
environment = dict(os.environ, PYTHONPATH=os.environ.get("DF_PVBATCH_PYTHONPATH", ""),
                   OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1")
as_root = ["--allow-run-as-root"] if os.geteuid() == 0 else []
script = os.path.join(here, "run_in_paraview.py")
serial, served = os.path.join(out, "1"), os.path.join(out, "server")
for folder in (serial, served):
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)

# One process, as the reference (the distributed mode's writers and cases).
result = subprocess.run([mpiexec, "-n", "1"] + as_root +
                        [pvbatch, "--symmetric", script, plugin, data, serial, "distributed"],
                        capture_output=True, text=True, timeout=900, env=environment)
if result.returncode != 0:
    print(result.stdout + result.stderr)
    sys.exit(f"FAIL: the one-process run: exit status {result.returncode}")

# The server on a free port; it says when it accepts the connection.
with socket.socket() as probe:
    probe.bind(("localhost", 0))
    port = probe.getsockname()[1]
server = subprocess.Popen([mpiexec, "-n", str(ranks)] + as_root +
                          [pvserver, f"--server-port={port}"],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          env=environment)
log, ready = [], threading.Event()


def read_server():
    for line in server.stdout:
        log.append(line)
        if "Accepting connection" in line:
            ready.set()


threading.Thread(target=read_server, daemon=True).start()
failures = []
if not ready.wait(120):
    server.kill()
    print("".join(log))
    sys.exit("FAIL: pvserver did not start")
client = subprocess.run([pvpython, script, plugin, data, served, f"server:localhost:{port}"],
                        capture_output=True, text=True, timeout=900, env=environment)
if client.returncode != 0:
    failures.append(f"the client: exit status {client.returncode}")
    print(client.stdout + client.stderr)
try:
    server.wait(timeout=120)  # it ends when its client disconnects
except subprocess.TimeoutExpired:
    server.kill()
    failures.append("pvserver did not end after its client left")
print(f"== {ranks} pvserver ranks against one pvbatch process")
failures += compare(serial, served)
for name in sorted(os.listdir(served)):
    if not name.endswith(".pvti") or not name.startswith(SLAB_FILTERS):
        continue
    with open(os.path.join(served, name)) as f:
        text = f.read()
    whole = re.search(r'WholeExtent="([^"]*)"', text).group(1).split()
    pieces = [p.split() for p in re.findall(r'<Piece Extent="([^"]*)"', text)]
    print(f"{name}: pieces {[' '.join(p) for p in pieces]} of {' '.join(whole)}")
    if len(pieces) != ranks or any(p == whole for p in pieces):
        failures.append(f"{name}: not {ranks} slabs")
for failure in failures:
    print("FAIL:", failure)
sys.exit(1 if failures else 0)
