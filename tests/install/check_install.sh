#!/usr/bin/env bash
# Installs a built mrqp tree into a scratch prefix and builds a user project that generates code
# for panda.urdf with mrqp_generate_model() and runs it.  Usage: check_install.sh <build dir>
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > /dev/null
cmake -S "$here/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DPANDA_URDF="$here/../data/models/panda.urdf" > /dev/null
cmake --build "$work/consumer" -j"$(nproc)" > /dev/null
out=$("$work/consumer/consumer")
echo "$out"
grep -q '^panda nq 8 nv 8' <<<"$out"
