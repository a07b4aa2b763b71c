#!/usr/bin/env python3
"""mrqp-stream end to end on the simulated bus (`--interface sim`): the drives are mrqp-drive-emu's
emulated firmware on the in-process bus, on a simulated clock, so the whole program (boot, enable,
the stream, the checks, the safe exit, the summary) runs on a host without CAN. Checked against
what follows from the command line and the emulator file, not from the program:

- a clean run: exit 0 and PASS, `cycles` as asked, frames sent = cycles x (drives + one SYNC),
  SYNC intervals exactly one period (simulated clock: no jitter), every drive tracking within
  --max-error, the safe exit done;
- a heartbeat that stops (emulator file: node 2 at 1.0 s) with --expect-heartbeat-loss 2: exit 0,
  the loss detected within the consumer's timeout after the last heartbeat before the stop (the
  producer period is --heartbeat-ms), timed from the start of the stream (boot + enable cycles);
- a boot that fails (an identity the emulated drives do not have): exit 1, the boot FAIL line with
  the object 0x1000 of each node, the safe exit done.

usage: run_stream_sim.py MRQP_STREAM EMU_HB_LOSS.yaml
"""
import re
import subprocess
import sys


def stream(program, *args):
    p = subprocess.run([program, "--interface", "sim", *args], capture_output=True, text=True, timeout=60)
    return p.returncode, p.stdout + p.stderr


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    program, hb_yaml = sys.argv[1:3]
    failures = []
    rate, cycles, drives = 250.0, 500, 3

    code, out = stream(program, "--nodes", "1-3", "--cycles", str(cycles), "--rate", str(rate), "--max-error", "0.05")
    m = re.search(r"summary: cycles=(\d+) rate=\S+ frames_sent=(\d+)", out)
    sync = re.search(r"sync: syncs=\d+ intervals=\d+ period_us=([\d.]+) min_us=([\d.]+) max_us=([\d.]+) "
                     r"max_jitter_us=([\d.]+)", out)
    errors = [float(e) for e in re.findall(r"node \d+: max_error=([\d.]+) rad", out)]
    if code != 0 or "mrqp-stream: PASS" not in out or "safe exit: drives stopped" not in out:
        failures.append(f"clean run: exit {code}")
    if not m or int(m.group(1)) != cycles or int(m.group(2)) != cycles * (drives + 1):
        failures.append(f"clean run: summary {m.group(0) if m else None}, expected {cycles} cycles, "
                        f"{cycles * (drives + 1)} frames")
    period_us = 1e6 / rate
    if not sync or any(abs(float(sync.group(i)) - period_us) > 1e-6 for i in (1, 2, 3)) or float(sync.group(4)) != 0.0:
        failures.append(f"clean run: {sync.group(0) if sync else 'no sync line'}")
    if len(errors) != drives or not all(0.0 < e <= 0.05 for e in errors):
        failures.append(f"clean run: tracking errors {errors}")

    stop_s, timeout_ms, heartbeat_ms = 1.0, 250, 100
    code, out = stream(program, "--config", hb_yaml, "--expect-heartbeat-loss", "2", "--cycles", str(cycles),
                       "--heartbeat-timeout-ms", str(timeout_ms), "--heartbeat-ms", str(heartbeat_ms))
    boot = re.search(r"booted in (\d+) cycles, enabled in (\d+) cycles", out)
    hb = re.search(r"heartbeat loss of node 2 detected at ([\d.]+) ms of streaming", out)
    if code != 0 or "mrqp-stream: PASS" not in out or not boot or not hb:
        failures.append(f"heartbeat loss: exit {code}: {out[-600:]}")
    else:
        start_ms = (int(boot.group(1)) + int(boot.group(2))) * 1e3 / rate
        at_ms = start_ms + float(hb.group(1))
        lo = stop_s * 1e3 - heartbeat_ms + timeout_ms
        hi = stop_s * 1e3 + timeout_ms + 2 * 1e3 / rate
        print(f"run_stream_sim: heartbeat loss detected at {at_ms:.1f} ms of the run, expected in [{lo}, {hi}]")
        if not lo <= at_ms <= hi:
            failures.append(f"heartbeat loss at {at_ms} ms, expected in [{lo}, {hi}]")

    code, out = stream(program, "--nodes", "1,2", "--device-type", "0x12345", "--cycles", "50")
    if (code != 1 or "FAIL: boot ended in phase failed" not in out or "safe exit: drives stopped" not in out
            or not all(f"0x1000:00 of node {n}" in out for n in (1, 2))):
        failures.append(f"boot failure: exit {code}: {out}")

    for f in failures:
        print(f"run_stream_sim: {f}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
