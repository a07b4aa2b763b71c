#!/usr/bin/env bash
# Runs a guest script in the HIL VM (or, with --host, on this host's own vcan) and returns its
# results to the host: see tools/hil/README.md.
#
# Usage: run-vm.sh --script <guest-script.sh> [--add <host-file>[:<guest-path>]]... [--module <m>]...
#                  [--out <host-dir>] [--timeout <s>] [--append <kernel args>] [--host]
#   --script S    the POSIX sh script to run (busybox sh in the VM), with vcan0 and vcan1 up
#   --add F[:P]   copy host file/directory F to guest path P (default /hil/<name>); binaries in
#                 /hil/bin or /hil are on the guest's PATH
#   --module M    load one more kernel module (with its dependencies), e.g. can-bcm, can-gw, vxcan
#   --out D       where the files the script left in $HIL_OUT come back, plus console.log
#                 (default: a new folder under ${TMPDIR:-/tmp}, printed at the end)
#   --timeout S   kill the VM (or the host script) after S seconds (default 120); exit status 124
#   --append A    extra kernel command-line arguments
#   --host        run the script directly on this host (needs AF_CAN, vcan and root to create
#                 vcan0/vcan1 unless they exist) instead of in the VM
# Exit status: the guest script's; 124 on timeout; 125 when the VM failed (no exit status came
# back, a returned file was corrupted, /init failed); 2 on a usage error.
set -euo pipefail
shopt -s extglob
# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
HIL_DIE_STATUS=125 # a failure of this script, not of the guest script

usage_error() {
  echo "run-vm.sh: $* (see run-vm.sh --help)" >&2
  exit 2
}

script=""
adds=()
modules=()
out=""
timeout_s=120
append=""
mode=vm
while [ $# -gt 0 ]; do
  case $1 in
    --script | --add | --module | --out | --timeout | --append)
      [ $# -ge 2 ] || usage_error "$1 needs a value"
      case $1 in
        --script) script=$2 ;;
        --add) adds+=("$2") ;;
        --module) modules+=("$2") ;;
        --out) out=$2 ;;
        --timeout) timeout_s=$2 ;;
        --append) append=$2 ;;
      esac
      shift 2 ;;
    --host) mode=host; shift ;;
    -h | --help) hil_usage_text "$0"; exit 0 ;;
    *) usage_error "unknown argument '$1'" ;;
  esac
done
[ -n "$script" ] || usage_error "no --script given"
[ -f "$script" ] || hil_die "guest script '$script' not found"
if ! [[ $timeout_s =~ ^[0-9]+$ ]] || [ "$timeout_s" -eq 0 ]; then
  usage_error "--timeout wants whole seconds > 0, not '$timeout_s'"
fi

if [ -z "$out" ]; then
  out=$(mktemp -d "${TMPDIR:-/tmp}/mrqp-hil-out.XXXXXX")
fi
mkdir -p "$out" || hil_die "cannot create the output folder '$out'"
out=$(cd "$out" && pwd)
manifest=$out/.mrqp-hil-returned
# Forget what an earlier run returned into this folder, so that a stale file never passes a check.
if [ -f "$manifest" ]; then
  while IFS= read -r f; do rm -f "$out/$f"; done < "$manifest"
fi
rm -f "$manifest" "$out/console.log"
: > "$manifest"

