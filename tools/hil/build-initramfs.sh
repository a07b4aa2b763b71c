#!/usr/bin/env bash
# Builds the initramfs of the HIL VM (tools/hil/README.md): busybox-static with its applet links,
# can-utils with their shared libraries and dynamic loader, the CAN kernel modules of the cached
# Debian kernel (can, can-raw, can-dev, vcan and their dependencies, decompressed), and an /init
# that mounts proc/sys/dev/tmp, loads the modules, creates vcan0 and vcan1, runs the guest script,
# returns the files the script left in $HIL_OUT over the serial console and powers off.
#
# Usage: build-initramfs.sh <out.cpio.gz> [--script <guest-script>] [--add <host-file>[:<guest-path>]]...
#                           [--module <kernel-module>]...
#   --script F          the guest script, stored as /hil/run.sh (what /init runs unless the kernel
#                       command line says mrqp.script=<guest-path>)
#   --add F[:P]         copy host file or directory F into the image at P (default /hil/<name of F>;
#                       a P ending in / gets the name appended). Dynamically linked ELF files get
#                       their shared libraries and loader copied too (ldd).
#   --module M          load kernel module M (and what it depends on) as well, e.g. can-bcm, vxcan
# Needs tools/hil/setup.sh to have run (packages and kernel cache).
set -euo pipefail
# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

usage_error() {
  echo "build-initramfs.sh: $* (see build-initramfs.sh --help)" >&2
  exit 2
}

out=""
adds=()
modules=(can can-raw can-dev vcan)
while [ $# -gt 0 ]; do
  case $1 in
    --add)
      [ $# -ge 2 ] || usage_error "--add needs <host-file>[:<guest-path>]"
      adds+=("$2"); shift 2 ;;
    --script)
      [ $# -ge 2 ] || usage_error "--script needs a file"
      adds+=("$2:/hil/run.sh"); shift 2 ;;
    --module)
      [ $# -ge 2 ] || usage_error "--module needs a module name"
      modules+=("$2"); shift 2 ;;
    -h | --help) hil_usage_text "$0"; exit 0 ;;
    -*) usage_error "unknown option '$1'" ;;
    *)
      [ -z "$out" ] || usage_error "more than one output file ('$out', '$1')"
      out=$1; shift ;;
  esac
done
[ -n "$out" ] || usage_error "no output file given"

hil_find_kernel || hil_die "no kernel in the cache $HIL_CACHE: run tools/hil/setup.sh first"
for tool in cpio gzip ldd; do
  command -v "$tool" > /dev/null || hil_die "'$tool' not found: run tools/hil/setup.sh"
done

# busybox-static's busybox: the host's /bin/busybox may be the dynamic one of package busybox.
busybox=""
for b in $(dpkg -L busybox-static 2>/dev/null | grep '/busybox$' || true) /bin/busybox /usr/bin/busybox; do
  if [ -x "$b" ] && ! ldd "$b" > /dev/null 2>&1; then busybox=$b; break; fi
done
[ -n "$busybox" ] || hil_die "no statically linked busybox: run tools/hil/setup.sh (package busybox-static)"

root=$(mktemp -d "${TMPDIR:-/tmp}/mrqp-hil-initramfs.XXXXXX")
trap 'rm -rf "$root"' EXIT
mkdir -p "$root"/{bin,sbin,usr/bin,usr/sbin,dev,proc,sys,tmp,root,etc,hil/bin,hil/out,lib/modules/mrqp-hil}
chmod 1777 "$root/tmp"

# ---- busybox ----------------------------------------------------------------------------------
cp "$busybox" "$root/bin/busybox"
# /init makes the other applet links itself (busybox --install -s: instant in the guest, where
# ~400 ln processes here would cost seconds on a busy host).
ln -s busybox "$root/bin/sh"
# The kernel's built-in initramfs has /dev/console already; add it when we can, for any kernel.
if [ "$(id -u)" -eq 0 ]; then mknod -m 600 "$root/dev/console" c 5 1; fi

