"""mrqp_run: run mrqp-run on a scene into an output folder and read what it wrote, for the
run_*.py tests (the preamble they share).

    import os, sys
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
    import mrqp_run

    r = mrqp_run.run(MRQP_RUN, scene, out, plant="ideal", duration=1, args=["--set", "a.b=1"])
    r.returncode, r.stdout, r.stderr   # the process
    r.out                              # the output folder (a new temporary one when out is None)
    r.summary                          # summary.json parsed, or None when the program wrote none
    r.path("log.csv"), r.csv_rows("log.csv")
    r.failures()                       # the usual checks: exit status 0, no safe stop, no
                                       # allocation in the loop (each one a line of text)

    def check(run, scene, out):        # a test's own checks: its exit status
        ...
        return mrqp_run.report("run_x", failures)
    if __name__ == "__main__":
        sys.exit(mrqp_run.main(__doc__, 3, check))

The command is `MRQP_RUN SCENE [--plant P] --out OUT [--duration D] --no-plots --quiet ARGS...`
(`plots=True` drops --no-plots, `quiet=False` drops --quiet); command() builds it for a test that
runs the process itself (e.g. to send it a signal). Nothing here checks a scene's outcome: each
test keeps its own checks, computed independently of the program.
"""
import csv
import json
import os
import subprocess
import sys
import tempfile


class RunError(Exception):
    """mrqp-run exited with a status other than the one asked for, or wrote no summary.json."""


def command(mrqp_run, scene, out, *, plant=None, duration=None, args=(), quiet=True, plots=False):
    """The argument list of one mrqp-run."""
    cmd = [str(mrqp_run), str(scene)]
    if plant is not None:
        cmd += ["--plant", str(plant)]
    cmd += ["--out", str(out)]
    if duration is not None:
        cmd += ["--duration", str(duration)]
    if not plots:
        cmd.append("--no-plots")
    if quiet:
        cmd.append("--quiet")
    cmd += [str(a) for a in args]
    return cmd


def read_summary(out):
    """OUT/summary.json parsed, or None when the file does not exist (the program stopped before
    writing it, e.g. on a bad scene). A file that is not JSON raises ValueError."""
    path = os.path.join(out, "summary.json")
    if not os.path.exists(path):
        return None
    with open(path, encoding="utf-8") as f:
        return json.load(f)


class Result:
    """One finished mrqp-run: its command, exit status, output text, folder and summary."""

    def __init__(self, cmd, returncode, stdout, stderr, out, summary):
        self.cmd = cmd
        self.returncode = returncode
        self.stdout = stdout
        self.stderr = stderr
        self.out = out
        self.summary = summary

    def path(self, name):
        """The path of a file the run wrote (summary.json, log.csv, faults.log, ...)."""
        return os.path.join(self.out, name)

    def text(self, name):
        with open(self.path(name), encoding="utf-8") as f:
            return f.read()

    def csv_rows(self, name):
        """The rows of a CSV file of the run, each a dict by column name."""
        with open(self.path(name), encoding="utf-8", newline="") as f:
            return list(csv.DictReader(f))

    def csv_header(self, name):
        with open(self.path(name), encoding="utf-8", newline="") as f:
            return next(csv.reader(f))

    def failures(self, *, exit_status=0, safe_stop=True, allocations=True, unchecked_allocations_ok=False):
        """The usual checks of a run, each failed one as a line of text: the exit status is
        `exit_status` (None: not checked), summary.json exists, no safe stop (`safe_stop`), no
        allocation in the loop (`allocations`; -1, a build without the counting allocator, passes
        only with `unchecked_allocations_ok`)."""
        out = []
        if exit_status is not None and self.returncode != exit_status:
            out.append(f"exit status {self.returncode}" + (f": {self.stderr.strip()}" if self.stderr.strip() else ""))
        s = self.summary
        if s is None:
            out.append("no summary.json")
            return out
        if safe_stop and s.get("safe_stop") is not None:
            out.append(f"safe stop: {s['safe_stop']}")
        if allocations:
            n = s.get("allocations_in_loop")
            if not (n == 0 or (unchecked_allocations_ok and n == -1)):
                out.append(f"{n} allocations in the loop")
        return out


def run(mrqp_run, scene, out=None, *, plant=None, duration=None, args=(), quiet=True, plots=False,
        echo=False, expect=None, timeout=None):
    """Runs mrqp-run once (see command()) and returns its Result. `out` None: a new temporary
    folder (left in place for a look after a failure). `echo`: the program's stdout and stderr are
    copied to this process's. `expect` an exit status: RunError when the run ends with another one
    or (for 0) writes no summary.json, with the program's stderr in the message."""
    if out is None:
        out = tempfile.mkdtemp(prefix="mrqp_run_")
    cmd = command(mrqp_run, scene, out, plant=plant, duration=duration, args=args, quiet=quiet, plots=plots)
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    if echo:
        sys.stdout.write(p.stdout)
        sys.stderr.write(p.stderr)
        sys.stdout.flush()
        sys.stderr.flush()
    r = Result(cmd, p.returncode, p.stdout, p.stderr, out, read_summary(out))
    if expect is not None:
        if p.returncode != expect:
            raise RunError(f"{' '.join(cmd)}: exit status {p.returncode} (expected {expect}): {p.stderr.strip()}")
        if expect == 0 and r.summary is None:
            raise RunError(f"{' '.join(cmd)}: no summary.json in {out}")
    return r


def report(name, failures, last_line=None):
    """Prints each failure as a line `NAME: failure` on stderr, then `NAME: LAST_LINE` (when given)
    on stdout; returns the test's exit status: 1 with failures, else 0."""
    for f in failures:
        print(f"{name}: {f}", file=sys.stderr)
    if last_line is not None:
        print(f"{name}: {last_line}")
    return 1 if failures else 0


def main(doc, nargs, check):
    """The command line of a test program: `check(*arguments)` when it was given exactly `nargs`
    arguments, its return value the exit status; otherwise `doc` (the usage) on stderr and 2."""
    if len(sys.argv) != nargs + 1:
        print(doc, file=sys.stderr)
        return 2
    return check(*sys.argv[1:])
