#!/usr/bin/env bash
# Instructions per control cycle (update() + solve()) of the bench_controller scenes, counted by
# valgrind's callgrind (docs/BENCHMARKS.md, "Controller cycle"). For every scene, one run of
# `bench_controller --no-timing --scene S --cycles 1` and one with K + 1 cycles, counting only
# inside MultiRobotProblem::update() and ::solve() (--toggle-collect: the scene loading and the
# integration of the plant are not counted). The first run gives cycle 0 (the first update and
# the cold solve); (Ir(K + 1) − Ir(1)) / K is the mean of cycles 1..K of the closed loop, warm
# started. The update/solve split is the inclusive count of each function (callgrind_annotate).
# Counts are deterministic for a given binary: the load of the machine does not change them.
#
#   tools/bench_controller/callgrind_cycles.sh [BINARY] [K] [SCENE...]
#     BINARY  bench_controller (default build/release/tools/bench_controller/bench_controller)
#     K       cycles after the first (default 1000)
#     SCENE   scene names (default panda_reach jvrc1_standing comanipulation)
# Prints a Markdown table. Needs valgrind (Debian package valgrind).
set -euo pipefail
bin=${1:-build/release/tools/bench_controller/bench_controller}
k=${2:-1000}
shift $(( $# < 2 ? $# : 2 ))
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(panda_reach jvrc1_standing comanipulation)
command -v valgrind > /dev/null || { echo "callgrind_cycles.sh: valgrind not found (apt-get install valgrind)" >&2; exit 1; }
command -v callgrind_annotate > /dev/null || { echo "callgrind_cycles.sh: callgrind_annotate not found" >&2; exit 1; }
[ -x "$bin" ] || { echo "callgrind_cycles.sh: no program $bin (build target bench_controller)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# run SCENE CYCLES: one callgrind run; prints "total update solve" (Ir).
run() {
  local out=$work/cg.out
  valgrind --tool=callgrind --callgrind-out-file="$out" \
    --toggle-collect='*MultiRobotProblem::update*' --toggle-collect='*MultiRobotProblem::solve*' \
    "$bin" --no-timing --scene "$1" --cycles "$2" > "$work/stdout" 2> "$work/stderr" \
    || { cat "$work/stdout" "$work/stderr" >&2; exit 1; }
  local total update solve
  total=$(awk '/^(summary|totals):/ { print $2; exit }' "$out")
  # Inclusive counts; the figures are printed with thousands separators.
  callgrind_annotate --inclusive=yes --threshold=100 "$out" > "$work/annotate" 2> /dev/null
  update=$(awk '/MultiRobotProblem::update\(\)/ { gsub(",", "", $1); print $1; exit }' "$work/annotate")
  solve=$(awk '/MultiRobotProblem::solve\(\)/ { gsub(",", "", $1); print $1; exit }' "$work/annotate")
  echo "$total ${update:-0} ${solve:-0}"
}

echo "| scene | n | eq | ineq | cycle 0 (Ir) | mean of cycles 1..$k (Ir) | of which update | of which solve |"
echo "|---|--:|--:|--:|--:|--:|--:|--:|"
for s in "${scenes[@]}"; do
  read -r t1 u1 s1 < <(run "$s" 1)
  read -r tk uk sk < <(run "$s" $((k + 1)))
  # "NAME: C cycles, n N, me E, mi I, ..."
  sizes=$(sed -n 's/.* n \([^,]*\), me \([^,]*\), mi \([^,]*\),.*/\1 | \2 | \3/p' "$work/stdout")
  grep -q FAILED "$work/stdout" && { echo "callgrind_cycles.sh: $s: a QP failed" >&2; cat "$work/stdout" >&2; exit 1; }
  printf '| %s | %s | %s | %s | %s | %s |\n' "$s" "$sizes" "$t1" \
    $(( (tk - t1 + k / 2) / k )) $(( (uk - u1 + k / 2) / k )) $(( (sk - s1 + k / 2) / k ))
done
