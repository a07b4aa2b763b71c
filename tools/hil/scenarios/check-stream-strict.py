#!/usr/bin/env python3
"""Host-side check of the HIL scenario hil.stream_strict (stream-strict-guest.sh): the candump -L
logs and the programs' outputs of its two runs against 3 strict emulated drives (two TPDOs each).
Expected frames are encoded here by hand from CiA 301 / CiA 402. Usage: check-stream-strict.py <out-dir>"""
import re
import sys

out = sys.argv[1]
nodes = [1, 2, 3]
errors = []


def fail(msg):
    errors.append(msg)
    print("check-stream-strict: FAIL: " + msg)


def load(name):
    frames = []
    with open(out + "/" + name) as f:
        for line in f:
            m = re.match(r"^\((\d+\.\d+)\) vcan0 ([0-9A-F]{3})#([0-9A-F]*)$", line.strip())
            if not m:
                fail("%s: not a classic candump -L line: %s" % (name, line.strip()))
                continue
            frames.append((float(m.group(1)), int(m.group(2), 16), m.group(3)))
    print("check-stream-strict: %d frames in %s" % (len(frames), name))
    return frames


def text(name):
    with open(out + "/" + name) as f:
        return f.read()


def index(frames, cob, data, start=0):
    for i in range(start, len(frames)):
        if frames[i][1] == cob and frames[i][2] == data:
            return i
    return -1


def le32(v):
    return "".join("%02X" % ((v >> (8 * k)) & 0xFF) for k in range(4))


def check_safe_exit(frames, stream, emu, run):
    """Quick stop (0x0002) then disable voltage (0x0000) in each drive's RPDO1, then NMT enter
    pre-operational (0x80) to it, nothing cyclic after; the emulator's drives end disabled, pre-operational."""
    if "safe exit: drives stopped" not in stream:
        fail("run %d: mrqp-stream reports no completed safe exit" % run)
    for n in nodes:
        i_nmt = index(frames, 0x000, "80%02X" % n)
        if i_nmt < 0:
            fail("run %d: node %d: no NMT enter pre-operational 000#80%02X" % (run, n, n))
            continue
        cws = []
        for f in frames[:i_nmt]:
            if f[1] == 0x200 + n and len(f[2]) == 16:
                cw = int(f[2][2:4] + f[2][0:2], 16)
                if not cws or cws[-1] != cw:
                    cws.append(cw)
        if cws[-2:] != [0x0002, 0x0000]:
            fail("run %d: node %d: controlwords before the NMT command end %s, not quick stop 0x0002 then 0x0000"
                 % (run, n, [hex(c) for c in cws[-4:]]))
        if any(f[1] in (0x080, 0x200 + n) for f in frames[i_nmt + 1:]):
            fail("run %d: node %d: SYNC or RPDO1 after the safe exit's NMT command" % (run, n))
        m = re.search(r"node %d: nmt=0x(\w+) cia402=\d+ \(([^)]*)\)" % n, emu)
        if not m:
            fail("run %d: node %d: no final state in the emulator's log" % (run, n))
        elif m.group(1) != "7f" or m.group(2) != "switch on disabled":
            fail("run %d: node %d: left in NMT 0x%s, CiA 402 %s" % (run, n, m.group(1), m.group(2)))
    if "LEFT ENABLED" in emu:
        fail("run %d: the emulator reports a drive left enabled" % run)


