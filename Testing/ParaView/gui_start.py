"""The plugin in ParaView's Qt GUI, started as a user starts it (TestParaViewGUI.sh runs
`paraview --script=gui_start.py` under Xvfb with PV_PLUGIN_PATH set): every case of
cases.py run through run_in_paraview.py, then every output shown in a render view and
rendered. The GUI cannot be told to quit from --script, so this script leaves it at once
(os._exit) after writing DF_GUI_OUT/done (the outputs shown), or DF_GUI_OUT/failed (the
traceback). ParaView's log goes to stderr, which TestParaViewGUI.sh checks."""
import os
import runpy
import sys
import traceback

out = os.environ["DF_GUI_OUT"]
here = os.path.dirname(os.path.abspath(os.environ["DF_GUI_SCRIPT"]))
try:
    outputs = os.path.join(out, "outputs")
    os.makedirs(outputs, exist_ok=True)
    sys.argv = [os.path.join(here, "run_in_paraview.py"), os.environ["DF_GUI_PLUGIN"],
                os.environ["DF_GUI_DATA"], outputs]
    ran = runpy.run_path(sys.argv[0], run_name="__main__")
    from paraview import simple

    view = simple.GetActiveViewOrCreate("RenderView")
    shown = 0
    for name, proxy in ran["made"].items():
        for port in range(proxy.SMProxy.GetNumberOfOutputPorts()):
            display = simple.Show(simple.OutputPort(proxy, port), view)
            simple.ResetCamera(view)
            simple.Render(view)
            simple.Hide(simple.OutputPort(proxy, port), view)
            shown += display is not None
    with open(os.path.join(out, "done"), "w") as done:
        done.write("%d outputs of %d cases shown\n" % (shown, len(ran["made"])))
    sys.stdout.flush()
    os._exit(0)
except BaseException:  # noqa: B036 (anything that would leave the GUI open)
    with open(os.path.join(out, "failed"), "w") as failed:
        failed.write(traceback.format_exc())
    os._exit(1)
