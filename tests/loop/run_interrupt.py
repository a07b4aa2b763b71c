#!/usr/bin/env python3
"""SIGINT (and SIGTERM) during mrqp-run's loop: the loop ends after the cycle under way, the drives
get the safe exit as after a last cycle, and summary.json reports the cycles run (docs/loop.md,
"Safety").

Usage: run_interrupt.py MRQP_RUN SCENE OUT_DIR
panda_door runs paced (wall clock) for up to 30 s; the signal comes 1.5 s after the devices are
ready. Checks: exit status 0, the "interrupted" line, summary.json's cycles (those of the loop after
the boot) more than none and fewer than planned, the safe exit done, no allocation in the loop, no safe stop.
"""
import os
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import mrqp_run  # noqa: E402  (tests/support/mrqp_run.py)


def run_once(run, scene, out, sig):
    cmd = mrqp_run.command(run, scene, out, plant="ideal", duration=30, quiet=False, args=["--paced"])
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    ready = False
    started = time.monotonic()
    lines = []
    while time.monotonic() - started < 60:
        line = proc.stdout.readline()
        if not line:
            break
        lines.append(line)
        if "devices ready" in line:
            ready = True
            break
    failures = []
    if not ready:
        proc.kill()
        return ["the devices never became ready: " + "".join(lines)]
    time.sleep(1.5)
    proc.send_signal(sig)
    try:
        rest, err = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        proc.kill()
        return ["mrqp-run did not end within 60 s of the signal"]
    out_text = "".join(lines) + rest
    sys.stdout.write(out_text)
    if proc.returncode != 0:
        failures.append(f"exit status {proc.returncode}: {err}")
    if "interrupted by a signal" not in out_text:
        failures.append("no 'interrupted' line")
    s = mrqp_run.read_summary(out)
    if s is None:
        return failures + ["no summary.json"]
    planned = round(30.0 / s["period_s"])
    # The loop ran (cycles after the boot) and ended before its end. No lower bound from the 1.5 s
    # of wall clock: the deadline clock skips the periods a stalled process misses, so a loaded
    # machine runs fewer cycles in that time (969 seen after one 10 ms stall and 126 misses).
    if not (0 < s["cycles"] < planned):
        failures.append(f"cycles {s['cycles']} (planned {planned})")
    if not s["safe_exit"]["done"]:
        failures.append(f"safe exit: {s['safe_exit']!r}")
    if s["safe_stop"] is not None:
        failures.append(f"safe stop: {s['safe_stop']!r}")
    if s["allocations_in_loop"] not in (0, -1):
        failures.append(f"{s['allocations_in_loop']} allocations in the loop")
    return failures


def main() -> int:
    if len(sys.argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    run, scene, out = sys.argv[1:4]
    failures = []
    for name, sig in (("SIGINT", signal.SIGINT), ("SIGTERM", signal.SIGTERM)):
        for f in run_once(run, scene, f"{out}/{name}", sig):
            failures.append(f"{name}: {f}")
    for f in failures:
        print(f"run_interrupt: {f}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
