#!/bin/sh
# HIL guest script (tools/hil/run-vm.sh): 7 emulated drives + mrqp-stream on vcan0, a foreign
# EMCY and a malformed TPDO1 during the run, node 7's heartbeat stopped by the emulator.
# Returns bus.log (candump -L), emu.log and stream.log in $HIL_OUT.
set -eu
# TCG: the guest's scheduling stalls for tens of ms at times (cycle overruns), so the latency
# checks are loose (tracking error, feedback-missing cycles); order and counts are checked on the host.
RATE=${MRQP_HIL_RATE:-100}
CYCLES=${MRQP_HIL_CYCLES:-2000}
HB_STOP=${MRQP_HIL_HB_STOP:-16}   # s after the emulator starts: late in the stream
candump -L vcan0 > "$TMPDIR/bus.log" &
dump=$!
sleep 1
mrqp-drive-emu --config /hil/emu7.yaml --interface vcan0 --stop-heartbeat "7@$HB_STOP" > "$HIL_OUT/emu.log" 2>&1 &
emu=$!
sleep 1
mrqp-stream --interface vcan0 --config /hil/emu7.yaml --rate "$RATE" --cycles "$CYCLES" \
  --expect-heartbeat-loss 7 --max-error 0.5 --feedback-missing-cycles 50 --sdo-timeout-ms 1000 --heartbeat-timeout-ms 1500 \
  > "$HIL_OUT/stream.log" 2>&1 &
stream=$!
sleep 8
cansend vcan0 081#1023010000000000   # foreign EMCY, node 1, 0x2310 over-current
cansend vcan0 181#00                 # malformed TPDO1 of node 1 (1 byte)
echo "injected EMCY and malformed frame"
rc=0
wait "$stream" || rc=$?
kill "$emu" 2> /dev/null || true
wait "$emu" 2> /dev/null || true
sleep 1
kill "$dump" 2> /dev/null || true
cp "$TMPDIR/bus.log" "$HIL_OUT/bus.log"
cat "$HIL_OUT/stream.log"
tail -10 "$HIL_OUT/emu.log"
echo "mrqp-stream exit status $rc"
exit "$rc"
