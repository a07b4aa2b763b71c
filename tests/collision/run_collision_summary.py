#!/usr/bin/env python3
"""Runs mrqp-run on a scene with collision avoidance and checks the smallest distance that its
summary.json reports (docs/collision.md, "Measuring" and "The scenes").

Usage: run_collision_summary.py MRQP_RUN SCENE OUT_DIR PLANT MAX_GAP [MRQP_RUN ARGS...]
Checks: exit status 0, no safe stop, no allocation in the loop, summary.json has min_distance_m
and delta_s_m, and delta_s_m - MAX_GAP <= min_distance_m <= delta_s_m + 0.01 (the bodies came
close and were stopped). min_distance_m is mrqp-run's independent measurement: every pair of every
collision constraint, exactly, on a second problem moved to the plant's state after each cycle.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import mrqp_run  # noqa: E402  (tests/support/mrqp_run.py)


def main() -> int:
    if len(sys.argv) < 6:
        print(__doc__, file=sys.stderr)
        return 2
    run, scene, out, plant, max_gap = sys.argv[1:6]
    r = mrqp_run.run(run, scene, out, plant=plant, args=sys.argv[6:], echo=True)
    failures = r.failures()
    s = r.summary
    name = f"run_collision_summary: {os.path.basename(scene)} ({plant})"
    if s is None:
        print(f"{name}: {failures}", file=sys.stderr)
        return 1
    if "min_distance_m" not in s or "delta_s_m" not in s:
        failures.append("summary.json has no min_distance_m or delta_s_m")
    else:
        d, ds = s["min_distance_m"], s["delta_s_m"]
        if not d >= ds - float(max_gap):
            failures.append(f"min_distance_m {d} more than {max_gap} m below delta_s_m {ds}")
        if not d <= ds + 0.01:
            failures.append(f"min_distance_m {d} not within 1 cm of delta_s_m {ds}: the bodies never came close")
        print(f"{name}: min_distance_m {d} ({(d - ds) * 1e6:.1f} µm from delta_s_m {ds})")
    for f in failures:
        print(f"{name}: {f}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
