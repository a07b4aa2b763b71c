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
import csv
import json
import math
import re
import subprocess
import sys
import xml.etree.ElementTree as ET


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
    cmd = [run, scene, "--plant", plant, "--out", out, "--no-plots", "--quiet"]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    sys.stdout.write(proc.stdout)
    sys.stderr.write(proc.stderr)
    try:
        with open(out + "/summary.json", encoding="utf-8") as f:
            s = json.load(f)
        with open(out + "/button_travel.csv", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
    except (OSError, ValueError) as e:
        print(f"run_pen_click: {scene} ({plant}): exit status {proc.returncode}, no result: {e}", file=sys.stderr)
        return 1
    failures = []
    if proc.returncode != 0:
        failures.append(f"exit status {proc.returncode}")
    if s["safe_stop"] is not None:
        failures.append(f"safe stop: {s['safe_stop']}")
    if s["allocations_in_loop"] != 0:
        failures.append(f"{s['allocations_in_loop']} allocations in the loop")
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
        with open(out + "/log.csv", encoding="utf-8") as f:
            log = list(csv.DictReader(f))
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
