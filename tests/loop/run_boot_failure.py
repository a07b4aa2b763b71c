#!/usr/bin/env python3
"""Runs mrqp-run on two_arms with the right arm's first CiA 402 group configured for a vendor id
its drives do not have (hardware.robots[1].cia402[0].vendor_id = 0x1234; the emulated drives
report 0x0000029C in 0x1018:01): their boot fails (docs/loop.md, "Safety": a boot that does not
complete leaves every device safe).

Usage: run_boot_failure.py MRQP_RUN SCENE OUT_DIR
Checks: exit status 1 before the first cycle (no summary.json), stderr naming each of the five
drives of that group with its node and the values read and expected, the left arm's drives told
in one line as held back, and the safe exit of every device completed.
"""
import os
import shutil
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import mrqp_run  # noqa: E402  (tests/support/mrqp_run.py)


def check(run, scene, out) -> int:
    shutil.rmtree(out, ignore_errors=True)  # no summary.json of an earlier run
    r = mrqp_run.run(run, scene, out, plant="ideal", duration=0.5, echo=True,
                     args=["--set", "hardware.robots[1].cia402[0].vendor_id=0x1234"], expect=None)
    failures = []
    if r.returncode != 1:
        failures.append(f"exit status {r.returncode}, expected 1")
    if r.summary is not None:
        failures.append("a summary.json was written: the loop ran")
    err = r.stderr
    if "mrqp-run: the devices did not boot and enable: a device's boot failed" not in err:
        failures.append("no boot-failure line")
    for node in range(1, 6):
        line = (f"right.panda_joint{node}: boot failed (node {node}); 0x1018:01 of node {node} is "
                f"0x0000029C, the configuration expects 0x00001234")
        if line not in err:
            failures.append(f"missing: {line}")
    if "left: its 8 CiA 402 drives in phase" not in err:
        failures.append("the left arm's drives are not told")
    if ("safe exit of every device (CiA 402 drives: quick stop, then NMT pre-operational; "
            "the other devices disabled): done after") not in err:
        failures.append("no completed safe exit")
    return mrqp_run.report("run_boot_failure", failures)


if __name__ == "__main__":
    sys.exit(mrqp_run.main(__doc__, 3, check))
