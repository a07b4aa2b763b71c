#!/usr/bin/env bash
# Installs a built mrqp tree into a scratch prefix and builds a user project that generates code
# for panda.urdf with mrqp_generate_model() and runs a few cycles of tools/scenes/panda_reach.yaml
# with it through the installed controller.  Usage: check_install.sh <build dir>
set -euo pipefail
build=$1
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > /dev/null
# The built-in models' collision geometry comes with the collision library (docs/collision.md).
if [ -n "$(find "$work/prefix" -name libmrqp_collision.a -print -quit)" ]; then
  for f in panda.yaml panda.srdf jvrc1.yaml; do test -f "$work/prefix/share/mrqp/collision/$f"; done
fi
cmake -S "$here/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DPANDA_URDF="$here/../../control/model/urdf/panda.urdf" > /dev/null
cmake --build "$work/consumer" -j"$(nproc)" > /dev/null
out=$("$work/consumer/consumer" "$here/../../tools/scenes/panda_reach.yaml")
echo "$out"
grep -q '^panda nq 8 nv 8' <<<"$out"
grep -q '^scene .*panda_reach.yaml: 20 cycles solved' <<<"$out"
