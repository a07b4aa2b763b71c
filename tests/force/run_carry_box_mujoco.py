#!/usr/bin/env python3
"""carry_box on the MuJoCo plant, with and without force control, checked from summary.json
(docs/force-control.md, "carry_box").

usage: run_carry_box_mujoco.py MRQP_RUN SCENE OUT_DIR

Always checked (a failure fails the test): both runs write summary.json with `force_control`
as asked (true, then false with --no-force-control), one `box_waypoint_errors_m` entry per
waypoint of the scene file's trajectory (read here from the file), `box_slip_m` a number,
`box_dropped` a boolean, and no allocation in the loop.

The outcome of Sec. V-C (Fig. 14), asserted: with force control no safe stop, every waypoint
reached within WAYPOINT_M, slip at most SLIP_M, not dropped; without it no safe stop either, and
the box slips (more than SLIP_M) or drops: the hands, which only touch it, cannot lift it.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import mrqp_run  # noqa: E402  (tests/support/mrqp_run.py)

WAYPOINT_M = 0.02
SLIP_M = 0.02


def waypoints(scene):
    import yaml  # python3-yaml

    with open(scene, encoding="utf-8") as f:
        doc = yaml.safe_load(f)
    return len(doc["trajectories"][0]["waypoints"])


def main():
    exe, scene, out = sys.argv[1], sys.argv[2], sys.argv[3]
    n = waypoints(scene)
    failures = []
    runs = {}
    for fc in (True, False):
        d = os.path.join(out, "on" if fc else "off")
        r = mrqp_run.run(exe, scene, d, plant="mujoco", args=() if fc else ("--no-force-control",))
        s = r.summary
        if s is None:
            failures.append(f"force control {fc}: no summary.json (exit {r.returncode}): {r.stderr.strip()}")
            continue
        runs[fc] = s
        if s.get("force_control") is not fc:
            failures.append(f"force_control is {s.get('force_control')!r}, expected {fc}")
        errs = s.get("box_waypoint_errors_m")
        if not isinstance(errs, list) or len(errs) != n:
            failures.append(f"box_waypoint_errors_m {errs!r}: expected {n} entries")
        if not isinstance(s.get("box_slip_m"), (int, float)):
            failures.append(f"box_slip_m {s.get('box_slip_m')!r} is not a number")
        if not isinstance(s.get("box_dropped"), bool):
            failures.append(f"box_dropped {s.get('box_dropped')!r} is not a boolean")
        if s.get("allocations_in_loop") != 0:
            failures.append(f"{s.get('allocations_in_loop')} allocations in the loop")
    if failures:
        print("FAIL: " + "; ".join(failures))
        return 1
    on, off = runs[True], runs[False]
    measured = (f"with force control: safe stop {on.get('safe_stop')!r}, waypoint errors "
                f"{on['box_waypoint_errors_m']} m, slip {on['box_slip_m']} m, dropped {on['box_dropped']}; "
                f"without: safe stop {off.get('safe_stop')!r}, slip {off['box_slip_m']} m, dropped {off['box_dropped']}")
    outcome = []
    if on.get("safe_stop"):
        outcome.append(f"the run with force control stopped safely: {on['safe_stop']}")
    if off.get("safe_stop"):
        outcome.append(f"the run without force control stopped safely: {off['safe_stop']}")
    errs = on["box_waypoint_errors_m"]
    if any(e is None or e > WAYPOINT_M for e in errs):
        outcome.append(f"waypoint errors {errs} (limit {WAYPOINT_M} m)")
    if on["box_slip_m"] > SLIP_M:
        outcome.append(f"slip {on['box_slip_m']} m (limit {SLIP_M} m)")
    if on["box_dropped"]:
        outcome.append("box dropped")
    if not (off["box_dropped"] or off["box_slip_m"] > SLIP_M):
        outcome.append(f"without force control the box neither slipped nor dropped (slip {off['box_slip_m']} m)")
    if outcome:
        print("FAIL: " + "; ".join(outcome) + f" ({measured})")
        return 1
    print(f"OK ({measured})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
