#!/usr/bin/env python3
"""Runs mrqp-run on a shipped scene with the MuJoCo plant and checks its summary.json
(docs/mujoco.md, "The shipped scenes on MuJoCo").

Usage: run_scene_summary.py MRQP_RUN SCENE OUT_DIR TASK MAX_ERROR
Checks: exit status 0, no safe stop, the plant was MuJoCo's (the log says nothing about it, so
the command line asks for it), no allocation in the loop, no log record dropped, the task's final
error at most MAX_ERROR.
"""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import mrqp_run  # noqa: E402  (tests/support/mrqp_run.py)


def main() -> int:
    if len(sys.argv) != 6:
        print(__doc__, file=sys.stderr)
        return 2
    run, scene, out, task, max_error = sys.argv[1:6]
    r = mrqp_run.run(run, scene, out, plant="mujoco", echo=True)
    failures = r.failures()
    s = r.summary
    if s is None:
        print(f"run_scene_summary: {scene}: {failures}", file=sys.stderr)
        return 1
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
