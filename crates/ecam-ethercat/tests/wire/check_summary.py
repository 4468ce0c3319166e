#!/usr/bin/env python3
"""Checks the output of one `ecam ethercat run` in run.sh: prints its
figures and evaluates an expression on `s` (the JSON summary, the last
line), `status` (the status line before it) and `bridge` (the impairing
bridge's counts).

Usage: check_summary.py OUTPUT NAME EXPRESSION BRIDGE_JSON
"""

import json
import sys


def main():
    path, name, expression, counts = sys.argv[1:5]
    lines = open(path, encoding="utf-8").read().splitlines()
    s = json.loads(lines[-1])
    status = lines[-2]
    bridge = json.loads(counts)
    ok = eval(expression, {}, {"s": s, "status": status, "bridge": bridge})
    sync0 = s["sync0"]["lead_mean_us"]
    print(f"   {name}: cycles {s['cycles']}, lost {s['lost_cycles']} "
          f"(at most {s['lost_in_a_row_max']} in a row), late replies {s['late_replies']}, "
          f"send errors {s['send_errors']}, recoveries {s['recoveries']}, "
          f"faults {len(s['faults'])}, SYNC0 lead mean {sync0:.1f} µs; bridge {bridge}")
    for fault in s["faults"]:
        print(f"     fault: {fault}")
    if not ok:
        print(f"   expected: {expression}\n   status: {status}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
