#!/usr/bin/env bash
# Runs the SocketCAN tests on a real Linux CAN stack where the host kernel has none: boots
# Debian's kernel (linux-image-amd64, with the can, can-raw, can-dev and vcan modules) in QEMU
# with a busybox initramfs that creates vcan0 (CAN FD MTU) and runs a statically linked
# test_drivers_socketcan_vcan.
#
#   tests/drivers/vcan_vm.sh <build dir>       (needs qemu-system-x86, busybox-static, apt access)
#
# Exit status: the test program's (0 = passed). Runs under TCG (about 10 s to boot and test).
set -euo pipefail
build=$(cd "$1" && pwd)
src=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# 1. The kernel and its modules, unpacked (not installed on the host).
pkg=$(apt-cache depends linux-image-amd64 | awk '/Depends: linux-image-[0-9]/{print $2; exit}')
(cd "$work" && apt-get download "$pkg" > /dev/null 2>&1)
dpkg-deb -x "$work"/linux-image-*.deb "$work/k"
kver=$(ls "$work/k/lib/modules")
mods="$work/k/lib/modules/$kver/kernel"

# 2. The test, statically linked against the built libraries.
g++ -std=c++17 -O1 -static -I"$src/drivers/include" -I"$src/firmware_if/include" \
  "$src/tests/catch_main.cpp" "$src/tests/drivers/test_socketcan_vcan.cpp" \
  "$build/drivers/libmrqp_drivers.a" "$build/firmware_if/libmrqp_firmware_if.a" -o "$work/vcan_test" 2> /dev/null

# 3. The initramfs.
root="$work/initrd"
mkdir -p "$root"/{bin,proc,sys,dev,mods}
cp "$(command -v busybox)" "$root/bin/busybox"
for a in sh mount insmod ip echo poweroff; do ln -s busybox "$root/bin/$a"; done
cp "$mods/net/can/can.ko" "$mods/net/can/can-raw.ko" "$mods/drivers/net/can/dev/can-dev.ko" \
   "$mods/drivers/net/can/vcan.ko" "$root/mods/"
cp "$work/vcan_test" "$root/bin/"
cat > "$root/init" <<'INIT'
#!/bin/sh
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
for m in can can-raw can-dev vcan; do insmod /mods/$m.ko; done
ip link add dev vcan0 type vcan
ip link set vcan0 mtu 72
ip link set vcan0 up
/bin/vcan_test
echo "=== VCAN TEST EXIT $? ==="
poweroff -f
INIT
chmod +x "$root/init"
(cd "$root" && find . | cpio -o -H newc 2> /dev/null | gzip > "$work/initrd.gz")

# 4. Boot.
timeout 600 qemu-system-x86_64 -accel tcg -m 512 -nographic -no-reboot \
  -kernel "$work/k/boot/vmlinuz-$kver" -initrd "$work/initrd.gz" \
  -append "console=ttyS0 panic=-1 loglevel=4" > "$work/console.log" 2>&1 || true
sed -n '/vcan_test\|===/,$p' "$work/console.log" | grep -av "reboot: Power down" || true
code=$(grep -ao "=== VCAN TEST EXIT [0-9]*" "$work/console.log" | awk '{print $5}')
exit "${code:-1}"
