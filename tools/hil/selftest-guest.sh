#!/bin/sh
# HIL self-test, guest side (busybox sh in the VM, or sh on a host with vcan: run-vm.sh --host).
# Proves the whole channel: vcan0 is up, can-utils talk over it (classic frames, a CANopen SYNC and
# a 64-byte CAN FD frame), and a file comes back to the host ($HIL_OUT/dump.log, the candump log),
# where tools/hil/check-selftest.sh checks it again.
set -eu

fail() {
  echo "selftest: FAIL: $*" >&2
  exit 1
}
tmp=${TMPDIR:-/tmp}
log=$tmp/dump.log

[ -d /sys/class/net/vcan0 ] || fail "no vcan0 interface"
[ -d /sys/class/net/vcan1 ] || fail "no vcan1 interface"
[ -d /proc/net/can ] || fail "no /proc/net/can: the kernel has no AF_CAN"
echo "selftest: kernel $(uname -r), vcan0 and vcan1 present"

# CAN FD: vcan takes the FD MTU (72) while down. (On a host whose vcan0 is classic and where we
# may not change it, the FD frame is left out and selftest.txt says so.)
fd_data=$(i=0; while [ $i -lt 64 ]; do printf '%02X' $i; i=$((i + 1)); done)
if [ "$(cat /sys/class/net/vcan0/mtu)" != 72 ]; then
  if ip link set vcan0 down 2> /dev/null; then
    ip link set vcan0 mtu 72 2> /dev/null || true
    ip link set vcan0 up || fail "cannot set vcan0 up again"
  fi
fi
fd=no
[ "$(cat /sys/class/net/vcan0/mtu)" != 72 ] || fd=yes
[ $fd = yes ] || [ "${HIL_MODE:-vm}" = host ] || fail "vcan0 does not take the CAN FD MTU 72"
echo "selftest: CAN FD on vcan0: $fd (mtu $(cat /sys/class/net/vcan0/mtu))"

# candump is ready once its socket shows in vcan0's receive list (where every filter-less socket
# is: a line "   vcan0     000    00000000 ... raw").
receivers() { grep -c '^ *vcan0 ' /proc/net/can/rcvlist_all 2> /dev/null || true; }
uptime_s() { cut -d. -f1 /proc/uptime; }
before=$(receivers)
candump -L vcan0 > "$log" &
dump_pid=$!
deadline=$(($(uptime_s) + 10))
while [ "$(receivers)" -le "$before" ]; do
  [ "$(uptime_s)" -le $deadline ] || { kill "$dump_pid" 2> /dev/null; fail "candump did not open its socket on vcan0 within 10 s"; }
  kill -0 "$dump_pid" 2> /dev/null || fail "candump died at start"
  sleep 0.05
done

cansend vcan0 123#DEADBEEF || fail "cansend vcan0 123#DEADBEEF failed"
cansend vcan0 080# || fail "cansend vcan0 080# (SYNC) failed"
if [ $fd = yes ]; then
  cansend vcan0 "123##1$fd_data" || fail "cansend of a 64-byte CAN FD frame failed"
fi
sleep 0.2
kill -TERM "$dump_pid"
wait "$dump_pid" || true

# Returned whatever happens, for the host check and for a look after a failure.
cp "$log" "$HIL_OUT/dump.log"
printf 'kernel %s\nfd %s\nmode %s\n' "$(uname -r)" "$fd" "${HIL_MODE:-?}" > "$HIL_OUT/selftest.txt"

echo "selftest: candump -L vcan0 logged:"
cat "$log"
expected="123#DEADBEEF 080#"
[ $fd = no ] || expected="$expected 123##1$fd_data"
# The FD flags nibble after '##': we sent BRS (1); kernels >= 6.0 also set CANFD_FDF (4) on every
# FD frame they deliver, so candump shows 5 there. Compare with FDF masked out.
got=$(awk '{ f = $3; if (f ~ /##5/) sub(/##5/, "##1", f); printf "%s%s", sep, f; sep = " " }' "$log")
[ "$got" = "$expected" ] || fail "frames logged: '$got'; expected, in this order: '$expected'"
bad=$(awk '$2 != "vcan0"' "$log")
[ -z "$bad" ] || fail "lines for an interface other than vcan0: $bad"

echo "selftest: PASS ($(wc -l < "$log") frames in order; dump.log returned)"
