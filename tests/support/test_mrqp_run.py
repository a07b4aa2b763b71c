#!/usr/bin/env python3
"""Test of tests/support/mrqp_run.py against a stand-in for mrqp-run: a small program that records
the arguments it was given in its summary.json (or writes none), prints to stdout and stderr and
exits with a status chosen by the test. Checked: the command line the module builds (as the
program saw it), the summary read back, the output folder (given and temporary), the usual checks
of failures(), `expect` raising RunError, a missing summary.json read as None.

usage: test_mrqp_run.py
"""
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mrqp_run  # noqa: E402

FAKE = r'''#!/usr/bin/env python3
import json, os, sys
args = sys.argv[1:]
out = args[args.index("--out") + 1]
os.makedirs(out, exist_ok=True)
behaviour = os.path.basename(args[0])  # the "scene" names the behaviour
print("fake stdout")
print("fake stderr", file=sys.stderr)
if behaviour != "no_summary":
    summary = {"args": args, "safe_stop": "qp" if behaviour == "stop" else None,
               "allocations_in_loop": {"alloc": 3, "unchecked": -1}.get(behaviour, 0)}
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f)
    with open(os.path.join(out, "log.csv"), "w") as f:
        f.write("t,a\n0,1\n0.001,2\n")
sys.exit({"fail": 1, "no_summary": 1}.get(behaviour, 0))
'''


def main():
    failures = []

    def check(cond, what):
        if not cond:
            failures.append(what)

    with tempfile.TemporaryDirectory(prefix="test_mrqp_run_") as tmp:
        fake = os.path.join(tmp, "fake-mrqp-run")
        with open(fake, "w") as f:
            f.write(FAKE)
        os.chmod(fake, 0o755)
        out = os.path.join(tmp, "ok")
        r = mrqp_run.run(fake, "ok", out, plant="ideal", duration=0.5, args=["--set", "a.b=1"])
        check(r.summary["args"] == ["ok", "--plant", "ideal", "--out", out, "--duration", "0.5", "--no-plots",
                                    "--quiet", "--set", "a.b=1"], f"arguments {r.summary['args']}")
        check(r.cmd[1:] == r.summary["args"], "cmd is what the program saw")
        check(r.returncode == 0 and r.out == out and r.failures() == [], f"ok run: {r.failures()}")
        check(r.stdout == "fake stdout\n" and r.stderr == "fake stderr\n", "output captured")
        check([row["a"] for row in r.csv_rows("log.csv")] == ["1", "2"], "csv_rows")
        check(r.csv_header("log.csv") == ["t", "a"], "csv_header")

        r = mrqp_run.run(fake, "ok", None, plots=True, quiet=False)
        check(r.out.startswith(tempfile.gettempdir()) and os.path.isdir(r.out), f"temporary folder {r.out}")
        check("--no-plots" not in r.summary["args"] and "--quiet" not in r.summary["args"]
              and "--plant" not in r.summary["args"] and "--duration" not in r.summary["args"],
              f"plots/quiet/plant/duration left out: {r.summary['args']}")
        shutil.rmtree(r.out)

        r = mrqp_run.run(fake, "fail", os.path.join(tmp, "fail"))
        check(r.failures() == ["exit status 1: fake stderr"], f"fail: {r.failures()}")
        check(r.failures(exit_status=1) == [] and r.failures(exit_status=None) == [], "exit_status")
        r = mrqp_run.run(fake, "stop", os.path.join(tmp, "stop"))
        check(r.failures() == ["safe stop: qp"] and r.failures(safe_stop=False) == [], f"stop: {r.failures()}")
        r = mrqp_run.run(fake, "alloc", os.path.join(tmp, "alloc"))
        check(r.failures() == ["3 allocations in the loop"] and r.failures(allocations=False) == [],
              f"alloc: {r.failures()}")
        r = mrqp_run.run(fake, "unchecked", os.path.join(tmp, "unchecked"))
        check(r.failures() == ["-1 allocations in the loop"] and r.failures(unchecked_allocations_ok=True) == [],
              f"unchecked: {r.failures()}")
        r = mrqp_run.run(fake, "no_summary", os.path.join(tmp, "none"))
        check(r.summary is None and mrqp_run.read_summary(r.out) is None, "no summary.json read as None")
        check(r.failures(exit_status=None) == ["no summary.json"], f"no summary: {r.failures(exit_status=None)}")

        for behaviour, expect in (("fail", 0), ("no_summary", 1), ("ok", 1)):
            try:
                mrqp_run.run(fake, behaviour, os.path.join(tmp, "expect_" + behaviour), expect=expect)
                check(behaviour == "no_summary", f"expect={expect} with {behaviour}: no RunError")
            except mrqp_run.RunError as e:
                check(behaviour != "no_summary", f"expect={expect} with {behaviour}: RunError {e}")
        try:
            mrqp_run.run(fake, "ok", os.path.join(tmp, "expect_ok"), expect=0)
        except mrqp_run.RunError as e:
            failures.append(f"expect=0 with ok: {e}")
    return mrqp_run.report("test_mrqp_run", failures, "FAIL" if failures else "PASS")


if __name__ == "__main__":
    sys.exit(main())