# ---- run 1: boot against two TPDOs, no RTR, 100 Hz stream, safe exit ---------------------------
bus1, stream1, emu1 = load("bus1.log"), text("stream1.log"), text("emu1.log")
for n in nodes:
    # The drive answers the writes disabling TPDO3 and TPDO4 with abort 0x06020000.
    for index_lo in (0x02, 0x03):
        if index(bus1, 0x580 + n, "80%02X1801" % index_lo + le32(0x06020000)) < 0:
            fail("node %d: no abort 0x06020000 for 0x18%02X:01" % (n, index_lo))
    # TPDO1 and TPDO2 enabled with bit 30 (no RTR): expedited 4-byte writes, 0x23.
    for k, base in ((0, 0x180), (1, 0x280)):
        want = "23%02X1801" % k + le32(0x40000000 + base + n)
        if index(bus1, 0x600 + n, want) < 0:
            fail("node %d: no TPDO%d COB-ID write %03X#%s" % (n, k + 1, 0x600 + n, want))
    # 0x1006 as configured (100 ms).
    if index(bus1, 0x600 + n, "23061000" + le32(100000)) < 0:
        fail("node %d: 0x1006 not written as 100000 us" % n)
    m = re.search(r"node %d: max_error=\S+ .* tolerated_aborts=(\d+)" % n, stream1)
    if not m or int(m.group(1)) != 2:
        fail("node %d: mrqp-stream does not report 2 tolerated aborts" % n)
syncs = [f for f in bus1 if f[1] == 0x080]
print("check-stream-strict: run 1: %d SYNC frames" % len(syncs))
if len(syncs) < 1000:
    fail("run 1: %d SYNCs < 1000 cycles" % len(syncs))
if "mrqp-stream: PASS" not in stream1:
    fail("run 1: mrqp-stream did not PASS")
m = re.search(r"sync: syncs=(\d+) intervals=(\d+) period_us=10000\.0 .* max_jitter_us=([\d.]+)", stream1)
if not m:
    fail("run 1: no SYNC jitter line at a 10 ms period")
else:
    print("check-stream-strict: run 1: SYNC max jitter %s us" % m.group(3))
check_safe_exit(bus1, stream1, emu1, 1)

# ---- run 2: SYNC timeout (EMCY 0x8100, pre-operational), recovery, SIGINT, safe exit ------------
bus2, stream2, emu2 = load("bus2.log"), text("stream2.log"), text("emu2.log")
for n in nodes:
    # EMCY 0x8100, error register 0x11 (generic | communication).
    i_emcy = index(bus2, 0x080 + n, "0081110000000000")
    if i_emcy < 0:
        fail("run 2: node %d: no EMCY 0x8100 (SYNC timeout)" % n)
        continue
    i_pre = index(bus2, 0x700 + n, "7F", i_emcy)
    i_start = index(bus2, 0x000, "01%02X" % n, i_emcy)
    i_op = index(bus2, 0x700 + n, "05", max(i_start, 0))
    if not (i_emcy < i_pre < i_start < i_op):
        fail("run 2: node %d: EMCY(%d) pre-operational heartbeat(%d) NMT start(%d) operational(%d) out of order"
             % (n, i_emcy, i_pre, i_start, i_op))
    # Operation enabled again after the start, as the drive itself reports it: a TPDO1 statusword
    # with the state bits (mask 0x6F) of Operation enabled, 0x27, and bit 9 (remote).
    enabled = [f for f in bus2[max(i_op, 0):] if f[1] == 0x180 + n and len(f[2]) == 16
               and (int(f[2][2:4] + f[2][0:2], 16) & 0x026F) == 0x0227]
    if i_op < 0 or not enabled:
        fail("run 2: node %d: no TPDO1 reporting Operation enabled after the recovery" % n)
    m = re.search(r"node %d: max_error=\S+ .* recoveries=(\d+)" % n, stream2)
    if not m or int(m.group(1)) < 1:
        fail("run 2: node %d: mrqp-stream reports no recovery" % n)
if "stopped by a signal" not in stream2:
    fail("run 2: mrqp-stream did not report the SIGINT")
if not re.search(r"EMCY 0x8100 \([^)]*\) register 0x11 from node 1", stream2):
    fail("run 2: mrqp-stream did not describe the EMCY 0x8100")
check_safe_exit(bus2, stream2, emu2, 2)

print("check-stream-strict: %s" % ("FAIL (%d problem(s))" % len(errors) if errors else "PASS"))
sys.exit(1 if errors else 0)
