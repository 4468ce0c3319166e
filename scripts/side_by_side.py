"""Reference half of scripts/bench-side-by-side (run it through that script).

Runs the ecam timing binary, then times the references on the data it
wrote, and prints one JSON object per line: case, ecam_ns, reference,
reference_ns, ratio (= ecam / reference). Lookup lines also carry the
largest difference between ecam's and numpy's results on the same queries
(both interpolate the same straight lines, so it is rounding only).
"""

import argparse
import json
import shutil
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


def peer_ns(quick):
    """ns per MC_CamIn cycle of pyplcopen's C++ core on cam513, or why not.

    pyplcopen's wheel exposes no MC_CamIn to Python, so its C++ function
    blocks are compiled from the sdist with scripts/plcopen-peer/build.sh
    (g++ and the sdist from PyPI) and timed by that driver's --bench.
    """
    if shutil.which("g++") is None:
        return None, "g++ is not installed (the peer is C++, built from pyplcopen's sdist)"
    build = Path(__file__).resolve().parent / "plcopen-peer" / "build.sh"
    cycles = "200000" if quick else "2000000"
    run = subprocess.run([str(build), "--bench", cycles], capture_output=True, text=True)
    if run.returncode != 0:
        tail = (run.stderr.strip().splitlines() or ["no output"])[-1]
        return None, f"the peer did not build or run: {tail}"
    for line in run.stdout.splitlines():
        fields = line.split(",")
        if len(fields) >= 5 and fields[0] == "tick-peer" and fields[1] == "cam513":
            return float(fields[4].split()[0]), None
    return None, "the peer driver printed no cam513 figure"


def instructions_per_path(binary, workdir):
    """Instructions of every tick `binary` (the tick_paths example) measures.

    callgrind counts only inside `instr_probe` and dumps after each call, so
    each dump is one tick; the binary prints the path of each call in order.
    Returns {path: [instructions of each tick]} or, when valgrind is
    missing, why not.
    """
    if shutil.which("valgrind") is None:
        return None, "valgrind is not installed (apt-get install valgrind)"
    out = Path(workdir) / "callgrind.out"
    if out.exists():
        out.unlink()
    probe = "tick_paths::instr_probe"
    run = subprocess.run(
        ["valgrind", "--tool=callgrind", "--collect-atstart=no",
         f"--toggle-collect={probe}", f"--dump-after={probe}", "--combine-dumps=yes",
         f"--callgrind-out-file={out}", binary],
        capture_output=True, text=True)
    if run.returncode != 0:
        tail = (run.stderr.strip().splitlines() or ["no output"])[-1]
        return None, f"callgrind failed: {tail}"
    paths = [line[len("probe "):] for line in run.stdout.splitlines() if line.startswith("probe ")]
    with open(out) as f:
        totals = [int(line.split()[1]) for line in f if line.startswith("totals:")]
    # One dump per probe call, then the (empty) one at the program's end.
    if len(totals) < len(paths):
        return None, f"callgrind gave {len(totals)} dumps for {len(paths)} ticks"
    per_path = {}
    for path, count in zip(paths, totals):
        per_path.setdefault(path, []).append(count)
    return per_path, None


def worst_instructions_line(binary, workdir):
    """The tick-worst-instr line: the most instructions any measured tick
    took, its path, and the mean of the steady ticks."""
    line = {"case": "tick-worst-instr"}
    per_path, reason = instructions_per_path(binary, workdir)
    if per_path is None:
        return dict(line, skipped=reason)
    steady = per_path.get("steady") or [float("nan")]
    mean = sum(steady) / len(steady)
    worst = {path: max(counts) for path, counts in per_path.items()}
    path = max(worst, key=worst.get)
    return dict(
        line,
        ecam_instr=worst[path],
        path=path,
        reference="mean instructions of a steady tick (tick-1 scenario, callgrind)",
        reference_instr=round(mean, 1),
        ratio=round(worst[path] / mean, 3),
        goal=3.0,
        worst_per_path={p: worst[p] for p in sorted(worst, key=worst.get, reverse=True)},
    )


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--ecam", required=True, help="the side_by_side example binary")
    parser.add_argument("--data", required=True, help="where the binary writes the data")
    parser.add_argument("--paths", help="the tick_paths example binary (tick-worst-instr)")
    parser.add_argument("--cycle", help="ecam-ethercat's cycle_cost example binary (ethercat-cycle-N)")
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    data = Path(args.data)
    quick = ["--quick"] if args.quick else []

    def ecam(*extra):
        run = subprocess.run([args.ecam, *extra, *quick], check=True, capture_output=True, text=True)
        return {line["case"]: line for line in map(json.loads, run.stdout.splitlines())}

    # The data first (and ecam's results on it for the agreement check).
    ecam("--lookups", "--data", str(data))
    table = np.loadtxt(data / "table.csv", delimiter=",", dtype=np.int64)
    xp = table[:, 0].astype(np.float64)
    fp = table[:, 1].astype(np.float64)
    sets = {
        "lookup-sequential": ("sequential", 40 if args.quick else 150),
        "lookup-random": ("random", 40 if args.quick else 150),
        "lookup-batch-1M": ("batch", 5 if args.quick else 11),
    }
    queries = {case: np.fromfile(data / f"{name}.f64", dtype="<f8") for case, (name, _) in sets.items()}
    # Rounds alternate between ecam and numpy so that both see the same
    # machine (a shared machine's load drifts); medians over the rounds.
    rounds = 3 if args.quick else 7
    ours = {case: [] for case in sets}
    theirs = {case: [] for case in sets}
    for _ in range(rounds):
        for case, line in ecam("--lookups").items():
            ours[case].append(line["ecam_ns"])
        for case, (_, reps) in sets.items():
            q = queries[case]
            theirs[case].append(median_ns_per_query(lambda: np.interp(q, xp, fp), len(q), reps))
    for case, (name, _) in sets.items():
        mine = np.fromfile(data / f"{name}.ecam.f64", dtype="<f8")
        diff = float(np.max(np.abs(np.interp(queries[case], xp, fp) - mine)))
        line = {"case": case, "ecam_ns": round(float(np.median(ours[case])), 2)}
        ns = float(np.median(theirs[case]))
        extra = {"goal": 0.5} if case == "lookup-batch-1M" else {}
        emit(with_reference(line, "numpy.interp " + np.__version__, ns, max_abs_diff=diff, **extra))

    lines = ecam("--ticks")
    for case in ("tick-1", "tick-64", "tick-worst"):
        emit(lines[case])
    if args.paths:
        emit(worst_instructions_line(args.paths, data))
    peer = lines["tick-peer"]
    ns, reason = peer_ns(args.quick)
    if ns is None:
        peer = dict(peer, reference="pyplcopen 0.21.0 MC_CamIn (C++)", reference_ns=None, ratio=None)
        peer["skipped"] = reason
        emit(peer)
    else:
        emit(with_reference(peer, "pyplcopen 0.21.0 MC_CamIn (C++, scripts/plcopen-peer)", ns))
    if args.cycle:
        run = subprocess.run([args.cycle, *quick], check=True, capture_output=True, text=True)
        for line in run.stdout.splitlines():
            emit(json.loads(line))
    return 0


if __name__ == "__main__":
    sys.exit(main())
