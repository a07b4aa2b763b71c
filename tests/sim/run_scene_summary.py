#!/usr/bin/env python3
"""Runs mrqp-run on a shipped scene with the MuJoCo plant and checks its summary.json
(docs/mujoco.md, "The shipped scenes on MuJoCo").

Usage: run_scene_summary.py MRQP_RUN SCENE OUT_DIR TASK MAX_ERROR
Checks: exit status 0, no safe stop, the plant was MuJoCo's (the log says nothing about it, so
the command line asks for it), no allocation in the loop, no log record dropped, the task's final
error at most MAX_ERROR.
"""
import json
import subprocess
import sys


def main() -> int:
    if len(sys.argv) != 6:
        print(__doc__, file=sys.stderr)
        return 2
    run, scene, out, task, max_error = sys.argv[1:6]
    cmd = [run, scene, "--plant", "mujoco", "--out", out, "--no-plots", "--quiet"]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    sys.stdout.write(proc.stdout)
    sys.stderr.write(proc.stderr)
    with open(out + "/summary.json", encoding="utf-8") as f:
        s = json.load(f)
    failures = []
    if proc.returncode != 0:
        failures.append(f"exit status {proc.returncode}")
    if s["safe_stop"] is not None:
        failures.append(f"safe stop: {s['safe_stop']}")
    if s["allocations_in_loop"] != 0:
        failures.append(f"{s['allocations_in_loop']} allocations in the loop")
    if s["log_records_dropped"] != 0:
        failures.append(f"{s['log_records_dropped']} log records dropped")
    error = s["task_errors_final"][task]
    if not error <= float(max_error):
        failures.append(f"task {task}: final error {error} > {max_error}")
    for f in failures:
        print(f"run_scene_summary: {scene}: {f}", file=sys.stderr)
    print(f"run_scene_summary: {scene}: {task} {error}, safe stop {s['safe_stop']}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
