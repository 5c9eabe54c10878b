#!/usr/bin/env bash
# ParaView's Qt GUI with the plugin, under Xvfb: PV_PLUGIN_PATH set as the docs tell a
# user, gui_start.py run at start (every case of cases.py, each output shown and
# rendered). Fails when the script does not finish, or on any error or warning ParaView
# logs (an unknown XML element of the plugin was logged at every start of the GUI).
# Usage: TestParaViewGUI.sh PARAVIEW PLUGIN DATA_DIR OUT_DIR
# (DF_PVBATCH_PYTHONPATH: python3-paraview's modules, unpacked beside the build).
set -uo pipefail
paraview=$1 plugin=$2 data=$3 out=$4
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$out"
mkdir -p "$out"
log="$out/gui.log"
PV_PLUGIN_PATH=$(dirname "$plugin") PYTHONPATH=${DF_PVBATCH_PYTHONPATH:-} \
  DF_GUI_OUT=$out DF_GUI_PLUGIN=$plugin DF_GUI_DATA=$data DF_GUI_SCRIPT=$here/gui_start.py \
  timeout 600 xvfb-run -a -s "-screen 0 1280x1024x24" "$paraview" --script="$here/gui_start.py" \
  >"$log" 2>&1
status=$?
cat "$log"
if [ -f "$out/failed" ]; then
  cat "$out/failed"
  echo "FAIL: the GUI's script failed"
  exit 1
fi
if [ ! -f "$out/done" ] || [ $status -ne 0 ]; then
  echo "FAIL: the GUI did not finish its script (exit status $status)"
  exit 1
fi
"$here/check_log.sh" "$log" "ParaView's GUI" || exit 1
cat "$out/done"
