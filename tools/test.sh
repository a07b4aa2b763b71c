#!/usr/bin/env bash
# The whole test suite: installs what it needs, builds the release configuration and runs every
# test, then builds with AddressSanitizer + UndefinedBehaviorSanitizer and runs the unit tests
# again, then builds the libFuzzer harnesses with clang and runs each briefly, then checks that an
# installed mrqp serves a user's own CMake project, and last
# cross-compiles for aarch64 and runs those tests under qemu-aarch64 emulation.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
jobs=$(nproc)
step() { printf '\n== %s\n' "$*"; }

step "dependencies"
./tools/setup-deps.sh
./tools/hil/setup.sh   # qemu, busybox, the Debian kernel with vcan for the hardware-in-the-loop tests

step "release build"
# Configure presets of CMakePresets.json: release (build/release) and asan (build/asan).
cmake --preset release > build-release-configure.log 2>&1 \
  || { cat build-release-configure.log; exit 1; }
rm -f build-release-configure.log
cmake --build --preset release -j"$jobs"
step "release tests"
ctest --preset release -j"$jobs"

step "sanitizer build (ASan + UBSan)"
cmake --preset asan > /dev/null
cmake --build --preset asan -j"$jobs"
step "sanitizer tests (unit)"
ctest --preset asan -j"$jobs"  # label unit, with the ASAN/UBSAN/LSAN options of the preset

step "fuzz build (clang: libFuzzer + ASan + UBSan, the harnesses of tests/fuzz)"
cmake --preset fuzz > /dev/null
cmake --build --preset fuzz -j"$jobs"
step "fuzz tests (each harness replays tests/data/fuzz and its seeds, then fuzzes for 5 s)"
ctest --preset fuzz -j"$jobs"

step "installed package: find_package(mrqp) from a user project"
"$root/tests/install/check_install.sh" "$root/build/release"

step "aarch64 cross build, tests under qemu-aarch64 (docs/cross-compiling.md)"
# The workflow preset of the docs, with the release build's mrqp-gen as the host generator (no
# second host build). Installs the cross compiler and qemu-user first (setup-deps.sh, as root).
have_aarch64() {
  command -v aarch64-linux-gnu-g++ > /dev/null &&
    { command -v qemu-aarch64 > /dev/null || command -v qemu-aarch64-static > /dev/null; }
}
./tools/setup-deps.sh --target aarch64 || [ "$(id -u)" -ne 0 ]  # as root, a failed install fails
if have_aarch64; then
  host_gen=$root/build/release/model_gen/mrqp-gen
  [ -x "$host_gen" ] || host_gen=""
  MRQP_HOST_GENERATOR=$host_gen CTEST_PARALLEL_LEVEL=$jobs CMAKE_BUILD_PARALLEL_LEVEL=$jobs \
    cmake --workflow --preset aarch64
else
  printf 'aarch64: SKIPPED: no aarch64-linux-gnu-g++ or qemu-aarch64 on this machine, and they could not\n'
  printf '         be installed (run tools/setup-deps.sh --target aarch64 as root)\n'
fi

printf '\nall tests passed\n'
