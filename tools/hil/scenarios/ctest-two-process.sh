#!/usr/bin/env bash
# The two-process scenario (docs/loop.md, "Controller and plant in two processes"), run by hand:
# two-process-guest.sh in the HIL VM -- the comanipulation scene's controller (mrqp-run) and its
# plant with the emulated drives and sensors (mrqp-plant) as two processes that share nothing but
# vcan -- then check-two-process.py on the host. Not in the test suite: under TCG the guest stalls
# for longer than the controller's feedback checks allow (docs/loop.md says what a run shows).
# Usage: ctest-two-process.sh <out-dir> <mrqp-plant> <mrqp-run> <scene.yaml>
# Exit status 77 (CTest SKIP_RETURN_CODE) when qemu or the guest kernel is missing.
set -euo pipefail
# shellcheck source=../lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/../lib.sh"
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
out=${1:?usage: ctest-two-process.sh <out-dir> <mrqp-plant> <mrqp-run> <scene.yaml>}
plant=${2:?} run=${3:?} scene=${4:?}
skip() {
  echo "two-process scenario SKIPPED: $* -- run tools/hil/setup.sh to install the HIL VM"
  exit 77
}
rm -rf "$out"
# Dynamically linked programs: the image gets their shared libraries and loader (build-initramfs.sh).
args=(--script "$here/two-process-guest.sh" --add "$plant:/hil/bin/mrqp-plant" --add "$run:/hil/bin/mrqp-run"
      --add "$scene:/hil/comanipulation.yaml" --out "$out" --timeout 300)
rc=0
if [ "${MRQP_HIL_HOST:-0}" = 1 ]; then
  "$HIL_DIR/run-vm.sh" --host "${args[@]}" || rc=$?
else
  [ -n "$(hil_find_qemu)" ] || skip "qemu-system-x86_64 is not installed (Debian package qemu-system-x86)"
  hil_find_kernel || skip "no guest kernel in $HIL_CACHE"
  "$HIL_DIR/run-vm.sh" "${args[@]}" || rc=$?
fi
python3 "$here/check-two-process.py" "$out" "$rc"
