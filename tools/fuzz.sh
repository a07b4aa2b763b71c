#!/usr/bin/env bash
# A long libFuzzer run of one harness of tests/fuzz (docs/robustness.md, "Fuzzing").
#
# Usage: tools/fuzz.sh HARNESS MINUTES [CORPUS_DIR] [CRASH_DIR]
#   HARNESS     firmware_frame, candump_line, qp_text, scene_yaml, drive_emu_yaml, mesh or urdf
#   MINUTES     how long to fuzz
#   CORPUS_DIR  where the corpus grows (kept between runs; default build/fuzz/corpus/HARNESS);
#               the seeds (tests/data) and regression inputs (tests/data/fuzz/HARNESS) are read too
#   CRASH_DIR   where a crashing, leaking or timing-out input is saved (default build/fuzz/crashes/
#               HARNESS); copy it into tests/data/fuzz/HARNESS/ with the fix, so every later run
#               and the test suite replay it
# Environment: MRQP_FUZZ_BUILD (default build/fuzz, configured with the fuzz preset when missing),
#   MRQP_FUZZ_JOBS (parallel builds, default nproc).
# Prints libFuzzer's final statistics (stat::number_of_executed_units = executions) and exits
# non-zero when libFuzzer found something.
set -euo pipefail
usage() { sed -n '4,16s/^# \{0,1\}//p' "$0"; }
if [ $# -lt 2 ] || [ $# -gt 4 ]; then
  usage >&2
  exit 2
fi
cd "$(dirname "$0")/.."
root=$(pwd)
harness=$1 minutes=$2
case $minutes in '' | *[!0-9]*) echo "mrqp fuzz: MINUTES must be a whole number, got '$minutes'" >&2; exit 2 ;; esac
build=${MRQP_FUZZ_BUILD:-$root/build/fuzz}
corpus=${3:-$build/corpus/$harness}
crashes=${4:-$build/crashes/$harness}

if [ ! -f "$build/CMakeCache.txt" ]; then
  ./tools/setup-deps.sh
  cmake --preset fuzz -B "$build" > /dev/null
fi
cmake --build "$build" -j"${MRQP_FUZZ_JOBS:-$(nproc)}" --target "fuzz_$harness" > /dev/null \
  || { echo "mrqp fuzz: no harness '$harness' (tests/fuzz/CMakeLists.txt lists them)" >&2; exit 2; }
seeds=$build/tests/fuzz/$harness.seeds
mkdir -p "$corpus" "$crashes"

dirs=() files=()
while IFS= read -r line; do
  if [ -d "$line" ]; then dirs+=("$line"); elif [ -f "$line" ]; then files+=("$line"); fi
done < "$seeds"
seed_inputs=()
if [ ${#files[@]} -gt 0 ]; then
  seed_inputs=("-seed_inputs=$(IFS=,; echo "${files[*]}")")
fi
# as the fuzz test preset (CMakePresets.json)
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/tests/lsan.supp}
echo "mrqp fuzz: $harness for $minutes min, corpus $corpus, crashes into $crashes" >&2
# The limits of the short runs (tests/fuzz/run_fuzzer.sh): 2 GB, 10 s per input.
exec "$build/tests/fuzz/fuzz_$harness" -max_total_time=$((minutes * 60)) -rss_limit_mb=2048 \
  -malloc_limit_mb=2048 -timeout=10 -artifact_prefix="$crashes/" -print_final_stats=1 \
  "${seed_inputs[@]}" "$corpus" "${dirs[@]}"
