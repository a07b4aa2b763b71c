#!/bin/sh
# Runs an aarch64 Linux program on this (other) machine under qemu user-mode emulation: the
# CMAKE_CROSSCOMPILING_EMULATOR of cmake/toolchains/aarch64-linux-gnu.cmake.
#   qemu-aarch64.sh PROGRAM [ARGS...]
# The dynamic loader and the C/C++ runtime of the target are Debian's cross ones
# (/usr/aarch64-linux-gnu, from g++-aarch64-linux-gnu, the ones the programs were linked with);
# arm64 multiarch libraries (/usr/lib/aarch64-linux-gnu, MRQP_EXTRA_ARM64_PACKAGES) are found
# after them. The target's LD_LIBRARY_PATH puts the cross runtime first, so that the loader never
# meets the C library of libc6:arm64, which multiarch packages bring along (a loader and a C
# library from two different builds must not be mixed). MRQP_QEMU_AARCH64 names another qemu
# binary, QEMU_LD_PREFIX another target root.
: "${QEMU_LD_PREFIX:=/usr/aarch64-linux-gnu}"
export QEMU_LD_PREFIX
QEMU_SET_ENV="LD_LIBRARY_PATH=$QEMU_LD_PREFIX/lib${QEMU_SET_ENV:+,$QEMU_SET_ENV}"
export QEMU_SET_ENV
for q in ${MRQP_QEMU_AARCH64:-} qemu-aarch64 qemu-aarch64-static; do
  if command -v "$q" > /dev/null 2>&1; then
    exec "$q" "$@"
  fi
done
echo "qemu-aarch64.sh: no qemu-aarch64 or qemu-aarch64-static on PATH: install one with" \
     "tools/setup-deps.sh --target aarch64 (Debian qemu-user)" >&2
exit 127