# ---- copying host ELF files with their shared libraries ------------------------------------------
is_elf() { [ -f "$1" ] && [ "$(head -c 4 "$1" | od -An -c | tr -d ' ')" = '177ELF' ]; }
copy_libs() { # copy_libs <elf>: the libraries and loader ldd reports, at the same paths
  local f=$1 line lib
  ldd "$f" > /dev/null 2>&1 || return 0 # statically linked
  while read -r line; do
    case $line in
      *'=> not found'*) hil_die "$f needs a library the host lacks: $line" ;;
      *'=> /'*) lib=${line#*=> }; lib=${lib%% (*} ;;
      /*) lib=${line%% (*} ;;
      *) continue ;;
    esac
    if [ ! -e "$root$lib" ]; then
      mkdir -p "$root$(dirname "$lib")"
      cp -L "$lib" "$root$lib"
    fi
  done < <(ldd "$f")
}
add_file() { # add_file <host-path> <guest-path>
  local src=$1 dst=$2
  [ -e "$src" ] || hil_die "--add: no such host file '$src'"
  case $dst in /*) ;; *) dst=/hil/$dst ;; esac
  case $dst in */) dst=$dst$(basename "$src") ;; esac
  mkdir -p "$root$(dirname "$dst")"
  cp -aL "$src" "$root$dst"
  local f
  while IFS= read -r -d '' f; do
    if is_elf "$f"; then copy_libs "$f"; fi
  done < <(find "$src" -type f -print0)
}

# ---- can-utils ----------------------------------------------------------------------------------
for t in candump cansend cangen canbusload canplayer cansequence cansniffer; do
  p=$(command -v "$t" || true)
  if [ -z "$p" ]; then
    case $t in candump | cansend | cangen) hil_die "$t not found: run tools/hil/setup.sh (package can-utils)" ;; esac
    continue
  fi
  add_file "$p" "/usr/bin/$t"
done

# ---- kernel modules ---------------------------------------------------------------------------
# modules.dep lines: "kernel/net/can/can-raw.ko: kernel/net/can/can.ko" (all dependencies listed).
modpath() { # the modules.dep path of a module name ('-' and '_' are the same in module names)
  local want=${1//-/_}
  awk -F: -v want="$want" '{ n = $1; sub(/.*\//, "", n); sub(/\.ko(\.(xz|gz|zst))?$/, "", n);
                             gsub(/-/, "_", n); if (n == want) { print $1; exit } }' "$HIL_MODDIR/modules.dep"
}
declare -A mod_done=()
load_order=()
add_module_path() { # add_module_path <modules.dep path>: its dependencies first, then itself
  local p=$1 d deps
  [ -z "${mod_done[$p]:-}" ] || return 0
  mod_done[$p]=1
  deps=$(awk -F: -v p="$p" '$1 == p { print $2; exit }' "$HIL_MODDIR/modules.dep")
  for d in $deps; do add_module_path "$d"; done
  local name; name=$(basename "$p"); name=${name%%.ko*}
  case $p in
    *.ko.xz) xz -dc "$HIL_MODDIR/$p" > "$root/lib/modules/mrqp-hil/$name.ko" ;;
    *.ko.gz) gzip -dc "$HIL_MODDIR/$p" > "$root/lib/modules/mrqp-hil/$name.ko" ;;
    *.ko.zst) zstd -qdc "$HIL_MODDIR/$p" > "$root/lib/modules/mrqp-hil/$name.ko" ;;
    *.ko) cp "$HIL_MODDIR/$p" "$root/lib/modules/mrqp-hil/$name.ko" ;;
    *) hil_die "unexpected module file $p" ;;
  esac
  load_order+=("$name")
}
for m in "${modules[@]}"; do
  p=$(modpath "$m")
  if [ -z "$p" ]; then
    # Built into the kernel needs no loading.
    if grep -q "/${m//_/-}\.ko$\|/${m//-/_}\.ko$" "$HIL_MODDIR/modules.builtin" 2>/dev/null; then continue; fi
    hil_die "kernel $HIL_KVER has no module '$m' (searched $HIL_MODDIR/modules.dep)"
  fi
  add_module_path "$p"
