#!/usr/bin/env python3
"""An independent master against `ecam ethercat emulate`: SOEM (through
pysoem) finds the emulated drives, lists their object dictionary (SDO
information), reads identity and mode by SDO, configures distributed
clocks, maps the process data and cycles the drives in OP through the
CiA 402 state machine to "operation enabled", moves them and reads the
emergency a following-error fault sends.

Usage: independent_master.py IFACE DRIVES

Exits 0 when every check holds, 1 (with the reason) otherwise. Run by
crates/ecam-ethercat/tests/wire/run.sh inside a network namespace.
"""

import sys
import time

import pysoem

CYCLE_NS = 2_000_000  # a relaxed cycle: Python on a loaded host
VENDOR_ID = 0x0000_0000
PRODUCT_CODE = 0x4543_414D
NAME = "ecam emulated CSP drive"


def check(condition, what):
    if not condition:
        raise AssertionError(what)


def u32(data):
    return int.from_bytes(data[:4], "little")


def text(name):
    return name.decode() if isinstance(name, bytes) else name


def i8(data):
    return int.from_bytes(data[:1], "little", signed=True)


def dictionary_checks(slave):
    """Object list, descriptions and entries through SDO information."""
    od = slave.od
    indices = {obj.index for obj in od}
    for index in (0x1018, 0x1C12, 0x1C13, 0x1C32, 0x1600, 0x1A00, 0x6040,
                  0x6041, 0x6060, 0x6061, 0x6064, 0x607A, 0x60F4, 0x603F):
        check(index in indices, f"object {index:#06x} in the dictionary list")
    identity = next(obj for obj in od if obj.index == 0x1018)
    check(text(identity.name) == "Identity", f"0x1018 is named {identity.name!r}")
    check(identity.object_code == 9, "0x1018 is a record")
    entries = identity.entries
    check(len(entries) == 5, f"0x1018 has 5 entries, not {len(entries)}")
    check(text(entries[1].name) == "Vendor ID" and entries[1].bit_length == 32,
          "0x1018:01 described as a 32-bit vendor id")
    statusword = next(obj for obj in od if obj.index == 0x6041)
    check(statusword.bit_length == 16, "0x6041 is 16 bits")
    check(statusword.obj_access & 0x80, "0x6041 may be mapped into a TxPDO")
    return len(od)


def identity_checks(slave, position):
    """0x1018 by SDO agrees with the SII; the name with 0x1008."""
    check(text(slave.name) == NAME, f"SII name {slave.name!r}")
    check(slave.man == VENDOR_ID and slave.id == PRODUCT_CODE,
          f"SII identity {slave.man:#x}/{slave.id:#x}")
    check(u32(slave.sdo_read(0x1018, 1)) == slave.man, "0x1018:01 = SII vendor")
    check(u32(slave.sdo_read(0x1018, 2)) == slave.id, "0x1018:02 = SII product")
    check(u32(slave.sdo_read(0x1018, 3)) == slave.rev, "0x1018:03 = SII revision")
    check(u32(slave.sdo_read(0x1018, 4)) == position + 1, "0x1018:04 serial")
    check(slave.sdo_read(0x1008, 0).decode() == NAME, "0x1008 (a normal upload)")
    try:
        slave.sdo_read(0x2000, 0)
        raise AssertionError("0x2000 should not exist")
    except pysoem.SdoError as e:
        check(e.abort_code == 0x06020000, f"abort {e.abort_code:#010x}")


def mode_checks(slave):
    """0x6061 follows 0x6060 = 8 (CSP)."""
    check(slave.sdo_read(0x6060, 0) is not None, "0x6060 readable")
    slave.sdo_write(0x6060, 0, bytes([8]))
    check(i8(slave.sdo_read(0x6061, 0)) == 8, "0x6061 shows CSP after 0x6060 = 8")
    assignment = int.from_bytes(slave.sdo_read(0x1C12, 1), "little")
    check(assignment == 0x1600, f"0x1C12:01 = {assignment:#06x}")


def cycle(master, slaves, cycles, target_of):
    """`cycles` process-data cycles; each drive's outputs from target_of."""
    for _ in range(cycles):
        for k, slave in enumerate(slaves):
            controlword, target = target_of(k, slave)
            slave.output = (controlword.to_bytes(2, "little")
                            + int(target).to_bytes(4, "little", signed=True)
                            + bytes([8]))
        master.send_processdata()
        master.receive_processdata(10_000)
        time.sleep(CYCLE_NS / 1e9)


