# Shared helpers of the HIL tooling (sourced by setup.sh, build-initramfs.sh, run-vm.sh).
# shellcheck shell=bash
# shellcheck disable=SC2034 # the HIL_* variables set here are used by the scripts that source it

HIL_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
HIL_PROJECT_ROOT=$(cd "$HIL_DIR/../.." && pwd)
# Where setup.sh keeps the downloaded and extracted Debian kernel package.
HIL_CACHE=${MRQP_HIL_CACHE:-$HIL_PROJECT_ROOT/build/hil/cache}
HIL_KERNEL_ROOT=$HIL_CACHE/kernel
HIL_KERNEL_STAMP=$HIL_KERNEL_ROOT/.mrqp-hil-kernel

hil_die() {
  echo "mrqp hil: error: $*" >&2
  exit "${HIL_DIE_STATUS:-1}"
}

hil_note() {
  echo "mrqp hil: $*" >&2
}

# Sets HIL_VMLINUZ, HIL_KVER, HIL_MODDIR and HIL_KERNEL_IMAGE (what qemu boots: the uncompressed
# vmlinux that setup.sh extracts, booted through its PVH entry, or else the vmlinuz) from the kernel
# cache; returns 1 when it is not there.
hil_find_kernel() {
  [ -f "$HIL_KERNEL_STAMP" ] || return 1
  local v
  v=$(find "$HIL_KERNEL_ROOT/boot" -maxdepth 1 -name 'vmlinuz-*' 2>/dev/null | sort | tail -n 1)
  [ -n "$v" ] || return 1
  HIL_VMLINUZ=$v
  HIL_KVER=${v##*/vmlinuz-}
  local d
  for d in "$HIL_KERNEL_ROOT/lib/modules/$HIL_KVER" "$HIL_KERNEL_ROOT/usr/lib/modules/$HIL_KVER"; do
    if [ -f "$d/modules.dep" ]; then
      HIL_MODDIR=$d
      HIL_KERNEL_IMAGE=$HIL_VMLINUZ
      if [ -f "$HIL_KERNEL_ROOT/boot/vmlinux-$HIL_KVER" ]; then
        HIL_KERNEL_IMAGE=$HIL_KERNEL_ROOT/boot/vmlinux-$HIL_KVER
      fi
      return 0
    fi
  done
  return 1
}

# The qemu binary, or empty.
hil_find_qemu() {
  command -v qemu-system-x86_64 2>/dev/null || true
}

# Prints the calling script's header comment (its usage text).
hil_usage_text() {
  awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$1"
}
