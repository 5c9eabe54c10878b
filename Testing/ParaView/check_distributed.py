"""Runs cases.py's image cases under mpiexec -n R pvbatch --symmetric for R = 1 and each
R given, and checks that the assembled .pvti outputs of R ranks equal the 1-rank outputs
bit for bit (the mesh whole, or partitioned across the ranks with global ids), that the
filters that compute a piece (the linear factorization, the voxelizer, the medial axis,
the chamfer transform with a layer limit, the segmented field and its blend) computed only a slab on
each rank (the extents every rank prints), that the sparse band's pieces of R ranks are
one rank's, each on one rank, and that a mesh
partitioned without global ids is refused:
python3 check_distributed.py MPIEXEC PVBATCH PLUGIN DATA_DIR OUT_DIR R...
(DF_PVBATCH_PYTHONPATH: python3-paraview's modules)."""
import ast
import os
import re
import shutil
import subprocess
import sys

from compare_outputs import compare

SLAB_FILTERS = ("linfac_", "voxelizer", "medial", "chamfer_of_masks", "segmented", "blend")

mpiexec, pvbatch, plugin, data, out = sys.argv[1:6]
rank_counts = [int(r) for r in sys.argv[6:]]
here = os.path.dirname(os.path.abspath(__file__))
environment = dict(os.environ, PYTHONPATH=os.environ.get("DF_PVBATCH_PYTHONPATH", ""),
                   OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1")


def run(ranks):
    folder = os.path.join(out, str(ranks))
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    command = [mpiexec, "-n", str(ranks)]
    if os.geteuid() == 0:
        command.append("--allow-run-as-root")
    command += [pvbatch, "--symmetric", os.path.join(here, "run_in_paraview.py"), plugin,
                data, folder, "distributed"]
    result = subprocess.run(command, capture_output=True, text=True, timeout=900,
                            env=environment)
    if result.returncode != 0:
        print(result.stdout + result.stderr)
        sys.exit(f"FAIL: {ranks} ranks: exit status {result.returncode}")
    extents, pieces = {}, {}
    # The ranks share stdout: their lines may run together.
    for case, rank, extent in re.findall(
            r"([a-z0-9_]+): rank (\d+) of \d+ computed extent (\([-0-9, ]+\))", result.stdout):
        extents.setdefault(case, {})[int(rank)] = ast.literal_eval(extent)
    for name in os.listdir(folder):
        if ".pieces." in name:
            case, _, rank = name.split(".")
            with open(os.path.join(folder, name)) as listing:
                for line in listing:
                    extent, digest = line.rsplit(" ", 1)
                    pieces.setdefault(case, []).append((int(rank), extent, digest.strip()))
    return folder, extents, pieces


def compare_pieces(serial_pieces, pieces, ranks):
    """The ranks' pieces of each case with pieces_port: together one rank's (the same
    extents and digests), each on one rank, no rank with all of them."""
    found = []
    for case, alone in sorted(serial_pieces.items()):
        mine = pieces.get(case, [])
        expected = sorted((extent, digest) for _, extent, digest in alone)
        got = sorted((extent, digest) for _, extent, digest in mine)
        per_rank = [sum(1 for r, _, _ in mine if r == rank) for rank in range(ranks)]
        print(f"{case}: {len(expected)} pieces on 1 rank, {per_rank} on {ranks}")
        if got != expected:
            found.append(f"{case}: the ranks' pieces are not one rank's")
        if max(per_rank) == len(expected):
            found.append(f"{case}: one rank computed every piece")
    return found


failures = []
serial, serial_extents, serial_pieces = run(1)
if "sparse" not in serial_pieces:
    failures.append("no pieces were reported for the sparse band")
for ranks in rank_counts:
    folder, extents, pieces = run(ranks)
    print(f"== {ranks} ranks against 1")
    for case, by_rank in sorted(extents.items()):
        whole = serial_extents[case][0]
        print(f"{case}: " + ", ".join(f"rank {r} {by_rank[r]}" for r in sorted(by_rank)))
        if len(by_rank) != ranks:
            failures.append(f"{case}: {len(by_rank)} of {ranks} ranks reported")
        if case.startswith(SLAB_FILTERS) and any(e == whole for e in by_rank.values()):
            failures.append(f"{case}: a rank computed the whole extent {whole}")
    # Poly data and unstructured grids of several pieces in canonical order: a point or
    # cell that two ranks wrote counts once.
    failures += [f"{ranks} ranks: {f}" for f in compare(serial, folder, canonical_points=True)]
    failures += [f"{ranks} ranks: {f}" for f in compare_pieces(serial_pieces, pieces, ranks)]
# A mesh partitioned without global ids is refused on every rank, with the message.
command = [mpiexec, "-n", "2"] + (["--allow-run-as-root"] if os.geteuid() == 0 else [])
result = subprocess.run(command + [pvbatch, "--symmetric",
                                   os.path.join(here, "refuse_partitioned.py"), plugin],
                        capture_output=True, text=True, timeout=300, env=environment)
output = result.stdout + result.stderr
refused = (result.returncode == 0 and output.count("output has 0 points") == 2 and
           "is partitioned across the 2 ranks" in output)
print(f"== a partitioned mesh without global ids: {'refused' if refused else 'NOT refused'}")
if not refused:
    print(output)
    failures.append("a partitioned mesh without global ids was not refused on both ranks")
for failure in failures:
    print("FAIL:", failure)
sys.exit(1 if failures else 0)
