#!/usr/bin/env bash
# HIL self-test, host side: checks the candump log that selftest-guest.sh returned through
# run-vm.sh (tools/hil/README.md). Usage: check-selftest.sh <run-vm.sh --out folder>
set -euo pipefail
dir=${1:?usage: check-selftest.sh <folder with the returned dump.log>}
log=$dir/dump.log
fail() {
  echo "hil selftest (host check): FAIL: $*" >&2
  exit 1
}
[ -s "$log" ] || fail "no returned candump log $log"
fd_data=$(for i in $(seq 0 63); do printf '%02X' "$i"; done)
expected=("123#DEADBEEF" "080#" "123##1$fd_data")
# Only a --host run on a classic vcan0 it may not reconfigure goes without the FD frame.
if grep -qx 'fd no' "$dir/selftest.txt" 2> /dev/null && grep -qx 'mode host' "$dir/selftest.txt"; then
  echo "hil selftest (host check): WARNING: the host's vcan0 is not CAN FD: no FD frame checked" >&2
  expected=("123#DEADBEEF" "080#")
fi
mapfile -t lines < "$log"
[ ${#lines[@]} -eq ${#expected[@]} ] || fail "$log has ${#lines[@]} lines, expected ${#expected[@]}"
prev=0
for i in "${!expected[@]}"; do
  re='^\(([0-9]+\.[0-9]{6})\) vcan0 ([0-9A-F#]+)$'
  [[ ${lines[$i]} =~ $re ]] || fail "line $((i + 1)) is no candump -L line on vcan0: '${lines[$i]}'"
  ts=${BASH_REMATCH[1]} frame=${BASH_REMATCH[2]}
  # FD flags nibble: BRS (1) as sent, plus CANFD_FDF (4) that kernels >= 6.0 set on delivery.
  [ "$frame" = "${expected[$i]}" ] || [ "${frame/\#\#5/##1}" = "${expected[$i]}" ] \
    || fail "line $((i + 1)): frame $frame, expected ${expected[$i]}"
  awk -v a="$prev" -v b="$ts" 'BEGIN { exit !(b >= a) }' || fail "line $((i + 1)): timestamp $ts goes back in time"
  prev=$ts
done
echo "hil selftest (host check): PASS: $log holds the ${#expected[@]} frames in order:"
cat "$log"
