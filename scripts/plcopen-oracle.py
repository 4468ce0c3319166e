#!/usr/bin/env python3
"""Reference traces for ecam's PLCopen facade (crates/ecam-engine/src/plcopen.rs).

Writes crates/ecam-engine/tests/it/fixtures/plcopen_reference.csv, which the
Rust test `plcopen_reference` (tests/it/plcopen_reference.rs) replays through
`McCamAxis` and compares to within 0.5 pulse. Cargo never runs this script.

Provenance. The issue asks for pyplcopen (PyPI, lusipad/plcopen) as the
oracle. pyplcopen 0.21.0 installs, but its Python module exposes single-axis
moves (AxisSim), streaming, cam-law generation and an ST language-server
document only: MC_CamIn/MC_CamTableSelect exist in its C++ core but cannot be
driven from Python, and the GitHub snapshot of lusipad/plcopen has no cam
code. So this script is an independent, deliberately plain model of the four
semantic points, derived by hand from PLCopen Part 1 and from RTmotion's
MC_CamIn (Intel, read for its formulas, nothing copied):
  table input x = MasterScaling * master + MasterOffset
  slave         = SlaveScaling * table(x) + SlaveOffset (+ start position
                  when SlaveAbsolute = FALSE or StartMode = relative)
with linear interpolation between table points. When pyplcopen is installed
the script records its version and whether it exposes a cam API; if a later
version does, drive it here instead of the model.

Run: python3 scripts/plcopen-oracle.py   (writes the fixture; no arguments)
"""

import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "crates", "ecam-engine", "tests", "it", "fixtures",
                   "plcopen_reference.csv")

# Document 001's example table (examples/mc/periodic.mc).
DOC001 = [(0, 500), (10000, 1500), (20000, 1000), (30000, 2000)]
# A 513-point periodic cam with a stroke: 2000 over 512 steps of 100
# counts plus a 300-pulse sine, so first (0) and last (2000) differ.
CAM513 = [(100 * i, round(2000 * i / 512 + 300 * math.sin(2 * math.pi * i / 512)))
          for i in range(513)]
TABLES = {"doc001": DOC001, "cam513": CAM513}


def interpolate(table, x):
    """Linear interpolation inside [first, last] (x is already in range)."""
    for (x0, y0), (x1, y1) in zip(table, table[1:]):
        if x0 <= x <= x1:
            return y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    raise ValueError(x)


def periodic_value(table, x):
    """A periodic table re-evaluated each cycle (absolute slave)."""
    first, last = table[0][0], table[-1][0]
    period = last - first
    return interpolate(table, first + (x - first) % period)


def clamped_value(table, x):
    """A non-periodic table: the end values outside its master range."""
    return interpolate(table, min(max(x, table[0][0]), table[-1][0]))


def cases():
    """(case, table, masters, expected slave, expected end-of-profile)."""
    # (1) periodic, absolute master and slave: re-evaluated each cycle.
    masters = list(range(0, 3 * 51200 + 1, 997))
    yield "periodic_absolute", "cam513", [
        (m, periodic_value(CAM513, m), None) for m in masters]
    # (2) non-periodic, absolute master: the table's own range, then the
    # slave stays coupled at the last value with EndOfProfile set.
    masters = list(range(0, 40001, 1250))
    yield "non_periodic_master_absolute", "doc001", [
        (m, clamped_value(DOC001, m), m >= 30000) for m in masters]
    # (3) MasterScaling 2 and MasterOffset 1000: x = 2 m + 1000.
    masters = list(range(0, 40001, 625))
    yield "master_scaling_2_offset_1000", "doc001", [
        (m, periodic_value(DOC001, 2 * m + 1000), None) for m in masters]
    # (4) SlaveAbsolute = FALSE with the slave at 5000 and the master
    # relative: the table values plus 5000 over the first cycle.
    masters = list(range(0, 30001, 750))
    yield "slave_relative_adds_start_5000", "doc001", [
        (m, interpolate(DOC001, m) + 5000, None) for m in masters]


def pyplcopen_note():
    try:
        import pyplcopen  # noqa: F401
    except ImportError:
        return "pyplcopen not installed"
    from importlib.metadata import version
    names = dir(pyplcopen)
    cam_api = [n for n in names if "camin" in n.lower() or "cam_in" in n.lower()]
    return "pyplcopen %s installed; Python cam API: %s" % (
        version("pyplcopen"), ", ".join(cam_api) if cam_api else "none")


def main():
    lines = [
        "# Reference traces for the PLCopen facade; written by scripts/plcopen-oracle.py.",
        "# Model: the formulas in that script's docstring (PLCopen Part 1 and RTmotion's MC_CamIn).",
        "# " + pyplcopen_note(),
        "# Python " + sys.version.split()[0],
        "# Rows: table,NAME,MASTER,SLAVE | trace,CASE,TABLE,MASTER,SLAVE,END_OF_PROFILE(-|0|1)",
    ]
    for name, table in TABLES.items():
        lines += ["table,%s,%d,%d" % (name, m, s) for m, s in table]
    for case, table, rows in cases():
        for m, s, eop in rows:
            flag = "-" if eop is None else ("1" if eop else "0")
            lines.append("trace,%s,%s,%d,%.6f,%s" % (case, table, m, s, flag))
    with open(OUT, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    print("wrote %s (%d lines)" % (os.path.normpath(OUT), len(lines)))


if __name__ == "__main__":
    main()
