#!/usr/bin/env bash
# Installs the Debian 12 packages mrqp needs to build, test and run its scenario.
# Idempotent: when every package is present it returns at once without touching apt.
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  libeigen3-dev liburdfdom-dev libccd-dev catch2 libbenchmark-dev
  libyaml-cpp-dev libcli11-dev
  gnuplot-nox
  can-utils
)
if [ "${MRQP_EXTRA_PACKAGES:-}" != "" ]; then
  # shellcheck disable=SC2206
  packages+=(${MRQP_EXTRA_PACKAGES})
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "mrqp setup: installing ${missing[*]}" >&2
if [ "$(id -u)" -ne 0 ]; then
  echo "mrqp setup: missing packages (${missing[*]}); run as root or install them with apt-get" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y --no-install-recommends "${missing[@]}"
