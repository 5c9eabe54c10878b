#!/usr/bin/env bash
# Under an address-space limit (ulimit -v), a grid too large for it is refused before
# anything is allocated, by vtkdf and through the Python API (the interpreter survives),
# with the limit named; a grid that fits still runs.
# usage: TestMemoryLimit.sh VTKDF DATA_DIR OUT_DIR   (PYTHONPATH set to the module)
set -uo pipefail
vtkdf=$1 data=$2 out=$3
mkdir -p "$out"
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
ulimit -v 4000000 # 4 GB of address space

"$vtkdf" linfac "$data/teapot.vtp" -o "$out/big.vti" --resolution 1500 2> "$out/big.err"
status=$?
[ $status -eq 1 ] || fail "vtkdf on a 1500^3 grid: exit status $status, expected 1"
grep -q "RLIMIT_AS" "$out/big.err" || fail "vtkdf does not name RLIMIT_AS: $(grep -o 'ERR|.*' "$out/big.err" | head -2)"

"$vtkdf" linfac "$data/teapot.vtp" -o "$out/small.vti" --resolution 32 2> "$out/small.err" ||
  fail "vtkdf on a 32^3 grid failed under the limit"

/usr/bin/python3 - "$data/teapot.vtp" <<'PY' || fail "the Python check failed"
import sys
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkdistancefields import vtkLinearFactorDistanceField
reader = vtkXMLPolyDataReader()
reader.SetFileName(sys.argv[1])
reader.Update()
errors = []
@calldata_type(VTK_STRING)
def on_error(_o, _e, text):
    errors.append(text)
f = vtkLinearFactorDistanceField()
f.AddObserver("ErrorEvent", on_error)
f.SetInputData(reader.GetOutput())
f.SetBackendToCPU()
f.ExplicitGridOn()
f.SetGridOrigin(0, 0, 0)
f.SetGridSpacing(0.01, 0.01, 0.01)
f.SetGridDimensions(2000, 2000, 2000)
f.SetMemoryLimit(1e13)  # asked for, but the address space cannot give it
f.Update()
ok = f.GetErrorCode() != 0 and f.GetOutput().GetNumberOfPoints() == 0 and any("RLIMIT_AS" in e for e in errors)
print("python:", "ok" if ok else "FAIL", errors[-1:] if errors else "no error")
sys.exit(0 if ok else 1)
PY
echo "$failures failures"
[ $failures -eq 0 ]
