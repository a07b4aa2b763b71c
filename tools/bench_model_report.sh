#!/usr/bin/env bash
# Runs bench_model (generated model code against the slow reference) with 7 repetitions and
# prints a Markdown table of the medians: model, function, generated, reference, speed-up.
#
#   tools/bench_model_report.sh [BENCH_MODEL_BINARY] [extra Google Benchmark flags...]
#
# BENCH_MODEL_BINARY defaults to $BENCH_MODEL, else build/tools/bench_model. Extra flags go to
# bench_model as they are (e.g. --benchmark_filter='panda/' or --benchmark_min_time=0.1).
# Environment: MRQP_BENCH_TIME=cpu (default) or real selects the column of Google Benchmark's
# JSON that is reported; MRQP_BENCH_JSON=FILE keeps the raw JSON output in FILE.
# The benchmark's own context (CPU, load average) goes to stderr; the table to stdout.
set -euo pipefail

bin="${BENCH_MODEL:-build/tools/bench_model}"
if [ $# -gt 0 ] && [ -f "$1" ] && [ -x "$1" ]; then
  bin="$1"
  shift
fi
if [ ! -x "$bin" ]; then
  echo "bench_model_report.sh: no bench_model executable at '$bin'" \
    "(pass its path as the first argument)" >&2
  exit 2
fi
time_field="${MRQP_BENCH_TIME:-cpu}"
case "$time_field" in
  cpu | real) ;;
  *)
    echo "bench_model_report.sh: MRQP_BENCH_TIME must be cpu or real, not '$time_field'" >&2
    exit 2
    ;;
esac

json="${MRQP_BENCH_JSON:-}"
cleanup=""
if [ -z "$json" ]; then
  json="$(mktemp "${TMPDIR:-/tmp}/bench_model.XXXXXX.json")"
  cleanup="$json"
fi
trap '[ -n "$cleanup" ] && rm -f "$cleanup"' EXIT

"$bin" --benchmark_repetitions=7 --benchmark_report_aggregates_only=true \
  --benchmark_format=json "$@" >"$json"

python3 - "$json" "$time_field" <<'EOF'
import json
import sys

path, field = sys.argv[1], sys.argv[2] + "_time"
with open(path) as f:
    doc = json.load(f)

to_us = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}
medians = {}  # (model, function) -> {side: µs}, in order of appearance
for b in doc.get("benchmarks", []):
    if b.get("run_type") != "aggregate" or b.get("aggregate_name") != "median":
        continue
    parts = b["run_name"].split("/")
    if len(parts) != 3:
        continue
    model, function, side = parts
    medians.setdefault((model, function), {})[side] = b[field] * to_us[b.get("time_unit", "ns")]

def fmt(us):
    if us is None:
        return "—"
    if us < 10:
        return f"{us:.3f}"
    if us < 100:
        return f"{us:.2f}"
    if us < 1000:
        return f"{us:.1f}"
    return f"{us:.0f}"

ctx = doc.get("context", {})
load = "/".join(f"{x:.2f}" for x in ctx.get("load_avg", [])) or "?"
print(f"Google Benchmark, 7 repetitions, median {field.replace('_', ' ')} per call; "
      f"{ctx.get('num_cpus', '?')} CPUs at {ctx.get('mhz_per_cpu', '?')} MHz, "
      f"load average at start {load}, library built as {ctx.get('library_build_type', '?')}.")
print()
print("| model | function | generated median [µs] | reference median [µs] "
      "| speed-up (reference / generated) |")
print("|---|---|--:|--:|--:|")
for (model, function), sides in medians.items():
    g, r = sides.get("generated"), sides.get("reference")
    if g and r:
        ratio = f"{r / g:.0f}×" if r / g >= 100 else f"{r / g:.1f}×"
    else:
        ratio = "—"
    print(f"| {model} | {function} | {fmt(g)} | {fmt(r)} | {ratio} |")
EOF
