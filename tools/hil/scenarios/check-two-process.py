#!/usr/bin/env python3
"""Host-side check of the HIL scenario hil.two_process (two-process-guest.sh): the controller
(mrqp-run) and the plant with the emulated firmware (mrqp-plant) ran as two processes over vcan.
Checked from what came back: the run's summary.json (no safe stop, every cycle of the reference
run, the tasks' final errors against the reference's, no log row dropped, the joints where they
were commanded), the plant's own count of the frames it bridged and of the SYNCs it stepped by, and
the candump -L log of the first bus (the controller's SYNCs and RPDOs, two TPDOs of each of its 18
drives per SYNC). The reference is the same scene with the same overrides on the simulated buses
in one process (ctest-two-process.sh).
Usage: check-two-process.py <out-dir> <guest exit status> <reference summary.json>"""
import json
import re
import sys

out, guest_rc, ref_path = sys.argv[1], int(sys.argv[2]), sys.argv[3]
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

def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        fail("%s: %s" % (path, e))
        return {}


s = load(out + "/run/summary.json")
ref = load(ref_path)
DRIVES_BUS0 = 18  # comanipulation's body bus: JVRC-1's legs, waist and neck
if s and ref:
    if s.get("safe_stop") is not None:
        fail("the controller stopped: %s" % s["safe_stop"])
    if ref.get("safe_stop") is not None:
        fail("the reference run stopped: %s" % ref["safe_stop"])
    if s.get("cycles") != ref.get("cycles") or s.get("period_s") != ref.get("period_s"):
        fail("cycles %s of %s s, the reference ran %s of %s s" % (s.get("cycles"), s.get("period_s"),
                                                                  ref.get("cycles"), ref.get("period_s")))
    if s.get("log_records_dropped", 1) != 0:
        fail("log records dropped: %s" % s.get("log_records_dropped"))
    if (s.get("safe_exit") or {}).get("done") is not True:
        fail("the safe exit did not complete: %s" % s.get("safe_exit"))
    errors_final = s.get("task_errors_final", {})
    ref_final = ref.get("task_errors_final", {})
    if not errors_final or sorted(errors_final) != sorted(ref_final):
        fail("task errors %s, the reference has %s" % (sorted(errors_final), sorted(ref_final)))
    # As the loop tests compare the loop with the model run (tests/loop/test_loop.cpp): 2 %, or
    # 2e-3 for errors already small. Both controllers see their robots through the drives' encoders
    # one robot cycle late; the plants differ (here: drives that put the joints where commanded).
    for name, value in sorted(errors_final.items()):
        r = ref_final.get(name, float("nan"))
        print("check-two-process: task %s final error %.6f (reference %.6f)" % (name, value, r))
        if not abs(value - r) <= max(2e-3, 0.02 * r):
            fail("task %s: final error %.6f, the reference's %.6f" % (name, value, r))
    track = s.get("joint_tracking_error_max_rad", {})
    for robot, value in track.items():
        print("check-two-process: %s largest |measured - commanded| %.6f rad" % (robot, value))
        if value > 1e-4:  # the encoders' resolution (the loop tests' bound on the ideal plant)
            fail("%s: joint tracking error %.6f rad: the feedback does not follow the commands" % (robot, value))

plant = read("plant.log")
m = re.search(r"(\d+) frames to the devices, (\d+) from them \((\d+) not sent\)", plant)
plant_syncs = None
if not m:
    fail("plant.log has no frame counts (did mrqp-plant end normally?)")
else:
    to_dev, from_dev, not_sent = (int(x) for x in m.groups())
    print("check-two-process: plant bridged %d frames to the devices, %d from them" % (to_dev, from_dev))
    if not_sent:
        fail("%d device frames could not be sent on vcan" % not_sent)
    ms = re.search(r"lock-step: SYNCs per bus body (\d+) ", plant)
    if ms:
        plant_syncs = int(ms.group(1))
    elif "lock-step" in plant:
        fail("plant.log has no lock-step SYNC count of the body bus")

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
cycles = s.get("cycles", 0) if s else 0
# Every loop cycle has one SYNC on the body bus (the boot's cyclic exchange and the safe exit add
# some); each of its 18 drives answers every SYNC with TPDO1 and TPDO2 (the last SYNC of the run
# may go unanswered when the plant is stopped) and gets one RPDO per SYNC.
if sync < cycles or sync < 100:
    fail("vcan0: %d SYNCs for %d cycles" % (sync, cycles))
if tpdo < 2 * DRIVES_BUS0 * (sync - 1) or rpdo < DRIVES_BUS0 * sync:
    fail("vcan0: %d TPDOs and %d RPDOs for %d SYNCs of %d drives: the cyclic exchange did not run"
         % (tpdo, rpdo, sync, DRIVES_BUS0))
if plant_syncs is not None:
    print("check-two-process: the plant stepped %d SYNC periods on the body bus" % plant_syncs)
    if plant_syncs != sync:
        fail("the lock-stepped plant counted %d SYNCs on the body bus, candump %d" % (plant_syncs, sync))

if errors:
    print("check-two-process: %d failure(s)" % len(errors))
    sys.exit(1)
print("check-two-process: OK")
