#!/bin/sh
# HIL guest script (tools/hil/run-vm.sh): a scene as two processes that share nothing but vcan:
# mrqp-plant (the world and the emulated drives, F/T sensors and IMU) and mrqp-run (the
# controller), one vcan interface per bus of the scene's hardware section. Returns run.log,
# plant.log, bus.log (candump -L of the first bus), the run's summary.json and the scene overrides
# used (overrides.txt) in $HIL_OUT.
set -eu
SCENE=${MRQP_HIL_SCENE:-/hil/comanipulation.yaml}
DURATION=${MRQP_HIL_DURATION:-4}
NBUS=${MRQP_HIL_BUSES:-5}
# The plant's clock (docs/loop.md): in the VM, under software emulation (TCG), the guest cannot
# keep real time (it stalls for up to about a second), so the plant is lock-stepped to the
# controller's SYNCs (--clock sync) and the controller runs at 100 Hz (JVRC-1 at its 100 Hz, the
# Panda at 100 Hz instead of 250 Hz: one QP per 10 ms leaves the emulated CPU time for both
# processes). The controller's checks keep their values of the scene. On a host with vcan
# (HIL_MODE=host) the scene runs as it is, the plant in real time.
if [ "${HIL_MODE:-vm}" = host ]; then
  CLOCK=${MRQP_HIL_CLOCK:-realtime} STEP_US=250
  RUN_CLOCK="--clock wall"
  set --
else
  CLOCK=${MRQP_HIL_CLOCK:-sync} STEP_US=10000
  RUN_CLOCK="--clock cycles --pace ${MRQP_HIL_PACE:-10}"
  # The same overrides go to both (the positional parameters).
  set -- --set settings.dt=0.01 --set 'hardware.robots[0].divisor=1' --set 'hardware.robots[1].divisor=1'
fi
# The overrides go back with the results: the host runs the same scene with them as its reference.
: > "$HIL_OUT/overrides.txt"
for a in "$@"; do [ "$a" = --set ] || echo "$a" >> "$HIL_OUT/overrides.txt"; done
# Socket receive buffers of 4 MiB (the default is about 200 kB, some 300 frames): the controller
# opens its sockets before its set-up, which takes seconds under TCG while the drives' heartbeats
# arrive; a kernel queue that overflows is a fault the controller stops on.
echo 4194304 > /proc/sys/net/core/rmem_max
echo 4194304 > /proc/sys/net/core/rmem_default
buses=""
i=0
while [ "$i" -lt "$NBUS" ]; do
  if ! ip link show "vcan$i" > /dev/null 2>&1; then
    ip link add dev "vcan$i" type vcan
    ip link set "vcan$i" up
  fi
  buses="$buses${buses:+,}vcan$i"
  i=$((i + 1))
done
candump -L vcan0 > "$TMPDIR/bus.log" &
dump=$!
mrqp-plant "$SCENE" --bus "$buses" "$@" --clock "$CLOCK" --step-us "$STEP_US" > "$HIL_OUT/plant.log" 2>&1 &
plant=$!
# The drives answer at SYNC on hardware of their own; here the plant shares the guest's one CPU with
# the controller, so it is favoured: a SYNC is answered before the controller's next cycle even
# when that cycle starts late (busybox has renice, not nice or chrt).
if [ "${HIL_MODE:-vm}" != host ]; then renice -n -19 -p "$plant" > /dev/null; fi
sleep 1
rc=0
mrqp-run "$SCENE" --bus "$buses" "$@" --plant ideal $RUN_CLOCK --duration "$DURATION" --no-plots --out "$HIL_OUT/run" \
  > "$HIL_OUT/run.log" 2>&1 || rc=$?
kill -INT "$plant" 2> /dev/null || true
wait "$plant" 2> /dev/null || true
kill "$dump" 2> /dev/null || true
cp "$TMPDIR/bus.log" "$HIL_OUT/bus.log"
cat "$HIL_OUT/run.log"
tail -3 "$HIL_OUT/plant.log"
echo "mrqp-run exit status $rc"
exit "$rc"
