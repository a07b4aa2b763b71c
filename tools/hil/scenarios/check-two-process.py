#!/usr/bin/env python3
"""Host-side check of the HIL scenario hil.two_process (two-process-guest.sh): the controller
(mrqp-run) and the plant with the emulated firmware (mrqp-plant) ran as two processes over vcan.
Checked from what came back: the run's summary.json (no safe stop, every cycle run, the tasks'
final errors, no log row dropped), the plant's own count of the frames it bridged, and the
candump -L log of the first bus (SYNC from the controller, the drives' TPDOs after it, the
controller's RPDOs). Usage: check-two-process.py <out-dir> <guest exit status>"""
import json
import re
import sys

out, guest_rc = sys.argv[1], int(sys.argv[2])
errors = []


def fail(msg):
    errors.append(msg)
    print("check-two-process: FAIL: " + msg)


def read(name):
    try:
        with open(out + "/" + name) as f:
            return f.read()
    except OSError as e:
        fail("%s: %s" % (name, e))
        return ""


if guest_rc != 0:
    fail("the guest script exited with status %d (mrqp-run's exit status; 3 = an unexplained safe stop)" % guest_rc)

summary_text = read("run/summary.json")
s = {}
if summary_text:
    try:
        s = json.loads(summary_text)
    except ValueError as e:
        fail("run/summary.json is not JSON: %s" % e)
if s:
    if s.get("safe_stop") is not None:
        fail("the controller stopped: %s" % s["safe_stop"])
    expected = round(4.0 / s.get("period_s", 1.0))
    if s.get("cycles") != expected:
        fail("cycles %s, expected %d (4 s)" % (s.get("cycles"), expected))
    if s.get("log_records_dropped", 1) != 0:
        fail("log records dropped: %s" % s.get("log_records_dropped"))
    errors_final = s.get("task_errors_final", {})
    if not errors_final:
        fail("no task errors in summary.json")
    # The box target of comanipulation on the ideal plant (docs/loop.md); the controller's own
    # task errors, the plant being the other process.
    for name, value in errors_final.items():
        print("check-two-process: task %s final error %.4f" % (name, value))
    track = s.get("joint_tracking_error_max_rad", {})
    for robot, value in track.items():
        print("check-two-process: %s largest |measured - commanded| %.4f rad" % (robot, value))
        if value > 0.05:
            fail("%s: joint tracking error %.4f rad > 0.05 rad: the feedback does not follow the commands" % (robot, value))

plant = read("plant.log")
m = re.search(r"(\d+) frames to the devices, (\d+) from them \((\d+) not sent\)", plant)
if not m:
    fail("plant.log has no frame counts (did mrqp-plant end normally?)")
else:
    to_dev, from_dev, not_sent = (int(x) for x in m.groups())
    print("check-two-process: plant bridged %d frames to the devices, %d from them" % (to_dev, from_dev))
    if to_dev < 1000 or from_dev < 1000:
        fail("too few frames bridged (%d in, %d out)" % (to_dev, from_dev))
    if not_sent:
        fail("%d device frames could not be sent on vcan" % not_sent)

sync = tpdo = rpdo = 0
for line in read("bus.log").splitlines():
    mm = re.match(r"^\(\d+\.\d+\) vcan0 ([0-9A-F]{3})#", line.strip())
    if not mm:
        continue
    cob = int(mm.group(1), 16)
    if cob == 0x080:
        sync += 1
    elif 0x181 <= cob <= 0x1FF or 0x281 <= cob <= 0x2FF:
        tpdo += 1
    elif 0x201 <= cob <= 0x27F:
        rpdo += 1
print("check-two-process: vcan0: %d SYNC, %d TPDO, %d RPDO frames" % (sync, tpdo, rpdo))
if sync < 100 or tpdo < 18 * sync or rpdo < 18 * (sync - 50):
    fail("vcan0 traffic does not show a running cyclic exchange with 18 drives")

if errors:
    print("check-two-process: %d failure(s)" % len(errors))
    sys.exit(1)
print("check-two-process: OK")
