#!/usr/bin/env bash
# hil.two_process (docs/loop.md, "Controller and plant in two processes"): two-process-guest.sh in
# the HIL VM -- the comanipulation scene's controller (mrqp-run, on its cycle clock) and its plant
# with the emulated drives and sensors (mrqp-plant, lock-stepped to the controller's SYNCs) as two
# processes that share nothing but vcan -- then, on the host, the same scene with the same overrides
# on the simulated buses in one process (the reference) and check-two-process.py on both.
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
rm -rf "$out" "$out-reference"
# Dynamically linked programs: the image gets their shared libraries and loader (build-initramfs.sh).
args=(--script "$here/two-process-guest.sh" --add "$plant:/hil/bin/mrqp-plant" --add "$run:/hil/bin/mrqp-run"
      --add "$scene:/hil/comanipulation.yaml" --out "$out" --timeout 360)
rc=0
if [ "${MRQP_HIL_HOST:-0}" = 1 ]; then
  "$HIL_DIR/run-vm.sh" --host "${args[@]}" || rc=$?
else
  [ -n "$(hil_find_qemu)" ] || skip "qemu-system-x86_64 is not installed (Debian package qemu-system-x86)"
  hil_find_kernel || skip "no guest kernel in $HIL_CACHE"
  "$HIL_DIR/run-vm.sh" "${args[@]}" || rc=$?
fi
# The reference: one process, simulated buses, the ideal plant, the overrides the guest used.
sets=()
if [ -f "$out/overrides.txt" ]; then
  while IFS= read -r s; do [ -z "$s" ] || sets+=(--set "$s"); done < "$out/overrides.txt"
fi
ref_rc=0
"$run" "$scene" --bus sim --plant ideal "${sets[@]}" --duration 4 --no-plots --quiet --out "$out-reference" \
  > "$out-reference.log" 2>&1 || ref_rc=$?
[ "$ref_rc" = 0 ] || { echo "two-process: the reference run failed (exit $ref_rc):"; tail -5 "$out-reference.log"; }
python3 "$here/check-two-process.py" "$out" "$rc" "$out-reference/summary.json"
