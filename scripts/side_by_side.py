"""Reference half of scripts/bench-side-by-side (run it through that script).

Runs the ecam timing binary, then times the references on the data it
wrote, and prints one JSON object per line: case, ecam_ns, reference,
reference_ns, ratio (= ecam / reference). Lookup lines also carry the
largest difference between ecam's and numpy's results on the same queries
(both interpolate the same straight lines, so it is rounding only).
"""

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

import numpy as np


def median_ns_per_query(run, queries, reps):
    times = []
    for _ in range(reps):
        start = time.perf_counter_ns()
        run()
        times.append((time.perf_counter_ns() - start) / queries)
    times.sort()
    return times[len(times) // 2]


def emit(line):
    print(json.dumps(line), flush=True)


def with_reference(line, name, ns, **extra):
    line = dict(line)
    line["reference"] = name
    line["reference_ns"] = round(ns, 2)
    line["ratio"] = round(line["ecam_ns"] / ns, 3)
    line.update(extra)
    return line


def peer_skip_reason():
    """Why the PLCopen peer cannot run here, or None when it can."""
    try:
        import pyplcopen  # noqa: F401  (optional peer)
    except ImportError as e:
        return f"pyplcopen is not installed ({e})"
    # Cam helpers that only build or load tables do not run a cam.
    helpers = {"generate_cam_law", "load_cam_table_csv"}
    names = [n for n in dir(pyplcopen) if "cam" in n.lower() and n not in helpers]
    names += [n for n in dir(getattr(pyplcopen, "AxisSim", object)) if "cam" in n.lower()]
    if not names:
        from importlib.metadata import version as installed

        version = installed("pyplcopen")
        return (
            f"pyplcopen ({version}) exposes no MC_CamIn to Python: its module offers "
            "AxisSim moves, streaming and generate_cam_law/load_cam_table_csv only; "
            "its C++ MC_CamIn is not reachable from the wheel"
        )
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--ecam", required=True, help="the side_by_side example binary")
    parser.add_argument("--data", required=True, help="where the binary writes the data")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    data = Path(args.data)
    command = [args.ecam, "--data", str(data)] + (["--quick"] if args.quick else [])
    ecam = subprocess.run(command, check=True, capture_output=True, text=True)
    lines = {}
    for raw in ecam.stdout.splitlines():
        line = json.loads(raw)
        lines[line["case"]] = line

    table = np.loadtxt(data / "table.csv", delimiter=",", dtype=np.int64)
    xp = table[:, 0].astype(np.float64)
    fp = table[:, 1].astype(np.float64)
    reps = 40 if args.quick else 300

    def lookup(case, name, reps):
        queries = np.fromfile(data / f"{name}.f64", dtype="<f8")
        ours = np.fromfile(data / f"{name}.ecam.f64", dtype="<f8")
        theirs = np.interp(queries, xp, fp)
        diff = float(np.max(np.abs(theirs - ours)))
        ns = median_ns_per_query(lambda: np.interp(queries, xp, fp), len(queries), reps)
        emit(with_reference(lines[case], "numpy.interp " + np.__version__, ns, max_abs_diff=diff))

    lookup("lookup-sequential", "sequential", reps)
    lookup("lookup-random", "random", reps)
    lookup("lookup-batch-1M", "batch", 5 if args.quick else 21)
    for case in ("tick-1", "tick-64", "tick-worst"):
        emit(lines[case])
    reason = peer_skip_reason()
    peer = dict(lines["tick-peer"])
    peer["reference"] = "pyplcopen MC_CamIn"
    peer["reference_ns"] = None
    peer["ratio"] = None
    peer["skipped"] = reason or "pyplcopen offers a cam binding this script does not know yet"
    emit(peer)
    return 0


if __name__ == "__main__":
    sys.exit(main())
