#!/usr/bin/env bash
# CTest test hil.stream_strict (tools/hil/CMakeLists.txt): stream-strict-guest.sh in the HIL VM with
# the static mrqp-drive-emu and mrqp-stream, then check-stream-strict.py on the host.
# Usage: ctest-stream-strict.sh <out-dir> <mrqp-drive-emu> <mrqp-stream>
# Exit status 77 (CTest SKIP_RETURN_CODE) when qemu or the guest kernel is missing.
set -euo pipefail
# shellcheck source=../lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/../lib.sh"
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
out=${1:?usage: ctest-stream-strict.sh <out-dir> <emu> <stream>}
emu=${2:?} stream=${3:?}
skip() {
  echo "hil.stream_strict SKIPPED: $* -- run tools/hil/setup.sh to install the HIL VM"
  exit 77
}
for b in "$emu" "$stream"; do
  if ldd "$b" > /dev/null 2>&1; then
    echo "hil.stream_strict: $b is not statically linked" >&2
    exit 1
  fi
done
rm -rf "$out"
args=(--script "$here/stream-strict-guest.sh" --add "$emu:/hil/bin/mrqp-drive-emu"
      --add "$stream:/hil/bin/mrqp-stream" --add "$here/emu-strict.yaml:/hil/emu-strict.yaml" --out "$out"
      --timeout 250)
if [ "${MRQP_HIL_HOST:-0}" = 1 ]; then
  "$HIL_DIR/run-vm.sh" --host "${args[@]}"
else
  [ -n "$(hil_find_qemu)" ] || skip "qemu-system-x86_64 is not installed (Debian package qemu-system-x86)"
  hil_find_kernel || skip "no guest kernel in $HIL_CACHE"
  "$HIL_DIR/run-vm.sh" "${args[@]}"
fi
python3 "$here/check-stream-strict.py" "$out"
