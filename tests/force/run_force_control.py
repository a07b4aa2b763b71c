#!/usr/bin/env python3
"""mrqp-run with the force_control section of a scene, with and without --no-force-control.

On the ideal plant the F/T sensor reads zero, so an admittance in mode direct with f^d > 0
searches for its surface: the tool moves along its normal at K_I f^d and the arm's joint commands
change; with --no-force-control the arm holds its start. A force_control error is one line
FILE:LINE: FIELD: message and exit status 1.

usage: run_force_control.py MRQP_RUN SCENE OUTDIR
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import mrqp_run  # noqa: E402  (tests/support/mrqp_run.py)


def joint_travel(out):
    with open(os.path.join(out, "log.csv")) as f:
        rows = list(csv.reader(f))
    head, first, last = rows[0], rows[1], rows[-1]
    cols = [i for i, n in enumerate(head) if n.startswith("cmd_")]
    return max(abs(float(last[i]) - float(first[i])) for i in cols)


def main():
    run, scene, out = sys.argv[1:4]
    travel = {}
    for name, extra in (("with", []), ("without", ["--no-force-control"])):
        d = os.path.join(out, name)
        p = mrqp_run.run(run, scene, d, duration=1, args=extra)
        if p.returncode != 0:
            print(f"{name}: exit {p.returncode}: {p.stderr}")
            return 1
        travel[name] = joint_travel(d)
    print(f"largest joint command change in 1 s: with {travel['with']:.3g} rad, "
          f"without {travel['without']:.3g} rad")
    ok = travel["with"] > 1e-3 and travel["without"] < 1e-4
    p = mrqp_run.run(run, scene, os.path.join(out, "bad"), duration=1, args=["--set", "force_control[0].mode=qp"])
    want = "force_control[0].mode: mode 'qp' tracks the QP's force on a contact"
    if p.returncode != 1 or want not in p.stderr or ".yaml:" not in p.stderr:
        print(f"bad mode: exit {p.returncode}: {p.stderr}")
        ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
