#!/usr/bin/env python3
"""Runs mrqp-run on the pen_click scene and checks the click from its summary.json
(docs/scenes.md, "pen_click").

Usage: run_pen_click.py MRQP_RUN SCENE PEN_URDF OUT_DIR PLANT MAX_SLIP_M
Checks: exit status 0, no safe stop, no allocation in the loop; the button's travel on the plant
reached the travel the click requires (button_travel_max_m >= button_travel_required_m); the pen
moved at most MAX_SLIP_M in the palm (pen_slip_m). Independently of the program: the required
travel is the button joint's upper limit read from the pen's URDF less 0.1 mm; the largest travel
and slip agree with the time series of DIR/button_travel.csv; and where the controller's button
estimate is largest, the QP's force on the index contact (DIR/log.csv) balances the button's spring
read from the scene file, K q, within 10 % (the button is nearly at rest there).
"""
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import mrqp_run  # noqa: E402  (tests/support/mrqp_run.py)


def urdf_button_upper(path: str) -> float:
    for joint in ET.parse(path).getroot().iter("joint"):
        if joint.get("name") == "button":
            return float(joint.find("limit").get("upper"))
    raise ValueError(f"{path}: no joint 'button'")


def scene_button_stiffness(path: str) -> float:
    with open(path, encoding="utf-8") as f:
        m = re.search(r"button:\s*\{stiffness:\s*([0-9.eE+-]+)", f.read())
    if m is None:
        raise ValueError(f"{path}: no spring on the button")
    return float(m.group(1))


def main() -> int:
    if len(sys.argv) != 7:
        print(__doc__, file=sys.stderr)
        return 2
    run, scene, urdf, out, plant, max_slip = sys.argv[1:7]
    r = mrqp_run.run(run, scene, out, plant=plant, echo=True)
    try:
        if r.summary is None:
            raise OSError("no summary.json")
        s = r.summary
        rows = r.csv_rows("button_travel.csv")
    except (OSError, ValueError) as e:
        print(f"run_pen_click: {scene} ({plant}): exit status {r.returncode}, no result: {e}", file=sys.stderr)
        return 1
    failures = r.failures()
    travel = s["button_travel_max_m"]
    required = s["button_travel_required_m"]
    slip = s["pen_slip_m"]
    expected_required = urdf_button_upper(urdf) - 1e-4
    if abs(required - expected_required) > 1e-12:
        failures.append(f"required travel {required} m, the URDF's stop less 0.1 mm is {expected_required} m")
    if not travel >= required:
        failures.append(f"button travel {travel} m < required {required} m: no click")
    if not slip <= float(max_slip):
        failures.append(f"pen slip {slip} m > {max_slip} m")
    if len(rows) != s["cycles"]:
        failures.append(f"button_travel.csv has {len(rows)} rows for {s['cycles']} cycles")
    if rows:
        csv_travel = max(float(r["button_travel_m"]) for r in rows)
        csv_slip = max(float(r["pen_slip_m"]) for r in rows)
        if abs(csv_travel - travel) > 1e-8 or abs(csv_slip - slip) > 1e-8:
            failures.append(f"button_travel.csv's maxima {csv_travel}, {csv_slip} differ from summary.json's")
        log = r.csv_rows("log.csv")
        k = max(range(len(rows)), key=lambda i: float(rows[i]["button_estimate_m"]))
        q = float(rows[k]["button_estimate_m"])
        spring = scene_button_stiffness(scene) * q
        force = math.sqrt(sum(float(log[k][c + "_index"]) ** 2 for c in ("fx", "fy", "fz")))
        if len(log) != len(rows) or not abs(force - spring) <= 0.1 * spring:
            failures.append(f"index force {force} N at t = {rows[k]['t']} s, the spring's K q = {spring} N")
        print(f"run_pen_click: index force {force:.3f} N at t = {rows[k]['t']} s, spring K q = {spring:.3f} N")
    for f in failures:
        print(f"run_pen_click: {scene} ({plant}): {f}", file=sys.stderr)
    print(f"run_pen_click: {scene} ({plant}): travel {travel} m (required {required}), slip {slip} m")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
