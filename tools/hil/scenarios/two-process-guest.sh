#!/bin/sh
# HIL guest script (tools/hil/run-vm.sh): a scene as two processes that share nothing but vcan:
# mrqp-plant (the world and the emulated drives, F/T sensors and IMU) and mrqp-run (the
# controller), one vcan interface per bus of the scene's hardware section. Returns run.log,
# plant.log, bus.log (candump -L of the first bus) and the run's summary.json in $HIL_OUT.
set -eu
SCENE=${MRQP_HIL_SCENE:-/hil/comanipulation.yaml}
DURATION=${MRQP_HIL_DURATION:-4}
NBUS=${MRQP_HIL_BUSES:-5}
# Under TCG the guest runs several times slower than the host, and the plant and the controller
# share its one CPU: the controller runs at 200 Hz (JVRC-1 at 100 Hz as in the scene, the Panda
# at 200 Hz instead of 250 Hz) and the plant steps every 1 ms. Emulation stalls of tens of ms
# remain (and the controller's start-up delays the plant), so the controller
# tolerates 20 robot cycles without feedback (3 in the scene), 30 % of its robot cycles without
# fresh feedback (2 %) and a 1 s heartbeat timeout (0.25 s).
# The same overrides go to both (the positional parameters).
set -- --set settings.dt=0.005 --set 'hardware.robots[0].divisor=2' --set 'hardware.robots[1].divisor=1' \
  --set hardware.feedback_missing_cycles=20 --set hardware.heartbeat_timeout=1.0 \
  --set 'hardware.frame_loss={window: 100, limit: 0.3}'
STEP_US=${MRQP_HIL_STEP_US:-1000}
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
mrqp-plant "$SCENE" --bus "$buses" "$@" --step-us "$STEP_US" > "$HIL_OUT/plant.log" 2>&1 &
plant=$!
sleep 1
rc=0
mrqp-run "$SCENE" --bus "$buses" "$@" --plant ideal --duration "$DURATION" --no-plots --out "$HIL_OUT/run" \
  > "$HIL_OUT/run.log" 2>&1 || rc=$?
kill -INT "$plant" 2> /dev/null || true
wait "$plant" 2> /dev/null || true
kill "$dump" 2> /dev/null || true
cp "$TMPDIR/bus.log" "$HIL_OUT/bus.log"
cat "$HIL_OUT/run.log"
tail -2 "$HIL_OUT/plant.log"
echo "mrqp-run exit status $rc"
exit "$rc"
