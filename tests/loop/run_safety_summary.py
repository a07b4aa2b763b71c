#!/usr/bin/env python3
"""Runs mrqp-run on panda_door with an injected drive fault and checks what summary.json and
faults.log say about it (docs/loop.md, "Safety"): the drivers' own text of the fault that stopped
the controller and of the injected fault, and the safe exit after the last cycle.

Usage: run_safety_summary.py MRQP_RUN SCENE OUT_DIR
The fault is the encoder of panda_joint3 reading NaN at 0.2 s: its firmware raises EMCY 0x7305
(CiA 402: incremental sensor 1 fault), so the drivers' text must carry that code and the node of
the drive (3). Checks: exit status 0 (a stop explained by the injected fault), safe_stop set,
safe_stop_driver and the fault's "driver" naming panda.panda_joint3 and 0x7305, the same text in
faults.log, the safe exit done, no allocation in the loop.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import mrqp_run  # noqa: E402  (tests/support/mrqp_run.py)


def check(run, scene, out) -> int:
    r = mrqp_run.run(run, scene, out, plant="ideal", duration=0.6, echo=True,
                     args=["--fault", "nan-feedback@0.2:panda.panda_joint3",
                           "--set", "hardware.robots[0].safe_stop=quick_stop"])
    failures = r.failures(safe_stop=False, allocations=False)
    if r.summary is None:
        print(f"run_safety_summary: {failures}", file=sys.stderr)
        return 1
    s = r.summary
    log = r.text("faults.log")
    if s["safe_stop"] is None:
        failures.append("no safe stop")
    driver = s.get("safe_stop_driver") or ""
    if not driver.startswith("panda.panda_joint3: ") or "0x7305" not in driver or "node 3" not in driver:
        failures.append(f"safe_stop_driver: {driver!r}")
    fault = s["faults"][0]
    if "0x7305" not in (fault.get("driver") or ""):
        failures.append(f"faults[0].driver: {fault.get('driver')!r}")
    if not any("panda.panda_joint3" in e and "0x7305" in e for e in s["fault_events"]):
        failures.append(f"fault_events: {s['fault_events']!r}")
    if "panda.panda_joint3: " not in log or "0x7305" not in log:
        failures.append(f"faults.log: {log!r}")
    if not s["safe_exit"]["done"]:
        failures.append(f"safe exit: {s['safe_exit']!r}")
    if s["allocations_in_loop"] not in (0, -1):
        failures.append(f"{s['allocations_in_loop']} allocations in the loop")
    return mrqp_run.report("run_safety_summary", failures, f"safe stop {s['safe_stop']!r}; {driver}")


if __name__ == "__main__":
    sys.exit(mrqp_run.main(__doc__, 3, check))
