#!/usr/bin/env python3
"""Host-side check of the HIL stream scenario (stream-guest.sh): the returned candump -L log and
the programs' outputs. Usage: check-stream.py <out-dir> <mrqp-candecode> [nodes=1-7] [min_cycles=2000]"""
import re
import subprocess
import sys

out, candecode = sys.argv[1], sys.argv[2]
nodes = list(range(1, 8))
min_cycles = int(sys.argv[4]) if len(sys.argv) > 4 else 2000
errors = []


def fail(msg):
    errors.append(msg)
    print("check-stream: FAIL: " + msg)


frames = []  # (t, id, data bytes)
with open(out + "/bus.log") as f:
    for line in f:
        m = re.match(r"^\((\d+\.\d+)\) vcan0 ([0-9A-F]{3})#([0-9A-F]*)$", line.strip())
        if not m:
            fail("not a classic candump -L line: " + line.strip())
            continue
        frames.append((float(m.group(1)), int(m.group(2), 16), bytes.fromhex(m.group(3))))
print("check-stream: %d frames in bus.log" % len(frames))

# mrqp-candecode must decode the log (the project's own decoder of the contract).
dec = subprocess.run([candecode, "--arm", "1-7", "--rated-torque-mnm", "10000", out + "/bus.log"],
                     capture_output=True, text=True)
if dec.returncode != 0:
    fail("mrqp-candecode exited %d: %s" % (dec.returncode, dec.stderr.strip()[-400:]))
else:
    with open(out + "/decoded.csv", "w") as f:
        f.write(dec.stdout)
    print("check-stream: mrqp-candecode summary:\n" + dec.stderr.strip())


def first(pred, start=0):
    for i in range(start, len(frames)):
        if pred(frames[i]):
            return i
    return -1


# ---- boot order: NMT reset -> boot-up -> SDO writes -> NMT start -> heartbeats + enable ------------
i_reset = first(lambda f: f[1] == 0x000 and len(f[2]) == 2 and f[2][0] in (0x81, 0x82))
if i_reset < 0:
    fail("no NMT reset on the wire")
else:
    for n in nodes:
        i_boot = first(lambda f: f[1] == 0x700 + n and f[2] == b"\x00", i_reset)
        i_sdo = first(lambda f: f[1] == 0x600 + n and len(f[2]) == 8 and (f[2][0] & 0xE0) == 0x20, i_reset)
        i_start = first(lambda f: f[1] == 0x000 and len(f[2]) == 2 and f[2][0] == 0x01 and f[2][1] in (0, n), i_reset)
        sdo_after_start = [i for i in range(max(i_start, 0), len(frames))
                           if frames[i][1] == 0x600 + n] if i_start >= 0 else []
        i_hb_op = first(lambda f: f[1] == 0x700 + n and f[2] == b"\x05", max(i_start, 0))
        if not (0 <= i_boot < i_sdo < i_start):
            fail("node %d: boot order reset(%d) boot-up(%d) SDO(%d) start(%d) wrong" % (n, i_reset, i_boot, i_sdo, i_start))
        if sdo_after_start:
            fail("node %d: SDO writes after NMT start" % n)
        if i_hb_op < 0:
            fail("node %d: no operational heartbeat after NMT start" % n)
        # controlword enable sequence 0x06 -> 0x07 -> 0x0F in its RPDO1
        seq = []
        for f in frames[max(i_start, 0):]:
            if f[1] == 0x200 + n and len(f[2]) >= 2:
                cw = f[2][0] | (f[2][1] << 8)
                if not seq or seq[-1] != cw:
                    seq.append(cw)
        want = [0x06, 0x07, 0x0F]
        k = 0
        for cw in seq:
            if k < 3 and (cw & 0x8F) == want[k]:
                k += 1
        if k < 3:
            fail("node %d: controlword sequence %s lacks 0x06 -> 0x07 -> 0x0F" % (n, [hex(c) for c in seq[:8]]))