done
printf '%s\n' "${load_order[@]}" > "$root/lib/modules/mrqp-hil/modules.load"

# ---- the guest's files ----------------------------------------------------------------------------
for spec in "${adds[@]}"; do
  case $spec in
    *:*) add_file "${spec%%:*}" "${spec#*:}" ;;
    *) add_file "$spec" "/hil/" ;;
  esac
done

# ---- /init ------------------------------------------------------------------------------------------
cat > "$root/init" <<'INIT'
#!/bin/sh
# /init of the mrqp HIL initramfs, made by tools/hil/build-initramfs.sh. Console protocol (serial):
#   ==MRQP-BOOTED <uptime s>==                  vcan0/vcan1 are up, the guest script starts
#   ==MRQP-FILE <name> <bytes> <sha256> gzip==  then the file, gzip-compressed, in base64, then
#                                               ==MRQP-END== (bytes and sha256: of the file itself)
#   ==MRQP-ERROR <message>==                    /init itself failed (then EXIT 125)
#   ==MRQP-EXIT <code>==                        the guest script's exit status
/bin/busybox --install -s
export PATH=/hil/bin:/hil:/usr/local/bin:/usr/bin:/bin:/usr/sbin:/sbin
export HOME=/root TMPDIR=/tmp HIL_ROOT='' HIL_OUT=/hil/out HIL_MODE=vm
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev 2>/dev/null
mount -t tmpfs tmpfs /tmp
mkdir -p "$HIL_OUT"

hil_return() { # hil_return <file> <name>
  echo "==MRQP-FILE $2 $(wc -c < "$1") $(sha256sum "$1" | cut -d' ' -f1) gzip=="
  gzip -c "$1" | base64
  echo "==MRQP-END=="
}
hil_finish() { # hil_finish <code>
  # What the script left running (a candump in the background...) must neither write into the
  # file transfer nor hold a file open: TERM lets it flush, KILL makes sure.
  kill -TERM -1 2>/dev/null && sleep 0.2 && kill -KILL -1 2>/dev/null
  cd "$HIL_OUT" && find . -type f | sed 's|^\./||' | sort | while read -r f; do
    case $f in *[!A-Za-z0-9._/-]*) echo "==MRQP-ERROR not returning '$f': name has characters other than A-Za-z0-9._/-==" ;;
               *) hil_return "$f" "$f" ;; esac
  done
  echo "==MRQP-EXIT $1=="
  sync
  poweroff -f
}
hil_fail() {
  echo "==MRQP-ERROR $*=="
  dmesg | tail -n 20
  hil_finish 125
}

while read -r m; do
  insmod "/lib/modules/mrqp-hil/$m.ko" || hil_fail "insmod $m failed"
done < /lib/modules/mrqp-hil/modules.load
ip link set lo up
for i in 0 1; do
  ip link add dev "vcan$i" type vcan || hil_fail "ip link add dev vcan$i type vcan failed"
  ip link set up "vcan$i" || hil_fail "ip link set up vcan$i failed"
done

script=/hil/run.sh
read -r cmdline < /proc/cmdline
for arg in $cmdline; do
  case $arg in mrqp.script=*) script=${arg#mrqp.script=} ;; esac
done
[ -f "$script" ] || hil_fail "no guest script $script in the initramfs"
chmod +x "$script"

echo "==MRQP-BOOTED $(cut -d' ' -f1 /proc/uptime)=="
cd /hil || hil_fail "no /hil"
sh "$script" < /dev/null
rc=$?
cd /
hil_finish "$rc"
INIT
chmod 755 "$root/init"

mkdir -p "$(dirname "$out")"
(cd "$root" && find . -mindepth 1 | LC_ALL=C sort | cpio --quiet -o -H newc -R 0:0 | gzip -1) > "$out.tmp"
mv "$out.tmp" "$out"
