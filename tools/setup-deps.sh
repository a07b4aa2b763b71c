#!/usr/bin/env bash
# Installs the Debian 12 packages mrqp needs to build, test and run its scenario.
# Idempotent: when every package is present it returns at once without touching apt.
#
# Usage: tools/setup-deps.sh [--target aarch64]
#   --target aarch64   also what a cross build for an aarch64 robot computer needs
#                      (docs/cross-compiling.md): the cross compiler g++-aarch64-linux-gnu, the
#                      user-mode emulator qemu-aarch64 that runs the target tests, and the target's
#                      own libraries as Debian arm64 packages through multiarch (below).
#                      Same as MRQP_TARGET_ARCH=aarch64.
# Environment:
#   MRQP_EXTRA_PACKAGES         more host packages, space-separated
#   MRQP_EXTRA_ARM64_PACKAGES   more target packages, space-separated Debian names without the
#                               ":arm64" suffix (e.g. "libccd-dev"); with --target aarch64 they are
#                               installed as <name>:arm64 after `dpkg --add-architecture arm64`.
set -euo pipefail

usage() { sed -n '5,16s/^# \{0,1\}//p' "$0"; }
target=${MRQP_TARGET_ARCH:-}
while [ $# -gt 0 ]; do
  case $1 in
    --target) [ $# -ge 2 ] || { echo "mrqp setup: --target needs a value" >&2; exit 2; }
              target=$2; shift 2 ;;
    --target=*) target=${1#--target=}; shift ;;
    -h | --help) usage; exit 0 ;;
    *) echo "mrqp setup: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
done

packages=(
  cmake g++ make ninja-build pkg-config
  libeigen3-dev liburdfdom-dev libccd-dev catch2 libbenchmark-dev
  libyaml-cpp-dev libcli11-dev
  gnuplot-nox
  can-utils stress-ng
  clang libclang-rt-14-dev   # the fuzz build (tests/fuzz): libFuzzer, ASan and UBSan runtimes
  libmujoco-dev libegl-dev libegl-mesa0 libgl-dev libpng-dev ffmpeg
)
if [ "${MRQP_EXTRA_PACKAGES:-}" != "" ]; then
  # shellcheck disable=SC2206
  packages+=(${MRQP_EXTRA_PACKAGES})
fi

# Target (arm64) packages, installed through Debian multiarch. None is needed today: Eigen and
# Catch2 are header-only and their host packages (libeigen3-dev is Architecture: all, catch2 is
# Multi-Arch: foreign) serve the cross build as they are. Libraries the runtime links (libccd, ...)
# go here, or into MRQP_EXTRA_ARM64_PACKAGES, as they come in.
arm64_packages=()
case $target in
  "" | host | native) target="" ;;
  aarch64 | arm64)
    packages+=(g++-aarch64-linux-gnu)
    # qemu-aarch64 (user-mode emulation) from qemu-user, unless a static one is already there.
    if ! command -v qemu-aarch64 > /dev/null && ! command -v qemu-aarch64-static > /dev/null; then
      packages+=(qemu-user)
    fi
    if [ "${MRQP_EXTRA_ARM64_PACKAGES:-}" != "" ]; then
      # shellcheck disable=SC2206
      arm64_packages+=(${MRQP_EXTRA_ARM64_PACKAGES})
    fi
    if [ ${#arm64_packages[@]} -gt 0 ]; then
      # The CMake files of arm64 -dev packages may name the arm64 C library's own files (libccd's
      # name /usr/lib/aarch64-linux-gnu/libm.so), which the cross toolchain keeps elsewhere.
      arm64_packages=(libc6-dev "${arm64_packages[@]}")
    fi
    ;;
  *) echo "mrqp setup: unknown target '$target' (known: aarch64)" >&2; exit 2 ;;
esac

installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'install ok installed'; }

missing=()
for p in "${packages[@]}"; do
  installed "$p" || missing+=("$p")
done
need_arch=0
if [ ${#arm64_packages[@]} -gt 0 ]; then
  dpkg --print-foreign-architectures | grep -qx arm64 || need_arch=1
  for p in "${arm64_packages[@]}"; do
    installed "$p:arm64" || missing+=("$p:arm64")
  done
fi
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "mrqp setup: installing ${missing[*]}" >&2
if [ "$(id -u)" -ne 0 ]; then
  echo "mrqp setup: missing packages (${missing[*]}); run as root or install them with apt-get" >&2
  [ $need_arch -eq 0 ] || echo "mrqp setup: (the :arm64 ones after: dpkg --add-architecture arm64; apt-get update)" >&2
  exit 1
fi
if [ $need_arch -eq 1 ]; then
  echo "mrqp setup: dpkg --add-architecture arm64 (multiarch, for the target's libraries)" >&2
  dpkg --add-architecture arm64
fi
export DEBIAN_FRONTEND=noninteractive
# Wait for a dpkg lock held by another apt run instead of failing at once.
apt_opts=(-o DPkg::Lock::Timeout=600)
apt-get "${apt_opts[@]}" update -qq
apt-get "${apt_opts[@]}" install -y --no-install-recommends "${missing[@]}"
