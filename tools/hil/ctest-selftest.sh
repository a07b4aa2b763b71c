#!/usr/bin/env bash
# CTest test hil.selftest (CMakeLists.txt here): runs selftest-guest.sh in the HIL VM, then checks
# the returned candump log on the host with check-selftest.sh.
# Usage: ctest-selftest.sh <out-dir>
# Exit status 77 (CTest SKIP_RETURN_CODE) when qemu or the guest kernel is missing: run
# tools/hil/setup.sh first. MRQP_HIL_HOST=1 runs the guest script on this host's vcan instead
# (a robot computer with AF_CAN).
set -euo pipefail
# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
out=${1:?usage: ctest-selftest.sh <out-dir>}
skip() {
  echo "hil.selftest SKIPPED: $* -- run tools/hil/setup.sh to install the HIL VM"
  exit 77
}
rm -rf "$out"
if [ "${MRQP_HIL_HOST:-0}" = 1 ]; then
  "$HIL_DIR/run-vm.sh" --host --script "$HIL_DIR/selftest-guest.sh" --out "$out" --timeout 60
else
  [ -n "$(hil_find_qemu)" ] || skip "qemu-system-x86_64 is not installed (Debian package qemu-system-x86)"
  hil_find_kernel || skip "no guest kernel in $HIL_CACHE"
  "$HIL_DIR/run-vm.sh" --script "$HIL_DIR/selftest-guest.sh" --out "$out" --timeout 150
fi
"$HIL_DIR/check-selftest.sh" "$out"