# ---- cyclic: exactly one SYNC per cycle, one RPDO1 per drive per cycle ---------------------------
syncs = [i for i, f in enumerate(frames) if f[1] == 0x080]
print("check-stream: %d SYNC frames" % len(syncs))
if len(syncs) < min_cycles:
    fail("%d SYNCs < %d cycles" % (len(syncs), min_cycles))
bad = 0
for a, b in zip([-1] + syncs[:-1], syncs):
    window = frames[a + 1:b] if a >= 0 else frames[max(0, b - 50):b]
    counts = {n: 0 for n in nodes}
    for f in window:
        if 0x201 <= f[1] <= 0x27F and (f[1] - 0x200) in counts:
            counts[f[1] - 0x200] += 1
    if a < 0:
        continue
    if any(c != 1 for c in counts.values()):
        bad += 1
        if bad <= 5:
            fail("cycle before SYNC at line %d: RPDO1 counts %s" % (b + 1, counts))
if any(len(frames[i][2]) != 0 for i in syncs):
    fail("SYNC with data (the driver sends SYNC without counter)")
print("check-stream: %d cycles with a wrong RPDO count" % bad)

# ---- injected frames on the wire and counted by mrqp-stream --------------------------------------
if not any(f[1] == 0x081 and f[2].hex().upper() == "1023010000000000" for f in frames):
    fail("the foreign EMCY 081#1023010000000000 is not in bus.log")
if not any(f[1] == 0x181 and len(f[2]) == 1 for f in frames):
    fail("the malformed frame 181#00 is not in bus.log")
stream = open(out + "/stream.log").read()
m = re.search(r"node 1: max_error=\S+ rad emcy_count=(\d+) emcy_code=0x(\w+) corrupt_frames=(\d+)", stream)
if not m:
    fail("stream.log has no counters of node 1")
else:
    if int(m.group(1)) < 1:
        fail("the EMCY was not counted (node 1 emcy_count=%s)" % m.group(1))
    if int(m.group(3)) < 1:
        fail("the malformed frame was not counted (node 1 corrupt_frames=%s)" % m.group(3))
m = re.search(r"summary: cycles=(\d+)", stream)
if not m or int(m.group(1)) < min_cycles:
    fail("mrqp-stream did not stream %d cycles" % min_cycles)
if "mrqp-stream: PASS" not in stream:
    fail("mrqp-stream did not PASS")

# ---- heartbeat loss of node 7 detected within its timeout ----------------------------------------
m = re.search(r"heartbeat loss of node 7 detected at \S+ ms of streaming, wall ([\d.]+), timeout (\d+) ms", stream)
hb7 = [f[0] for f in frames if f[1] == 0x707]
if not m:
    fail("heartbeat loss of node 7 not reported by mrqp-stream")
elif not hb7:
    fail("no heartbeat of node 7 in bus.log")
else:
    detected, timeout = float(m.group(1)), int(m.group(2)) / 1000.0
    last = max(t for t in hb7 if t < detected) if any(t < detected for t in hb7) else None
    later = [t for t in hb7 if t > detected]
    if last is None:
        fail("no heartbeat of node 7 before its loss was detected")
    else:
        delay = detected - last
        print("check-stream: node 7 last heartbeat %.6f, loss detected %.6f (%.3f s, timeout %.3f s)" % (last, detected, delay, timeout))
        # >= the timeout; at most timeout + one 100 Hz cycle + TCG scheduling slack
        if delay < timeout - 0.01 or delay > timeout + 0.5:
            fail("heartbeat loss detected %.3f s after the last heartbeat (timeout %.3f s)" % (delay, timeout))
    if later:
        fail("node 7 heartbeats after the loss was detected")

print("check-stream: %s" % ("FAIL (%d problem(s))" % len(errors) if errors else "PASS"))
sys.exit(1 if errors else 0)
