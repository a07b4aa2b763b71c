#!/usr/bin/env python3
"""Runs mrqp-run on the carry_box scene with and without force control and checks the outcome
from summary.json (docs/force-control.md, "carry_box").

Usage: run_carry_box.py MRQP_RUN SCENE OUT_DIR PLANT TOLERANCE_M SLIP_M WITHOUT
  PLANT        ideal or mujoco
  TOLERANCE_M  largest distance of the plant's box to each waypoint at its time (with force control)
  SLIP_M       largest displacement of the box in a hand frame (with force control)
  WITHOUT      what the run without force control shows on this plant: "follows" (the same
               tolerances hold, as on the ideal plant, where nothing can slip) or "slips" (the box
               is dropped or misses a waypoint by more than the tolerance)
Both runs: exit status 0, no safe stop, no allocation in the loop, `force_control` as asked, one
error per waypoint.

On the ideal plant the F/T sensors read zero, so an admittance in mode autonomous presses its
hand into the box at its v_max for the whole run (with the scene's 0.01 m/s: 79 mm of slip in
8 s, measured); the run with force control there caps each admittance's v_max at IDEAL_V_MAX
(`--set force_control[NAME].velocity_limits=...`, names read from the scene file): what is
checked on that plant is the carrying, not the force loop, which only the MuJoCo plant closes.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import mrqp_run  # noqa: E402  (tests/support/mrqp_run.py)


IDEAL_V_MAX = 0.0002  # m/s


def ideal_caps(scene):
    import yaml  # python3-yaml

    with open(scene, encoding="utf-8") as f:
        doc = yaml.safe_load(f)
    args = []
    for fc in doc.get("force_control", []):
        v_min = fc.get("velocity_limits", [-0.05, 0.05])[0]
        args += ["--set", f"force_control[{fc['name']}].velocity_limits=[{v_min}, {IDEAL_V_MAX}]"]
    return args


def run(program, scene, out, plant, force_control):
    if not force_control:
        args = ["--no-force-control"]
    else:
        args = ideal_caps(scene) if plant == "ideal" else []
    r = mrqp_run.run(program, scene, out, plant=plant, echo=True, args=args)
    if r.summary is None:
        raise mrqp_run.RunError(f"{scene}: no summary.json (exit status {r.returncode})")
    return r.returncode, r.summary


def main() -> int:
    if len(sys.argv) != 8:
        print(__doc__, file=sys.stderr)
        return 2
    program, scene, out, plant, tol, slip_max, without = sys.argv[1:8]
    tol, slip_max = float(tol), float(slip_max)
    failures = []
    for fc in (True, False):
        name = "with force control" if fc else "without force control"
        code, s = run(program, scene, f"{out}/{'fc' if fc else 'no_fc'}", plant, fc)
        errors = s.get("box_waypoint_errors_m")
        print(f"run_carry_box: {name}: waypoint errors {errors}, slip {s.get('box_slip_m')}, "
              f"dropped {s.get('box_dropped')}, safe stop {s['safe_stop']}")
        if code != 0:
            failures.append(f"{name}: exit status {code}")
        if s["safe_stop"] is not None:
            failures.append(f"{name}: safe stop: {s['safe_stop']}")
        if s["allocations_in_loop"] != 0:
            failures.append(f"{name}: {s['allocations_in_loop']} allocations in the loop")
        if s.get("force_control") is not fc:
            failures.append(f"{name}: force_control is {s.get('force_control')}")
        if not isinstance(errors, list) or len(errors) != 3 or any(e is None for e in errors):
            failures.append(f"{name}: box_waypoint_errors_m is {errors}")
            continue
        follows = all(e <= tol for e in errors) and s["box_dropped"] is False
        if fc or without == "follows":
            if not follows:
                failures.append(f"{name}: the box misses a waypoint by more than {tol} m or is dropped")
            if not s["box_slip_m"] <= slip_max:
                failures.append(f"{name}: slip {s['box_slip_m']} > {slip_max} m")
        elif follows:
            failures.append(f"{name}: the box follows the waypoints (expected it to slip)")
    for f in failures:
        print(f"run_carry_box: {scene}: {f}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