def inputs(slave):
    data = slave.input
    return (int.from_bytes(data[0:2], "little"),
            int.from_bytes(data[2:6], "little", signed=True))


def main():
    iface, drives = sys.argv[1], int(sys.argv[2])
    # A loaded host answers late: generous frame and state timeouts.
    pysoem.settings.timeouts.ret = 20_000
    master = pysoem.Master()
    master.open(iface)
    try:
        found = master.config_init()
        check(found == drives, f"found {found} drives, expected {drives}")
        objects = 0
        for position, slave in enumerate(master.slaves):
            identity_checks(slave, position)
            objects = dictionary_checks(slave)
            mode_checks(slave)
        check(master.config_dc(), "distributed clocks found")
        for slave in master.slaves:
            slave.dc_sync(True, CYCLE_NS)
        size = master.config_map()
        check(size == drives * 19, f"process image {size} bytes, expected {drives * 19}")
        for slave in master.slaves:
            check(len(slave.output) == 7 and len(slave.input) == 12, "CSP sizes")
        check(master.state_check(pysoem.SAFEOP_STATE, 5_000_000) == pysoem.SAFEOP_STATE,
              "SAFE-OP reached")
        start = {}
        cycle(master, master.slaves, 5, lambda k, s: (0, 0))
        for k, slave in enumerate(master.slaves):
            start[k] = inputs(slave)[1]
        master.state = pysoem.OP_STATE
        master.write_state()
        deadline = time.monotonic() + 5
        while master.state_check(pysoem.OP_STATE, 10_000) != pysoem.OP_STATE:
            cycle(master, master.slaves, 1, lambda k, s: (0, start[k]))
            check(time.monotonic() < deadline, "OP within 5 s")
        # CiA 402: shutdown, switch on, enable operation, holding position.
        for controlword in (0x06, 0x07, 0x0F):
            cycle(master, master.slaves, 3, lambda k, s: (controlword, start[k]))
        for slave in master.slaves:
            statusword, _ = inputs(slave)
            check(statusword & 0x6F == 0x27, f"operation enabled, statusword {statusword:#06x}")
        # Move 10 counts per cycle for 100 cycles: the drive lags 2 cycles
        # and a frame reads its inputs before it writes the outputs, so
        # the last inputs show the target of three cycles before.
        step = {"n": 0}

        def moving(k, _slave):
            return 0x0F, start[k] + 10 * step["n"]

        for n in range(1, 101):
            step["n"] = n
            cycle(master, master.slaves, 1, moving)
        for k, slave in enumerate(master.slaves):
            _, actual = inputs(slave)
            check(actual == start[k] + 970, f"drive {k} at {actual}, expected {start[k] + 970}")
        check(all(i8(s.sdo_read(0x6061, 0)) == 8 for s in master.slaves), "0x6061 = 8 in OP")
        # A following-error fault on drive 0: its emergency reaches SOEM.
        first = master.slaves[0]
        seen = []
        first.add_emergency_callback(seen.append)
        first.sdo_write(0x6065, 0, (5).to_bytes(4, "little"))
        cycle(master, master.slaves, 3, lambda k, s: (0x0F, start[k] + 980 + (1000 if k == 0 else 0)))
        code = int.from_bytes(first.sdo_read(0x603F, 0), "little")
        check(code == 0x8611, f"0x603F = {code:#06x} after the following-error fault")
        check(any(e.error_code == 0x8611 for e in seen),
              f"emergency 0x8611 seen, got {[hex(e.error_code) for e in seen]}")
        master.state = pysoem.INIT_STATE
        master.write_state()
        print(f"pysoem: {drives} drives found, {objects} objects listed each, identity and "
              f"0x6061 read by SDO, DC on, cycled in OP, emergency {seen[0].error_code:#06x} received")
    finally:
        master.close()


if __name__ == "__main__":
    try:
        main()
    except (AssertionError, pysoem.SdoError, pysoem.WkcError, pysoem.MailboxError,
            pysoem.SdoInfoError, pysoem.ConfigMapError) as e:
        print(f"pysoem check failed: {type(e).__name__}: {e}", file=sys.stderr)
        sys.exit(1)
