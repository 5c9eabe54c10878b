"""Runs bad_values.py under pvbatch and checks that each bad value gave the filter's own
error and an empty output, that an unknown enumeration name raised ValueError in the
client, that a good value afterwards works, and that pvbatch exited cleanly:
python3 check_bad_values.py PVBATCH PLUGIN MESH (DF_PVBATCH_PYTHONPATH: python3-paraview's
modules, for pvbatch only)."""
import os
import subprocess
import sys

pvbatch, plugin, mesh = sys.argv[1:4]
script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bad_values.py")
# python3-paraview's modules for pvbatch only: they conflict with the system's VTK.
environment = dict(os.environ, PYTHONPATH=os.environ.get("DF_PVBATCH_PYTHONPATH", ""))
run = subprocess.run([pvbatch, script, plugin, mesh], capture_output=True, text=True,
                     timeout=300, env=environment)
output = run.stdout + run.stderr
print(output)
expected = [
    "nan spacing: 0 points",
    "GridSpacing must be finite and positive; it is (nan, 1, 1).",
    "resolution 0: 0 points",
    "Resolution must be at least 2 samples; it is 0.",
    "unknown name: ValueError (Bogus is not a valid value for attribute SignMode.)",
    "SignMode 7: 0 points",
    "SignMode must be 0 (Unsigned), 1 (PseudoNormal) or 2 (WindingNumber); it is 7.",
    "SignMode 1: 448 points",
]
missing = [line for line in expected if line not in output]
for line in missing:
    print("FAIL: missing:", line)
if run.returncode != 0:
    print(f"FAIL: pvbatch exited with {run.returncode}")
sys.exit(1 if missing or run.returncode != 0 else 0)
