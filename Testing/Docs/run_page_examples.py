#!/usr/bin/env python3
"""Runs every Python block of the docs pages as a user who pastes it would: each block
alone, in a fresh interpreter, in an empty folder where `Testing/Data` leads to the
bundled meshes; it must exit 0 and print something. Blocks that start with
`from paraview` run with pvbatch (the plugin's suite: the LoadPlugin path replaced by the
built plugin's), the others with this Python and the build's package.

usage: run_page_examples.py DOCS_DIR TESTING_DIR WORK_DIR [--paraview PVBATCH PLUGIN]
(DF_PVBATCH_PYTHONPATH: python3-paraview's modules, for pvbatch only)
"""
import glob
import os
import re
import shutil
import subprocess
import sys

BLOCK = re.compile(r"^```python\n(.*?)^```", re.S | re.M)
PLUGIN = re.compile(r'LoadPlugin\("[^"]*DistanceFields\.so"')


def main():
    docs, testing, work = sys.argv[1:4]
    paraview = sys.argv[4:] and sys.argv[4] == "--paraview"
    pvbatch, plugin = (sys.argv[5], sys.argv[6]) if paraview else (None, None)
    ran, failures = 0, []
    for page in sorted(glob.glob(os.path.join(docs, "*.md"))):
        blocks = BLOCK.findall(open(page, encoding="utf-8").read())
        for index, code in enumerate(blocks):
            if code.lstrip().startswith("from paraview") != bool(paraview):
                continue
            name = "%s-%d" % (os.path.basename(page)[:-3], index)
            folder = os.path.join(work, name)
            shutil.rmtree(folder, ignore_errors=True)
            os.makedirs(folder)
            os.symlink(os.path.abspath(testing), os.path.join(folder, "Testing"))
            if paraview:
                code = PLUGIN.sub('LoadPlugin("%s"' % plugin, code)
            script = os.path.join(folder, "example.py")
            with open(script, "w", encoding="utf-8") as f:
                f.write(code)
            command = [pvbatch, script] if paraview else [sys.executable, script]
            environment = dict(os.environ)
            if paraview:
                environment["PYTHONPATH"] = os.environ.get("DF_PVBATCH_PYTHONPATH", "")
            run = subprocess.run(command, cwd=folder, capture_output=True, text=True,
                                 timeout=300, env=environment)
            ran += 1
            output = (run.stdout + run.stderr).strip()
            print("== %s (exit %d)\n%s" % (name, run.returncode, output[-2000:]))
            if run.returncode != 0:
                failures.append("%s: exit status %d" % (name, run.returncode))
            elif not run.stdout.strip() and sorted(os.listdir(folder)) == ["Testing", "example.py"]:
                failures.append("%s: printed and wrote nothing" % name)
    if ran == 0:
        failures.append("no Python block found in %s" % docs)
    for failure in failures:
        print("FAIL: " + failure)
    print("%d blocks run, %d failed" % (ran, len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
