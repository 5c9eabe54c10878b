"""ParaView's server under MPI: mpiexec -n R pvserver, and pvpython connected to it runs
cases.py's cases (run_in_paraview.py server:localhost:PORT), each server rank writing
its piece of every output. The assembled outputs must equal one pvbatch process's bit
for bit, and the images of the filters that produce sub-extents must come in R pieces,
none the whole grid (each rank computed its slab). Then the representation "Segmented
Distance Volume" drawn by the server's ranks must give one process's picture
(server_representation.py; needs an X server, as the suite's xvfb-run gives):
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

SLAB_FILTERS = ("linfac_", "voxelizer", "medial", "chamfer_of_masks", "segmented", "blend")

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

def serve(client_command):
    """Runs `client_command` (given the port as its last argument) against a new server
    of `ranks` ranks on a free port; the failures."""
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
    if not ready.wait(120):
        server.kill()
        print("".join(log))
        return ["pvserver did not start"]
    failures = []
    client = subprocess.run(client_command(port), capture_output=True, text=True, timeout=900,
                            env=environment)
    print(client.stdout, end="")
    if client.returncode != 0:
        failures.append(f"{os.path.basename(client_command(port)[1])}: exit status "
                        f"{client.returncode}")
        print(client.stderr)
    try:
        server.wait(timeout=120)  # it ends when its client disconnects
    except subprocess.TimeoutExpired:
        server.kill()
        failures.append("pvserver did not end after its client left")
    return failures


failures = serve(lambda port: [pvpython, script, plugin, data, served,
                               f"server:localhost:{port}"])
print(f"== {ranks} pvserver ranks against one pvbatch process")
# Poly data and unstructured grids of several pieces in canonical order.
failures += compare(serial, served, canonical_points=True)
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
# The volume mapper's representation drawn by the server's ranks, composited by ParaView,
# against one process.
print(f"== the representation Segmented Distance Volume on {ranks} pvserver ranks")
failures += serve(lambda port: [pvpython, os.path.join(here, "server_representation.py"),
                                plugin, os.path.join(data, "bunny_small.vtp"),
                                os.path.join(out, "server_representation.png"), str(port)])
for failure in failures:
    print("FAIL:", failure)
sys.exit(1 if failures else 0)
