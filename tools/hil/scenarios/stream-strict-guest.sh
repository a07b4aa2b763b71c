#!/bin/sh
# HIL guest script (tools/hil/run-vm.sh) of hil.stream_strict: mrqp-stream at 100 Hz against 3
# strict emulated drives with two TPDOs each (emu-strict.yaml).
#  run 1: boot (TPDO3/4 absent: aborts 0x06020000 tolerated), enable, stream, safe exit at the end.
#         0x1006 is written as 100 ms (--comm-cycle-us): TCG stalls the guest for tens of ms at
#         times, and the drives' SYNC timeout is 1.5 x 0x1006.
#  run 2: 0x1006 = the 10 ms period, --recover; mrqp-stream is frozen for 1 s (SIGSTOP): every
#         drive times out on SYNC (EMCY 0x8100, pre-operational); after SIGCONT the master brings
#         them back; then SIGINT: the safe exit stops them.
# Returns bus1.log, bus2.log (candump -L), emu1.log, emu2.log, stream1.log, stream2.log in $HIL_OUT.
set -u
RATE=${MRQP_HIL_RATE:-100}
CYCLES=${MRQP_HIL_CYCLES:-1000}
common="--interface vcan0 --config /hil/emu-strict.yaml --rate $RATE --max-error 0.5 --feedback-missing-cycles 50 --sdo-timeout-ms 1000 --heartbeat-timeout-ms 1500"

# ---- run 1 ----
candump -L vcan0 > "$TMPDIR/bus1.log" &
dump=$!
sleep 1
mrqp-drive-emu --config /hil/emu-strict.yaml --interface vcan0 > "$HIL_OUT/emu1.log" 2>&1 &
emu=$!
sleep 1
rc1=0
# shellcheck disable=SC2086
mrqp-stream $common --cycles "$CYCLES" --comm-cycle-us 100000 > "$HIL_OUT/stream1.log" 2>&1 || rc1=$?
sleep 1
kill "$emu" 2> /dev/null || true
wait "$emu" 2> /dev/null || true
kill "$dump" 2> /dev/null || true
wait "$dump" 2> /dev/null || true
cp "$TMPDIR/bus1.log" "$HIL_OUT/bus1.log"
echo "run 1: mrqp-stream exit status $rc1"
cat "$HIL_OUT/stream1.log"
cat "$HIL_OUT/emu1.log"

# ---- run 2 ----
candump -L vcan0 > "$TMPDIR/bus2.log" &
dump=$!
sleep 1
mrqp-drive-emu --config /hil/emu-strict.yaml --interface vcan0 > "$HIL_OUT/emu2.log" 2>&1 &
emu=$!
sleep 1
# shellcheck disable=SC2086
mrqp-stream $common --cycles 100000 --recover --comm-cycle-us 40000 > "$HIL_OUT/stream2.log" 2>&1 &
stream=$!
sleep 10                 # booted, enabled, streaming
kill -STOP "$stream"
echo "run 2: mrqp-stream frozen"
sleep 1
kill -CONT "$stream"
echo "run 2: mrqp-stream resumed"
sleep 8                  # recovered
kill -INT "$stream"
rc2=0
wait "$stream" || rc2=$?
sleep 1
kill "$emu" 2> /dev/null || true
wait "$emu" 2> /dev/null || true
kill "$dump" 2> /dev/null || true
wait "$dump" 2> /dev/null || true
cp "$TMPDIR/bus2.log" "$HIL_OUT/bus2.log"
echo "run 2: mrqp-stream exit status $rc2 (1 expected: stopped by SIGINT)"
cat "$HIL_OUT/stream2.log"
cat "$HIL_OUT/emu2.log"
exit "$rc1"
