#!/usr/bin/env bash
# Prepares the hardware-in-the-loop VM tooling (tools/hil/README.md):
#  1. installs the Debian packages it needs (qemu, busybox-static, can-utils, cpio, ...), touching
#     apt only when one is missing;
#  2. downloads Debian's kernel package (the versioned linux-image-6.1.*-amd64 that
#     linux-image-amd64 points to) with `apt-get download` and extracts it into the cache
#     (default build/hil/cache, or $MRQP_HIL_CACHE). The kernel is never installed on the host.
# Idempotent and quick when everything is present: a second run does not touch apt at all.
#
# Usage: tools/hil/setup.sh [--refresh]   (--refresh: fetch the current kernel package again)
set -euo pipefail
# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

refresh=0
for arg in "$@"; do
  case $arg in
    --refresh) refresh=1 ;;
    -h | --help) hil_usage_text "$0"; exit 0 ;;
    *) hil_die "setup.sh: unknown argument '$arg' (usage: setup.sh [--refresh])" ;;
  esac
done

packages=(qemu-system-x86 busybox-static can-utils cpio xz-utils gzip iproute2 kmod coreutils)

apt_updated=0
apt_update_once() {
  if [ $apt_updated -eq 0 ]; then
    hil_note "apt-get update"
    apt-get update -qq || hil_die "apt-get update failed"
    apt_updated=1
  fi
}

# ---- 1. Debian packages -------------------------------------------------------------------------
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then
    hil_die "missing Debian packages: ${missing[*]}; run this script as root or: apt-get install ${missing[*]}"
  fi
  hil_note "installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt_update_once
  apt-get install -y -qq --no-install-recommends "${missing[@]}" \
    || hil_die "apt-get install ${missing[*]} failed"
fi

# ---- 2. the guest kernel ------------------------------------------------------------------------
# Debian's vmlinuz is xz-compressed, and its decompressor runs for ~15 s under TCG emulation. The
# kernel has CONFIG_PVH, so qemu can boot the uncompressed ELF vmlinux directly (boot ~3x faster):
# extract it once here, next to the vmlinuz, as boot/vmlinux-<version>.
make_vmlinux() {
  local z=$HIL_VMLINUZ out=$HIL_KERNEL_ROOT/boot/vmlinux-$HIL_KVER off
  [ -f "$out" ] && return 0
  if ! grep -q '^CONFIG_PVH=y' "$HIL_KERNEL_ROOT/boot/config-$HIL_KVER" 2>/dev/null; then
    hil_note "kernel $HIL_KVER has no PVH entry: qemu will boot the compressed vmlinuz (slower)"
    return 0
  fi
  off=$(LC_ALL=C grep -obUaP '\xfd7zXZ\x00' "$z" | head -n 1 | cut -d: -f1 || true)
  if [ -z "$off" ]; then
    hil_note "no xz payload in $z: qemu will boot the compressed vmlinuz (slower)"
    return 0
  fi
  # (xz stops after the first stream: tail may die of SIGPIPE, which is fine)
  if { tail -c +$((off + 1)) "$z" || true; } | xz -dc --single-stream > "$out.tmp" 2> /dev/null \
      && [ "$(head -c 4 "$out.tmp" | od -An -c | tr -d ' ')" = '177ELF' ]; then
    mv "$out.tmp" "$out"
    hil_note "extracted the uncompressed kernel $out"
  else
    rm -f "$out.tmp"
    hil_note "could not extract vmlinux from $z: qemu will boot the compressed vmlinuz (slower)"
  fi
}

if [ $refresh -eq 0 ] && hil_find_kernel; then
  make_vmlinux
  exit 0
fi

# The versioned image package that the linux-image-amd64 meta-package depends on, for example
# linux-image-6.1.0-56-amd64 (the module-carrying package; Debian ships the signed and unsigned
# flavours with identical modules).
kernel_pkg() {
  apt-cache depends linux-image-amd64 2>/dev/null \
    | sed -n 's/^ *Depends: \(linux-image-[0-9][^ ]*-amd64\)$/\1/p' | head -n 1
}
pkg=$(kernel_pkg)
if [ -z "$pkg" ]; then
  [ "$(id -u)" -eq 0 ] || hil_die "apt knows no linux-image-amd64; run 'apt-get update' as root first"
  apt_update_once
  pkg=$(kernel_pkg)
fi
[ -n "$pkg" ] || hil_die "cannot find the kernel package behind linux-image-amd64 (apt-cache depends linux-image-amd64)"

mkdir -p "$HIL_CACHE/debs"
deb=$(find "$HIL_CACHE/debs" -maxdepth 1 -name "${pkg}_*.deb" | sort | tail -n 1)
if [ $refresh -eq 1 ] || [ -z "$deb" ]; then
  hil_note "downloading $pkg (apt-get download; not installed on the host)"
  dl=$(mktemp -d "$HIL_CACHE/debs/.dl.XXXXXX")
  # apt's _apt sandbox user may not write into the cache: download as the current user.
  if ! (cd "$dl" && apt-get download -q -o APT::Sandbox::User="$(id -un)" "$pkg"); then
    rm -rf "$dl"
    hil_die "apt-get download $pkg failed"
  fi
  deb=$(find "$dl" -maxdepth 1 -name '*.deb' | head -n 1)
  [ -n "$deb" ] || hil_die "apt-get download $pkg produced no .deb"
  mv "$deb" "$HIL_CACHE/debs/"
  rm -rf "$dl"
  deb=$HIL_CACHE/debs/${deb##*/}
fi

hil_note "extracting ${deb##*/} into $HIL_KERNEL_ROOT"
tmp=$(mktemp -d "$HIL_CACHE/.kernel.XXXXXX")
if ! dpkg-deb -x "$deb" "$tmp"; then
  rm -rf "$tmp"
  hil_die "dpkg-deb -x $deb failed"
fi
# The package ships no modules.dep (depmod makes it at install time): make it here.
kver=$(find "$tmp/boot" -maxdepth 1 -name 'vmlinuz-*' | sed 's|.*/vmlinuz-||' | head -n 1)
[ -n "$kver" ] || { rm -rf "$tmp"; hil_die "$deb holds no boot/vmlinuz-*"; }
depmod_bin=$(command -v depmod || echo /sbin/depmod)
[ -x "$depmod_bin" ] || { rm -rf "$tmp"; hil_die "depmod not found (Debian package kmod)"; }
if ! "$depmod_bin" -b "$tmp" "$kver"; then
  rm -rf "$tmp"
  hil_die "depmod -b $tmp $kver failed"
fi
dpkg-deb -f "$deb" Package Version > "$tmp/.mrqp-hil-kernel"
rm -rf "$HIL_KERNEL_ROOT"
mv "$tmp" "$HIL_KERNEL_ROOT"
# The images are root-only readable in the package (0600); the VM runs as any user.
chmod a+r "$HIL_KERNEL_ROOT"/boot/vmlinuz-* 2>/dev/null || true
hil_find_kernel || hil_die "the extracted $pkg holds no boot/vmlinuz-* with modules.dep"
make_vmlinux
hil_note "kernel $HIL_KVER ready: $HIL_VMLINUZ"
