#!/usr/bin/env bash
# The controller loop's real-time benchmark (docs/BENCHMARKS.md, "Controller loop in real time"):
# mrqp-run on a scene for N cycles paced at its period (1 kHz for the shipped scenes), once paced
# only (--paced) and once with the real-time set-up (--realtime: mlockall, pre-faulted memory,
# SCHED_FIFO, the loop pinned to the last CPU), each time with the other CPU loaded by stress-ng
# (one CPU worker pinned to CPU 0). Prints what mrqp-run said about its real-time set-up and a
# Markdown table of the cycle-time distribution and the deadline misses from each summary.json.
#
# Usage: tools/run/bench_realtime.sh [--build DIR] [--out DIR] [--cycles N] [--scene FILE]
#        defaults: build/release, build/bench_realtime, 100000, tools/scenes/comanipulation.yaml
# Needs stress-ng (tools/setup-deps.sh) and jq. Do not run it under nice: the run is the measurement.
set -euo pipefail

here=$(cd "$(dirname "$0")/../.." && pwd)
build=$here/build/release
out=$here/build/bench_realtime
cycles=100000
scene=$here/tools/scenes/comanipulation.yaml
while [ $# -gt 0 ]; do
  case $1 in
    --build) build=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --cycles) cycles=$2; shift 2 ;;
    --scene) scene=$2; shift 2 ;;
    -h | --help) sed -n '2,11s/^# \{0,1\}//p' "$0"; exit 0 ;;
    *) echo "bench_realtime: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
run=$build/tools/run/mrqp-run
[ -x "$run" ] || { echo "bench_realtime: $run not built (cmake --build $build --target mrqp-run)" >&2; exit 1; }
command -v stress-ng > /dev/null || { echo "bench_realtime: stress-ng missing (tools/setup-deps.sh)" >&2; exit 1; }
command -v jq > /dev/null || { echo "bench_realtime: jq missing" >&2; exit 1; }
mkdir -p "$out"

stress_pid=
stop_stress() { if [ -n "$stress_pid" ]; then kill "$stress_pid" 2> /dev/null || true; wait "$stress_pid" 2> /dev/null || true; stress_pid=; fi; }
trap stop_stress EXIT

one_run() {  # one_run NAME OPTION
  local name=$1 option=$2
  stress-ng --cpu 1 --taskset 0 --timeout 0 --quiet &
  stress_pid=$!
  sleep 1
  echo "== $name: mrqp-run $(basename "$scene") --plant ideal --cycles $cycles $option (stress-ng --cpu 1 --taskset 0)"
  "$run" "$scene" --out "$out/$name" --plant ideal --cycles "$cycles" --no-plots $option \
    > "$out/$name.stdout" 2> "$out/$name.stderr" || echo "   (exit status $?)"
  grep -E 'realtime:|deadline|safe' "$out/$name.stdout" | sed 's/^/   /' || true
  stop_stress
}

one_run paced --paced
one_run realtime --realtime

echo
echo "| run | cycles | median µs | p99 µs | p99.9 µs | max µs | deadline misses | allocations in loop | safe stop |"
echo "|---|---|---|---|---|---|---|---|---|"
for name in paced realtime; do
  jq -r --arg n "$name" '"| \($n) | \(.cycles) | \(.cycle_time_us.median) | \(.cycle_time_us.p99) | \(.cycle_time_us.p999) | \(.cycle_time_us.max) | \(.deadline_misses) | \(.allocations_in_loop) | \(.safe_stop // "none") |"' \
    "$out/$name/summary.json"
done
