#!/usr/bin/env bash
# Instructions per call of the generated model functions (docs/BENCHMARKS.md), counted by
# valgrind's callgrind: for every model and function, one run of mrqp-model-cost with N + 1 calls
# and one with 1 call, counting only inside its measuredCalls() (--toggle-collect);
# (Ir(N + 1) - Ir(1)) / N is the cost of one call, the loop's own few instructions included, and
# the one-time costs of a first call (the dynamic linker binding libm's sin/cos) excluded. Counts are deterministic: the
# same binary gives the same figures on any machine (with the same valgrind), whatever the load.
#
#   tools/model_cost/callgrind_table.sh [BINARY] [N]
#     BINARY  mrqp-model-cost (default build/release/tools/model_cost/mrqp-model-cost)
#     N       calls per run (default 1000)
# Prints a Markdown table. Needs valgrind (Debian package valgrind).
set -euo pipefail
bin=${1:-build/release/tools/model_cost/mrqp-model-cost}
n=${2:-1000}
command -v valgrind > /dev/null || { echo "callgrind_table.sh: valgrind not found (apt-get install valgrind)" >&2; exit 1; }
[ -x "$bin" ] || { echo "callgrind_table.sh: no program $bin (build target mrqp-model-cost)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Total instructions (Ir) of one run under callgrind.
count() {
  local out=$work/cg.out
  valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect='*measuredCalls*' \
    "$bin" "$@" > "$work/stdout" 2> "$work/stderr" \
    || { cat "$work/stderr" >&2; exit 1; }
  awk '/^(summary|totals):/ { print $2; exit }' "$out"
}

echo "| model | nv | function | instructions per call (Ir) |"
echo "|---|--:|---|--:|"
for model in panda jvrc1; do
  for fn in fk jacobians crba rnea nle; do
    base=$(count "$model" "$fn" 1)
    total=$(count "$model" "$fn" $((n + 1)))
    nv=$(awk '{ print $4 }' "$work/stdout")
    per=$(( (total - base + n / 2) / n ))
    printf '| %s | %s | %s | %s |\n' "$model" "$nv" "$fn" "$per"
  done
done
