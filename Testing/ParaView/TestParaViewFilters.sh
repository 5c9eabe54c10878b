#!/usr/bin/env bash
# Runs cases.py's cases through the plugin (pvbatch) and through the system-VTK build's
# Python package, then compares the outputs bit for bit. Fails on any error or warning
# that ParaView logs while it loads the plugin and runs the filters (none of the cases is
# a bad input: those are ParaView.BadValues').
# Usage: TestParaViewFilters.sh PVBATCH PLUGIN DATA_DIR OUT_DIR SYSTEM_PYTHON SYSTEM_PYTHONPATH
# (DF_PVBATCH_PYTHONPATH: python3-paraview's modules, for pvbatch only).
set -euo pipefail
pvbatch=$1 plugin=$2 data=$3 out=$4 python=$5 system_pythonpath=$6
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"
mkdir -p "$out/paraview" "$out/vtk"
log="$out/paraview.log"
PYTHONPATH=${DF_PVBATCH_PYTHONPATH:-} "$pvbatch" "$here/run_in_paraview.py" "$plugin" "$data" \
  "$out/paraview" >"$log" 2>&1 || { cat "$log"; exit 1; }
cat "$log"
"$here/check_log.sh" "$log" "ParaView, while running the filters," || exit 1
PYTHONPATH=$system_pythonpath "$python" "$here/run_in_vtk.py" "$data" "$out/vtk"
"$python" "$here/compare_outputs.py" "$out/paraview" "$out/vtk"
