#!/usr/bin/env python3
"""mrqp-stream's command line and exit codes (tools/stream/README.md: 1 on failure, 2 on a usage
error): 0 after --help (the usage on stderr), 2 for a usage error (one line naming the option), 2
for a bad emulator YAML file (naming the file), and 1 with the interface named when the SocketCAN
interface cannot be opened (a host without AF_CAN or without the interface). The streaming itself needs CAN: the HIL
scenarios hil.stream and hil.stream_strict run it in the VM.

usage: run_stream_cli.py MRQP_STREAM
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import mrqp_run  # noqa: E402  (tests/support/mrqp_run.py)

CASES = [
    # (arguments, exit status, text expected on stderr)
    (["--help"], 0, "usage: mrqp-stream"),
    (["--bogus"], 2, "mrqp-stream: unknown option --bogus"),
    (["--rate"], 2, "mrqp-stream: --rate needs a value"),
    (["--rate", "0"], 2, "--rate must be 0..10000 Hz"),
    (["--cycles", "-3"], 2, "--cycles, heartbeat times"),
    (["--nodes", "0-3"], 2, "mrqp-stream: --nodes: expected e.g. 1-7 or 1,2,3 (ids 1..127)"),
    (["--comm-cycle-us", "-1"], 2, "mrqp-stream: --comm-cycle-us: expected microseconds"),
    (["--vendor-id", "0x1FFFFFFFF"], 2, "mrqp-stream: --vendor-id: expected a 32-bit unsigned number"),
    (["--exit-stop", "brake"], 2, "mrqp-stream: --exit-stop: expected quick-stop or disable"),
    (["--exit-nmt", "off"], 2, "mrqp-stream: --exit-nmt: expected pre-operational, stopped or unchanged"),
    (["--config", "/nonexistent/emu.yaml"], 2, "/nonexistent/emu.yaml"),
    (["--interface", "mrqpnone0", "--cycles", "1"], 1, "mrqp-stream: mrqpnone0: "),
]


def check(mrqp_stream):
    failures = []
    for args, status, text in CASES:
        p = subprocess.run([mrqp_stream, *args], capture_output=True, text=True, timeout=30)
        if p.returncode != status or text not in p.stderr:
            failures.append(f"{' '.join(args)}: exit {p.returncode} (expected {status}), stderr {p.stderr.strip()!r}")
    return mrqp_run.report("run_stream_cli", failures,
                           f"{len(CASES) - len(failures)} of {len(CASES)} cases as documented")


if __name__ == "__main__":
    sys.exit(mrqp_run.main(__doc__, 1, check))
