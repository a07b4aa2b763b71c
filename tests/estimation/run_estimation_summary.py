#!/usr/bin/env python3
"""mrqp-run with the estimation section of door_estimate.yaml on the ideal plant.

The run registers the estimator's log columns (each estimate with its standard deviation), adds
the estimation's fields to summary.json with the true spring taken from the scene file's door
entity (read here from the YAML, independently of the program), and refuses a bad estimation
section with one line FILE:LINE: FIELD: message and exit status 1. (The ideal plant's F/T sensor
reads zero, so the values of the estimate are not checked here: tests/estimation/
test_estimator_hook.cpp checks them against a plant that supplies the holding wrench.)

usage: run_estimation_summary.py MRQP_RUN SCENE OUTDIR
"""
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import mrqp_run  # noqa: E402  (tests/support/mrqp_run.py)


def scene_spring(scene):
    text = open(scene).read()
    m = re.search(r"handle: \{stiffness: ([-0-9.e]+), damping: ([-0-9.e]+), offset: ([-0-9.e]+)\}", text)
    return [float(m.group(i)) for i in (1, 2, 3)]


def main():
    run, scene, out = sys.argv[1:4]
    r = mrqp_run.run(run, scene, out, plant="ideal", duration=1)
    if r.returncode != 0:
        print(f"exit {r.returncode}: {r.stderr}")
        return 1
    s = r.summary
    ok = True
    truth = scene_spring(scene)
    got = [s["spring_true"][k] for k in ("K", "C", "O")]
    if got != truth:
        print(f"spring_true {got}, the scene's {truth}")
        ok = False
    for key in ("spring_initial", "spring_estimate", "spring_std"):
        v = s.get(key)
        if not isinstance(v, dict) or not all(isinstance(v.get(k), (int, float)) and math.isfinite(v[k])
                                                 for k in ("K", "C", "O")):
            print(f"{key}: {v}")
            ok = False
    if s.get("spring_joint") != "door.handle" or not s.get("estimation_updates", {}).get("door", 0) > 0:
        print(f"spring_joint {s.get('spring_joint')}, updates {s.get('estimation_updates')}")
        ok = False
    head = r.csv_header("log.csv")
    for c in ("est_door_handle_K", "est_door_handle_K_std", "est_door_handle_C", "est_door_handle_O_std",
              "est_door_nis", "est_door_updates"):
        if c not in head:
            print(f"log.csv has no column {c}")
            ok = False
    p = mrqp_run.run(run, scene, os.path.join(out, "bad"), plant="ideal", duration=1,
                     args=["--set", "estimation[0].cutoff=500"])
    want = "estimation[0].cutoff: the cutoff 500 Hz is not below half the F/T rate (250 Hz)"
    if p.returncode != 1 or want not in p.stderr or ".yaml:" not in p.stderr:
        print(f"bad cutoff: exit {p.returncode}: {p.stderr}")
        ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
