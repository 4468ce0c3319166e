#!/usr/bin/env python3
"""An impairing bridge for EtherCAT frames between two interfaces: what
comes in on the master's side goes out on the drives' side and back.
Replies (drives -> master) may be impaired:

- SIGUSR1: the next reply is held HOLD_MS (45) and then sent (late);
- --drop P: each reply is dropped with probability P;
- SIGTERM: stop and print the counts as one JSON line on stdout.

The kernel of this project's machines has no tc qdiscs (no netem), so the
bridge is a process: it also holds exactly one reply, which netem cannot
do. It asks for SCHED_FIFO so it forwards promptly on a loaded host.

Usage: impairing_bridge.py MASTER_SIDE_IFACE DRIVES_SIDE_IFACE [--drop P] [--seed N]
"""

import argparse
import heapq
import json
import os
import random
import select
import signal
import socket
import sys
import time

ETH_P_ALL = 0x0003
ETHERCAT = b"\x88\xa4"
PACKET_OUTGOING = 4
HOLD_MS = 45


def open_raw(iface):
    s = socket.socket(socket.AF_PACKET, socket.SOCK_RAW, socket.htons(ETH_P_ALL))
    s.bind((iface, 0))
    s.setblocking(False)
    return s


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("master_side")
    parser.add_argument("drives_side")
    parser.add_argument("--drop", type=float, default=0.0)
    parser.add_argument("--seed", type=int, default=24)
    args = parser.parse_args()
    try:
        os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(60))
    except (PermissionError, OSError):
        pass
    rng = random.Random(args.seed)
    master, drives = open_raw(args.master_side), open_raw(args.drives_side)
    counts = {"requests": 0, "replies": 0, "dropped": 0, "held": 0, "send_errors": 0}
    hold_next = {"n": 0}
    running = {"on": True}
    signal.signal(signal.SIGUSR1, lambda *_: hold_next.__setitem__("n", hold_next["n"] + 1))
    signal.signal(signal.SIGTERM, lambda *_: running.__setitem__("on", False))
    signal.signal(signal.SIGINT, lambda *_: running.__setitem__("on", False))
    held = []  # (due, sequence, frame)
    sequence = 0
    print(f"bridging {os.getpid()}", flush=True)

    def send(sock, frame):
        try:
            sock.send(frame)
        except OSError:
            counts["send_errors"] += 1

    while running["on"]:
        now = time.monotonic()
        while held and held[0][0] <= now:
            _, _, frame = heapq.heappop(held)
            send(master, frame)
        timeout = max(0.0, held[0][0] - now) if held else 0.05
        try:
            ready, _, _ = select.select([master, drives], [], [], timeout)
        except InterruptedError:
            continue
        for sock in ready:
            while True:
                try:
                    frame, address = sock.recvfrom(2048)
                except (BlockingIOError, InterruptedError):
                    break
                except OSError:
                    break  # the interface went down
                if address[2] == PACKET_OUTGOING or frame[12:14] != ETHERCAT:
                    continue
                if sock is master:
                    counts["requests"] += 1
                    send(drives, frame)
                    continue
                counts["replies"] += 1
                if hold_next["n"] > 0:
                    hold_next["n"] -= 1
                    counts["held"] += 1
                    sequence += 1
                    heapq.heappush(held, (time.monotonic() + HOLD_MS / 1000, sequence, frame))
                elif args.drop > 0 and rng.random() < args.drop:
                    counts["dropped"] += 1
                else:
                    send(master, frame)
    print(json.dumps(counts), flush=True)


if __name__ == "__main__":
    sys.exit(main())