work=$(mktemp -d "${TMPDIR:-/tmp}/mrqp-hil-run.XXXXXX")
child_pid=""
created_ifaces=()
# shellcheck disable=SC2317 # run by the EXIT trap
cleanup() {
  if [ -n "$child_pid" ] && kill -0 "$child_pid" 2> /dev/null; then
    kill -TERM "$child_pid" 2> /dev/null || true
    wait "$child_pid" 2> /dev/null || true
  fi
  local i
  for i in "${created_ifaces[@]}"; do ip link del dev "$i" 2> /dev/null || true; done
  rm -rf "$work"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

now() { echo "$EPOCHREALTIME"; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

# ---- --host: the same guest script on this host's vcan --------------------------------------------
run_on_host() {
  local i
  for i in vcan0 vcan1; do
    if ip link show dev "$i" > /dev/null 2>&1; then
      ip -d link show dev "$i" | grep -qw vcan || hil_die "--host: $i exists but is not a vcan interface"
    else
      modprobe vcan 2> /dev/null || true
      ip link add dev "$i" type vcan 2> "$work/ip.err" || hil_die "--host: cannot create $i on this host \
($(cat "$work/ip.err")): it needs AF_CAN, the vcan module and root; without --host the script runs in the VM"
      created_ifaces+=("$i")
    fi
    if ! ip link show dev "$i" | grep -q '[<,]UP[,>]'; then
      ip link set up dev "$i" 2> /dev/null || hil_die "--host: cannot set $i up (needs root)"
    fi
  done
  local root=$work/root spec src dst
  mkdir -p "$root/hil/bin" "$root/hil/out" "$root/tmp"
  for spec in "${adds[@]}" "$script:/hil/run.sh"; do
    case $spec in *:*) src=${spec%%:*} dst=${spec#*:} ;; *) src=$spec dst=/hil/ ;; esac
    [ -e "$src" ] || hil_die "--add: no such host file '$src'"
    case $dst in /*) ;; *) dst=/hil/$dst ;; esac
    case $dst in */) dst=$dst$(basename "$src") ;; esac
    mkdir -p "$root$(dirname "$dst")"
    cp -aL "$src" "$root$dst"
  done
  hil_note "running $script on this host (vcan0, vcan1; HIL_ROOT=$root)"
  local t0 rc=0
  t0=$(now)
  (
    cd "$root/hil"
    export HIL_ROOT=$root HIL_OUT=$root/hil/out HIL_MODE=host TMPDIR=$root/tmp
    export PATH=$root/hil/bin:$root/hil:$PATH
    exec timeout -k 5 "$timeout_s" sh run.sh < /dev/null
  ) 2>&1 | tee "$out/console.log" || rc=${PIPESTATUS[0]}
  local f
  while IFS= read -r f; do
    mkdir -p "$out/$(dirname "$f")"
    cp "$root/hil/out/$f" "$out/$f"
    echo "$f" >> "$manifest"
    hil_note "returned $f ($(wc -c < "$out/$f") bytes)"
  done < <(cd "$root/hil/out" && find . -type f | sed 's|^\./||' | sort)
  hil_note "host script ran $(elapsed "$t0" "$(now)") s; results in $out"
  if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
    hil_note "error: the script timed out after $timeout_s s"
    exit 124
  fi
  exit "$rc"
}
if [ $mode = host ]; then run_on_host; fi

# ---- the VM ---------------------------------------------------------------------------------------
qemu=$(hil_find_qemu)
[ -n "$qemu" ] || hil_die "qemu-system-x86_64 not found: run tools/hil/setup.sh"
hil_find_kernel || hil_die "no guest kernel in $HIL_CACHE: run tools/hil/setup.sh"

t_build=$(now)
initrd=$work/initramfs.cpio.gz
build_args=(--script "$script")
for spec in "${adds[@]}"; do build_args+=(--add "$spec"); done
for m in "${modules[@]}"; do build_args+=(--module "$m"); done
"$HIL_DIR/build-initramfs.sh" "$initrd" "${build_args[@]}" || hil_die "building the initramfs failed"
build_s=$(elapsed "$t_build" "$(now)")

console=$out/console.log
: > "$console"
fifo=$work/console.fifo
mkfifo "$fifo"
# Boot-time savers for an emulated CPU (README.md "Timing"): no Spectre/Meltdown mitigations (they
# cost alternatives patching and slower syscalls under TCG), no crypto self-tests (~1 s under TCG).
HIL_SPEED_ARGS="mitigations=off cryptomgr.notests"
kernel_args="console=ttyS0 quiet panic=-1 $HIL_SPEED_ARGS mrqp.script=/hil/run.sh${append:+ $append}"
qemu_cmd=("$qemu" -accel tcg -nographic -nodefaults -no-user-config -serial stdio -monitor none
          -no-reboot -m 512M -nic none
          -kernel "$HIL_KERNEL_IMAGE" -initrd "$initrd" -append "$kernel_args")
hil_note "booting $HIL_KVER under TCG (initramfs built in $build_s s), timeout $timeout_s s"
t_start=$(now)
timeout -k 5 "$timeout_s" "${qemu_cmd[@]}" < /dev/null > "$fifo" 2> "$work/qemu.err" &
child_pid=$!

# Reads the serial console: logs every line, shows the guest's own output, decodes returned files.
booted="" t_booted="" exit_code="" errors=() file_name="" file_size="" file_sum="" file_enc=""
b64=$work/file.b64
finish_file() {
  local dec=$work/file.bin
  local decode=(cat)
  [ "$file_enc" != gzip ] || decode=(gzip -dc)
  exec 4>&-
  if ! base64 -d "$b64" 2> /dev/null | "${decode[@]}" > "$dec" 2> /dev/null; then
    errors+=("returned file $file_name: bad base64 or gzip data (console output interleaved?)")
  elif [ "$(wc -c < "$dec")" != "$file_size" ] || [ "$(sha256sum "$dec" | cut -d' ' -f1)" != "$file_sum" ]; then
    errors+=("returned file $file_name: size or sha256 differs from what the guest sent (console output interleaved?)")
  elif [[ ! $file_name =~ ^[A-Za-z0-9._-]+(/[A-Za-z0-9._-]+)*$ ]] || [[ /$file_name/ == */../* ]]; then
    errors+=("returned file '$file_name': refused name")
  else
    mkdir -p "$out/$(dirname "$file_name")"
    mv "$dec" "$out/$file_name"
    echo "$file_name" >> "$manifest"
    hil_note "returned $file_name ($file_size bytes)"
  fi
  file_name=""
}
while IFS= read -r line || [ -n "$line" ]; do
  line=${line%$'\r'}
  printf '%s\n' "$line" >&3
  # Firmware and terminal control sequences (SeaBIOS resets the terminal): never to the user.
  line=${line//$'\e'c/}
  line=${line//$'\e'\[*([0-9;?])[A-Za-z]/}
  if [ -n "$file_name" ]; then
    if [ "$line" = "==MRQP-END==" ]; then finish_file; continue; fi
    if [[ $line =~ ^[A-Za-z0-9+/=]*$ ]]; then printf '%s\n' "$line" >&4; continue; fi
    # Anything else inside a file block is console noise (a kernel message): finish_file will
    # tell if it damaged the file; show it.
  fi
  if [[ $line =~ ==MRQP-BOOTED\ ([0-9.]+)== ]]; then
    t_booted=$(now)
    booted=${BASH_REMATCH[1]}
    hil_note "guest booted in $(elapsed "$t_start" "$t_booted") s (qemu start to guest script start; guest kernel uptime $booted s)"
  elif [[ $line =~ ==MRQP-FILE\ ([^ ]+)\ ([0-9]+)\ ([0-9a-f]{64})( gzip)?== ]]; then
    file_name=${BASH_REMATCH[1]} file_size=${BASH_REMATCH[2]} file_sum=${BASH_REMATCH[3]}
    file_enc=${BASH_REMATCH[4]# }
    exec 4> "$b64"
  elif [[ $line =~ ==MRQP-ERROR\ (.*)== ]]; then
    errors+=("guest: ${BASH_REMATCH[1]}")
  elif [[ $line =~ ==MRQP-EXIT\ ([0-9]+)== ]]; then
    exit_code=${BASH_REMATCH[1]}
  elif [ -n "$booted" ] && [ -z "$exit_code" ]; then
    printf '%s\n' "$line"
  fi
done < "$fifo" 3>> "$console"
qemu_rc=0
wait "$child_pid" || qemu_rc=$?
child_pid=""
t_end=$(now)
[ -z "$file_name" ] || errors+=("returned file $file_name: cut short (no ==MRQP-END==)")

script_s="?"
[ -z "$t_booted" ] || script_s=$(elapsed "$t_booted" "$t_end")
hil_note "timing: initramfs $build_s s, boot $( [ -n "$t_booted" ] && elapsed "$t_start" "$t_booted" || echo '?') s, \
guest script and shutdown $script_s s, VM total $(elapsed "$t_start" "$t_end") s"
hil_note "console log: $console; returned files in $out"

show_console_tail() {
  echo "---- last lines of the serial console ($console) ----" >&2
  tail -n 25 "$console" | sed 's/\x1b[^a-zA-Z]*[a-zA-Z]//g' >&2
  if [ -s "$work/qemu.err" ]; then
    echo "---- qemu's stderr ----" >&2
    cat "$work/qemu.err" >&2
  fi
}
if [ "$qemu_rc" -eq 124 ] || [ "$qemu_rc" -eq 137 ]; then
  show_console_tail
  hil_note "error: timed out after $timeout_s s (qemu killed)$( [ -n "$booted" ] || echo '; the guest never booted')"
  exit 124
fi
for e in "${errors[@]}"; do hil_note "error: $e"; done
if [ -z "$exit_code" ]; then
  show_console_tail
  hil_note "error: the guest reported no exit status (qemu exited with $qemu_rc; kernel panic, or /init died?)"
  exit 125
fi
if [ "$exit_code" -ne 0 ]; then
  hil_note "guest script exited with status $exit_code"
  exit "$exit_code"
fi
[ ${#errors[@]} -eq 0 ] || exit 125
hil_note "guest script exited with status 0"
exit 0
